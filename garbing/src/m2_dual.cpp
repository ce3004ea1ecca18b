// Step 3, the starting mesh: the dual of M1 (or M1 itself), triangulated.
#include "m2.h"

#include "garbing/detail/polygon_triangulation.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <utility>

namespace mg::garbing::refine {
namespace {

/// Triangulates a dual face by least total diagonal length (detail::min_diagonal_triangulation:
/// keeps the triangles of non-planar faces well shaped). A diagonal that is already an edge
/// of the mesh, or a diagonal of an earlier polygon (two dual faces can share more than one
/// vertex pair), is forbidden: it would be shared by more than two faces. A chord of another
/// polygon too (`shared`, where M1 is pinched) is avoided when the polygon has a
/// triangulation without it: around a pinched M1 edge the dual of one end can be a flat quad
/// whose two chords cross, and the other end's polygon taking either one would cut through
/// it in the fold-free starting mesh. When no triangulation avoids the forbidden ones, the
/// polygon is fanned from a new vertex at its centroid, moved onto G.
void triangulate_polygon(const std::vector<int>& poly, detail::EdgeSet& edges,
                         const detail::EdgeSet& shared, const Context& ctx, Vertices& m2,
                         RefineStats& stats, Triangles& out) {
  if (detail::min_diagonal_triangulation(poly, m2.position, edges, out, &shared)) return;
  if (detail::min_diagonal_triangulation(poly, m2.position, edges, out)) return;
  const int n = static_cast<int>(poly.size());
  Vec3 centroid = Vec3::Zero();
  for (int v : poly) centroid += m2.position[v];
  centroid /= n;
  const int c = static_cast<int>(m2.position.size());
  m2.start.push_back(centroid);
  m2.position.push_back(ctx.g.closest_point(centroid));
  m2.locale.emplace_back();
  ++stats.centroid_fans;
  for (int i = 0; i < n; ++i) out.push_back({poly[i], poly[(i + 1) % n], c});
}

}  // namespace

Polygons start_from_dual(const CoarseMesh& m1, const Context& ctx, Vertices& m2,
                         RefineStats& stats) {
  // Vertices: the centres of M1's squares; P from the owning leaf.
  const std::size_t n = m1.faces.size();
  m2.start.resize(n);
  m2.locale.resize(n);
  std::vector<int> owners;
  for (std::size_t f = 0; f < n; ++f) {
    const CoarseFace& face = m1.faces[f];
    const double side = ctx.tree.side(face.level);
    for (int a = 0; a < 3; ++a)
      m2.start[f][a] = (static_cast<double>(face.corner[a]) + (a == face.axis ? 0.0 : 0.5)) * side;
    owners.push_back(face.owner);
  }
  std::sort(owners.begin(), owners.end());
  owners.erase(std::unique(owners.begin(), owners.end()), owners.end());
  std::vector<Locale> per_owner(owners.size());
  tbb::parallel_for(std::size_t(0), owners.size(),
                    [&](std::size_t i) { per_owner[i] = leaf_locale(ctx, owners[i]); });
  for (std::size_t f = 0; f < n; ++f) {
    const auto it = std::lower_bound(owners.begin(), owners.end(), m1.faces[f].owner);
    m2.locale[f] = per_owner[it - owners.begin()];
  }
  // Faces: one per M1 vertex, the M1 faces around it in counter-clockwise order.
  Polygons polygons;
  const Mesh& mesh = m1.mesh;
  for (const auto v : mesh.vertices()) {
    std::vector<int> loop;
    for (const auto f : mesh.vf_ccw_range(v)) loop.push_back(f.idx());
    if (loop.size() < 3) {
      ++stats.collapsed_digons;  // a pinch midpoint: its two faces share an edge instead
      continue;
    }
    // Counter-clockwise around the vertex seen from outside: the dual face points outward.
    polygons.push_back(std::move(loop));
  }
  return polygons;
}

Polygons start_from_m1(const CoarseMesh& m1, const Context& ctx, Vertices& m2) {
  const Mesh& mesh = m1.mesh;
  m2.start.resize(mesh.n_vertices());
  m2.locale.resize(mesh.n_vertices());
  for (const auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    m2.start[v.idx()] = ctx.tree.to_local(Vec3(p[0], p[1], p[2]));
  }
  tbb::parallel_for(std::size_t(0), m2.start.size(),
                    [&](std::size_t i) { m2.locale[i] = point_locale(ctx, m2.start[i]); });
  Polygons polygons;
  for (const auto f : mesh.faces()) {
    std::vector<int> loop;
    for (const auto v : mesh.fv_range(f)) loop.push_back(v.idx());
    polygons.push_back(std::move(loop));
  }
  return polygons;
}

Triangles triangulate(const Polygons& polygons, const Context& ctx, Vertices& m2,
                      RefineStats& stats) {
  // Every edge of the mesh so far: the polygons' edges, then each chosen diagonal.
  detail::EdgeSet edges(m2.position.size());
  for (const auto& poly : polygons)
    for (std::size_t i = 0; i < poly.size(); ++i)
      edges.insert(poly[i], poly[(i + 1) % poly.size()]);
  // The chords (non-adjacent vertex pairs) that more than one polygon holds.
  std::vector<std::pair<int, int>> chords;
  for (const auto& poly : polygons) {
    const std::size_t n = poly.size();
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 2; j < n; ++j)
        if (i > 0 || j + 1 < n) chords.push_back(std::minmax(poly[i], poly[j]));
  }
  std::sort(chords.begin(), chords.end());
  detail::EdgeSet shared(m2.position.size());
  for (std::size_t k = 1; k < chords.size(); ++k)
    if (chords[k] == chords[k - 1]) shared.insert(chords[k].first, chords[k].second);
  Triangles triangles;
  for (const auto& poly : polygons)
    triangulate_polygon(poly, edges, shared, ctx, m2, stats, triangles);
  return triangles;
}

}  // namespace mg::garbing::refine
