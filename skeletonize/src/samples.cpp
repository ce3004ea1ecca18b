#include "samples.h"

#include "core/errors.h"
#include "core/mesh_topology.h"
#include "core/random.h"

#include <algorithm>
#include <array>

namespace mg::skeletonize::detail {
namespace {

using Vec3 = Eigen::Vector3d;

/// Draw k of the random samples' stream: depends only on (seed, k).
double uniform(std::uint64_t seed, std::uint64_t k) {
  return unit_interval(mix64(seed * kSplitmixIncrement + k + 0x632be59bd9b4e019ULL));
}

}  // namespace

void check_closed_mesh(const PolygonSoup& mesh, const std::string& name) {
  if (mesh.faces.empty()) throw InvalidInput(name + ": empty mesh (no faces)");
  validate_soup(mesh, name);
  const MeshTopology t = mesh_topology(mesh);
  if (!t.manifold) throw InvalidInput(name + ": non-manifold mesh: " + t.first_problem);
  if (!t.closed)
    throw InvalidInput(name + ": open mesh (" + std::to_string(t.boundary_edges) +
                       " boundary edges): poles need a closed surface");
  if (!t.oriented) throw InvalidInput(name + ": " + t.first_problem);
}

std::vector<Vec3> make_samples(const PolygonSoup& mesh, const SkeletonOptions& opt) {
  std::vector<Vec3> samples;
  std::vector<char> used(mesh.points.size(), 0);
  for (const auto& f : mesh.faces)
    for (int v : f) used[v] = 1;
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
    if (used[i]) samples.push_back(mesh.points[i]);
  if (opt.edge_midpoints) {
    std::vector<std::pair<int, int>> edges;
    for (const auto& f : mesh.faces)
      for (std::size_t i = 0; i < f.size(); ++i)
        edges.push_back(std::minmax(f[i], f[(i + 1) % f.size()]));
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    for (const auto& [a, b] : edges) samples.push_back((mesh.points[a] + mesh.points[b]) / 2);
  }
  if (opt.random_samples > 0) {
    const std::vector<std::array<int, 3>> tris = fan_triangles(mesh).corners;
    std::vector<double> cumulative;
    double total = 0;
    for (const auto& t : tris) {
      total += (mesh.points[t[1]] - mesh.points[t[0]])
                   .cross(mesh.points[t[2]] - mesh.points[t[0]])
                   .norm() /
               2;
      cumulative.push_back(total);
    }
    for (std::size_t k = 0; k < opt.random_samples; ++k) {
      const double pick = uniform(opt.seed, 3 * k) * total;
      const std::size_t t = std::min<std::size_t>(
          std::upper_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin(),
          tris.size() - 1);
      double u = uniform(opt.seed, 3 * k + 1), v = uniform(opt.seed, 3 * k + 2);
      if (u + v > 1) {
        u = 1 - u;
        v = 1 - v;
      }
      const Vec3& a = mesh.points[tris[t][0]];
      samples.push_back(a + u * (mesh.points[tris[t][1]] - a) + v * (mesh.points[tris[t][2]] - a));
    }
  }
  return samples;
}

}  // namespace mg::skeletonize::detail
