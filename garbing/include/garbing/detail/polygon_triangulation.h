#pragma once
/// \file detail/polygon_triangulation.h
/// Internal: M2's triangulation of its dual faces (refine_mesh.cpp), kept apart so that its
/// rule against repeated edges can be tested on hand-made polygons.

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <vector>

namespace mg::garbing::detail {

/// A set of undirected edges between vertices 0 .. n - 1: each vertex's higher neighbours in
/// insertion order (a handful per vertex on a surface mesh, so a scan beats a tree).
class EdgeSet {
 public:
  explicit EdgeSet(std::size_t n) : higher_(n) {}
  bool contains(int a, int b) const {
    if (a > b) std::swap(a, b);
    const auto& h = higher_[a];
    return std::find(h.begin(), h.end(), b) != h.end();
  }
  void insert(int a, int b) {
    if (a > b) std::swap(a, b);
    if (!contains(a, b)) higher_[a].push_back(b);
  }

 private:
  std::vector<std::vector<int>> higher_;
};

/// Triangulates the polygon `poly` (vertex ids into `position`, in order) so that the total
/// length of its diagonals is least (dynamic programming over the polygon's chords). A
/// diagonal already in `edges` is forbidden: it would be shared by more than two triangles.
/// On success appends the n - 2 triangles to `out`, adds the chosen diagonals to `edges` and
/// returns true; when every triangulation needs a forbidden diagonal, changes nothing and
/// returns false. Ties go to the lowest split vertex, so the result is deterministic. A chord
/// in `avoid` (when given) is forbidden too.
/// @pre poly.size() >= 3; the polygon's own edges are in `edges` (not needed for a triangle)
inline bool min_diagonal_triangulation(const std::vector<int>& poly,
                                       const std::vector<Eigen::Vector3d>& position, EdgeSet& edges,
                                       std::vector<std::array<int, 3>>& out,
                                       const EdgeSet* avoid = nullptr) {
  const int n = static_cast<int>(poly.size());
  if (n == 3) {
    out.push_back({poly[0], poly[1], poly[2]});
    return true;
  }
  // The chords' lengths, infinite where forbidden, looked up once per pair.
  std::vector<double> length(n * n, 0.0);
  for (int i = 0; i < n; ++i)
    for (int j = i + 2; j < n; ++j)
      length[i * n + j] = edges.contains(poly[i], poly[j]) ||
                                  (avoid != nullptr && avoid->contains(poly[i], poly[j]))
                              ? INFINITY
                              : (position[poly[i]] - position[poly[j]]).norm();
  std::vector<double> cost(n * n, 0.0);
  std::vector<int> split(n * n, -1);
  for (int gap = 2; gap < n; ++gap)
    for (int i = 0; i + gap < n; ++i) {
      const int j = i + gap;
      double best = INFINITY;
      for (int k = i + 1; k < j; ++k) {
        double c = cost[i * n + k] + cost[k * n + j];
        if (k > i + 1) c += length[i * n + k];
        if (j > k + 1) c += length[k * n + j];
        if (c < best) {
          best = c;
          split[i * n + j] = k;
        }
      }
      cost[i * n + j] = best;
    }
  if (!std::isfinite(cost[n - 1])) return false;
  // Unroll the split table.
  std::vector<std::pair<int, int>> stack = {{0, n - 1}};
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    if (j - i < 2) continue;
    const int k = split[i * n + j];
    out.push_back({poly[i], poly[k], poly[j]});
    for (const auto& [a, b] : {std::make_pair(i, k), std::make_pair(k, j)})
      if (b > a + 1) edges.insert(poly[a], poly[b]);
    stack.push_back({i, k});
    stack.push_back({k, j});
  }
  return true;
}

}  // namespace mg::garbing::detail
