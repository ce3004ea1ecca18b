#include "core/mesh_topology.h"

#include "core/union_find.h"

#include <algorithm>
#include <numeric>

namespace mg {
namespace {

/// One directed use of an undirected edge by a face.
struct EdgeUse {
  int lo, hi;    // vertex indices, lo < hi
  bool forward;  // the face runs lo -> hi
  std::size_t face;
  std::size_t corner_lo, corner_hi;  // global corner ids of lo and hi in that face
  bool operator<(const EdgeUse& o) const {
    return std::tie(lo, hi, face) < std::tie(o.lo, o.hi, o.face);
  }
};

std::string edge_name(int a, int b) {
  return "edge (" + std::to_string(a) + ", " + std::to_string(b) + ")";
}

}  // namespace

MeshTopology mesh_topology(const PolygonSoup& soup) {
  MeshTopology t;
  t.faces = soup.faces.size();
  const std::size_t n_points = soup.points.size();

  std::vector<std::size_t> first_corner(soup.faces.size() + 1, 0);
  for (std::size_t f = 0; f < soup.faces.size(); ++f)
    first_corner[f + 1] = first_corner[f] + soup.faces[f].size();
  const std::size_t n_corners = first_corner.back();

  std::vector<EdgeUse> uses;
  uses.reserve(n_corners);
  std::vector<char> used(n_points, 0);
  UnionFind vertex_sets(n_points);
  for (std::size_t f = 0; f < soup.faces.size(); ++f) {
    const auto& face = soup.faces[f];
    const std::size_t k = face.size();
    for (std::size_t i = 0; i < k; ++i) {
      const int a = face[i], b = face[(i + 1) % k];
      used[a] = 1;
      vertex_sets.unite(a, b);
      const std::size_t ca = first_corner[f] + i, cb = first_corner[f] + (i + 1) % k;
      if (a < b)
        uses.push_back({a, b, true, f, ca, cb});
      else
        uses.push_back({b, a, false, f, cb, ca});
    }
  }
  std::sort(uses.begin(), uses.end());

  // Corners of one vertex joined across each manifold edge: one class per fan.
  UnionFind fans(n_corners);
  auto note = [&t](const std::string& problem) {
    if (t.first_problem.empty()) t.first_problem = problem;
  };
  for (std::size_t i = 0; i < uses.size();) {
    std::size_t j = i;
    while (j < uses.size() && uses[j].lo == uses[i].lo && uses[j].hi == uses[i].hi) ++j;
    const std::size_t count = j - i;
    ++t.edges;
    if (count == 1) {
      ++t.boundary_edges;
    } else if (count == 2) {
      if (uses[i].forward == uses[i + 1].forward) {
        ++t.misoriented_edges;
        note("faces " + std::to_string(uses[i].face) + " and " + std::to_string(uses[i + 1].face) +
             " run along " + edge_name(uses[i].lo, uses[i].hi) +
             " in the same direction (inconsistent orientation)");
      }
      fans.unite(uses[i].corner_lo, uses[i + 1].corner_lo);
      fans.unite(uses[i].corner_hi, uses[i + 1].corner_hi);
    } else {
      ++t.nonmanifold_edges;
      note(edge_name(uses[i].lo, uses[i].hi) + " is shared by " + std::to_string(count) + " faces");
    }
    i = j;
  }

  // A vertex is manifold when all its corners fall in one fan.
  std::vector<std::size_t> fan_of(n_points, SIZE_MAX);
  std::vector<char> reported(n_points, 0);
  for (std::size_t f = 0; f < soup.faces.size(); ++f) {
    for (std::size_t i = 0; i < soup.faces[f].size(); ++i) {
      const int v = soup.faces[f][i];
      const std::size_t root = fans.find(first_corner[f] + i);
      if (fan_of[v] == SIZE_MAX) {
        fan_of[v] = root;
      } else if (fan_of[v] != root && !reported[v]) {
        reported[v] = 1;
        ++t.nonmanifold_vertices;
        note("vertex " + std::to_string(v) + " is non-manifold (its faces form separate fans)");
      }
    }
  }

  for (std::size_t v = 0; v < n_points; ++v) {
    if (!used[v]) continue;
    ++t.vertices;
    if (vertex_sets.find(v) == v) ++t.components;
  }
  t.euler = static_cast<long>(t.vertices) - static_cast<long>(t.edges) + static_cast<long>(t.faces);
  t.closed = t.boundary_edges == 0 && t.faces > 0;
  t.manifold = t.nonmanifold_edges == 0 && t.nonmanifold_vertices == 0;
  t.oriented = t.manifold && t.misoriented_edges == 0;
  if (t.closed && t.oriented)
    t.genus = static_cast<int>((2 * static_cast<long>(t.components) - t.euler) / 2);
  return t;
}

}  // namespace mg
