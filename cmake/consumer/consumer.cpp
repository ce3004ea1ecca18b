// Built against the installed package: garbs one ball (the paper's Sphere row: M2 has 1344
// vertices and 2684 faces) and reads its union's topology; prints them and exits 0 only when
// they are the expected ones.
#include "core/medial_surface.h"
#include "garbing/garb.h"
#include "skeletonize/union_topology.h"

#include <cstdio>

int main() {
  mg::MedialSurface ball;
  ball.atoms.push_back({Eigen::Vector3d(0.5, -1, 2), 1.5});
  const mg::garbing::Garbing g = mg::garbing::garb(ball);
  const auto vertices = g.m2.mesh.n_vertices(), faces = g.m2.mesh.n_faces();
  const mg::skeletonize::UnionTopology u = mg::skeletonize::union_topology(ball);
  std::printf("M2: %zu vertices, %zu faces; union: %zu component(s), Euler characteristic %ld\n",
              static_cast<std::size_t>(vertices), static_cast<std::size_t>(faces), u.components,
              u.euler);
  return vertices == 1344 && faces == 2684 && u.components == 1 && u.euler == 2 ? 0 : 1;
}
