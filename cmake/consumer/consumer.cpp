// Built against the installed package (no C++ standard set here: the targets carry C++17):
// garbs one ball (the paper's Sphere row: M2 has 1344 vertices and 2684 faces), checks M2
// (closed, no intersecting triangle) and reads the union's topology; prints them and exits 0
// only when they are the expected ones.
#include "core/medial_surface.h"
#include "evaluate/mesh_checks.h"
#include "garbing/garb.h"
#include "skeletonize/union_topology.h"

#include <cstdio>

int main() {
  mg::MedialSurface ball;
  ball.atoms.push_back({Eigen::Vector3d(0.5, -1, 2), 1.5});
  const mg::garbing::Garbing g = mg::garbing::garb(ball);
  const auto vertices = g.m2.mesh.n_vertices(), faces = g.m2.mesh.n_faces();
  const mg::evaluate::MeshCheck c = mg::evaluate::check_mesh(mg::soup_from_mesh(g.m2.mesh));
  const mg::skeletonize::UnionTopology u = mg::skeletonize::union_topology(ball);
  std::printf(
      "M2: %zu vertices, %zu faces, closed %d, %zu intersecting pairs; union: %zu component(s), "
      "Euler characteristic %ld\n",
      static_cast<std::size_t>(vertices), static_cast<std::size_t>(faces),
      static_cast<int>(c.topology.closed), c.intersecting_pairs, u.components, u.euler);
  const bool sound = c.topology.closed && c.intersecting_pairs == 0;
  return vertices == 1344 && faces == 2684 && sound && u.components == 1 && u.euler == 2 ? 0 : 1;
}
