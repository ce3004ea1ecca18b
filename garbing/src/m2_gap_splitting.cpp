// Step 3, gap splitting: an edge bridging a notch of G narrower than a leaf gets a vertex on G.
#include "m2.h"

#include "core/detail/box_grid.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <stdexcept>

namespace mg::garbing::refine {
namespace {

/// The triangles split by the edges with a vertex (mid[edge] >= 0): one split edge, 1-to-2
/// through the opposite corner; two, the corner triangle and the rest by its shorter diagonal;
/// three, 1-to-4.
Triangles split_triangles(const Triangles& triangles,
                          const std::vector<std::array<std::size_t, 3>>& sides,
                          const std::vector<int>& mid, const std::vector<Vec3>& points) {
  std::vector<std::array<int, 3>> out;
  out.reserve(triangles.size() + triangles.size() / 8);
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const auto& t = triangles[f];
    const std::array<int, 3> m = {mid[sides[f][0]], mid[sides[f][1]], mid[sides[f][2]]};
    const int split = (m[0] >= 0) + (m[1] >= 0) + (m[2] >= 0);
    if (split == 0) {
      out.push_back(t);
    } else if (split == 3) {
      out.push_back({t[0], m[0], m[2]});
      out.push_back({m[0], t[1], m[1]});
      out.push_back({m[2], m[1], t[2]});
      out.push_back({m[0], m[1], m[2]});
    } else if (split == 1) {
      const int k = m[0] >= 0 ? 0 : (m[1] >= 0 ? 1 : 2);  // the edge t[k] t[k+1]
      const int a = t[k], b = t[(k + 1) % 3], c = t[(k + 2) % 3];
      out.push_back({a, m[k], c});
      out.push_back({m[k], b, c});
    } else {
      const int k = m[0] < 0 ? 0 : (m[1] < 0 ? 1 : 2);  // the edge kept: t[k] t[k+1]
      const int a = t[k], b = t[(k + 1) % 3], c = t[(k + 2) % 3];
      const int mb = m[(k + 1) % 3], mc = m[(k + 2) % 3];  // on b-c and on c-a
      out.push_back({mb, c, mc});                          // the corner at c
      // The quad a, b, mb, mc by its shorter diagonal.
      if ((points[a] - points[mb]).squaredNorm() <= (points[b] - points[mc]).squaredNorm()) {
        out.push_back({a, b, mb});
        out.push_back({a, mb, mc});
      } else {
        out.push_back({a, b, mc});
        out.push_back({b, mb, mc});
      }
    }
  }
  return out;
}

}  // namespace

/// One round of gap splitting (RefineOptions::max_gap): the edges whose midpoint lies
/// farther than max_gap leaf sides outside G get a vertex there, migrated onto G; each
/// triangle is split by its split edges (one: 1-to-2 through the opposite corner; two: the
/// corner triangle and the rest by its shorter diagonal; three: 1-to-4). A split whose new
/// vertex is involved in an intersecting or degenerate triangle is undone (passes until none
/// is: this includes one whose triangles meet a fold that was there before), so the
/// splitting adds no fold. Later rounds test only edges at vertices the round before
/// added (`fresh` and beyond). False if no edge was split.
bool split_gaps(Triangles& triangles, std::size_t fresh, const Context& ctx, Vertices& m2,
                RefineStats& stats) {
  std::vector<std::pair<int, int>> edges;
  edges.reserve(3 * triangles.size() / 2);
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) {
      const int a = t[k], b = t[(k + 1) % 3];
      if (a < b) edges.emplace_back(a, b);  // each edge once (the mesh is closed, oriented)
    }
  std::sort(edges.begin(), edges.end());
  std::vector<char> far(edges.size(), 0);
  tbb::parallel_for(std::size_t(0), edges.size(), [&](std::size_t e) {
    const auto [a, b] = edges[e];
    if (static_cast<std::size_t>(b) < fresh) return;  // tested in an earlier round (b > a)
    const double tol = ctx.opt.max_gap * std::min(m2.locale[a].side, m2.locale[b].side);
    // Both ends lie on G: a midpoint within tol of one cannot be farther from G.
    if ((m2.position[a] - m2.position[b]).squaredNorm() <= 4 * tol * tol) return;
    const Vec3 m = (m2.position[a] + m2.position[b]) / 2;
    // The balls of a's leaf first (cheap, and nearly always one of them is within tol).
    if (ball_within(ctx, m2.locale[a], m, tol)) return;
    far[e] = !ctx.g.within(m, tol);
  });
  std::vector<std::size_t> split;  // edges with a candidate vertex, in edge order
  for (std::size_t e = 0; e < edges.size(); ++e)
    if (far[e]) split.push_back(e);
  if (split.empty()) return false;

  // Candidates after the current vertices: index first_new + j for split[j].
  const std::size_t first_new = m2.start.size(), count = split.size();
  std::vector<Vec3> from(count), to(count);
  std::vector<Locale> locale(count);
  std::vector<Outcome> outcome(count);
  tbb::parallel_for(std::size_t(0), count, [&](std::size_t j) {
    const auto [a, b] = edges[split[j]];
    from[j] = (m2.position[a] + m2.position[b]) / 2;
    locale[j] = point_locale(ctx, from[j]);
    outcome[j] = migrate(ctx, from[j], locale[j], to[j]);
  });
  std::vector<int> mid(edges.size(), -1);
  for (std::size_t j = 0; j < count; ++j) mid[split[j]] = static_cast<int>(first_new + j);
  std::vector<std::array<std::size_t, 3>> sides(triangles.size());
  tbb::parallel_for(std::size_t(0), triangles.size(), [&](std::size_t f) {
    for (int k = 0; k < 3; ++k) {
      const int a = triangles[f][k], b = triangles[f][(k + 1) % 3];
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      const auto it = std::lower_bound(edges.begin(), edges.end(), key);
      if (it == edges.end() || *it != key)  // every edge is listed once from its a < b side
        throw std::logic_error("gap splitting: the triangles are not a closed oriented mesh");
      sides[f][k] = static_cast<std::size_t>(it - edges.begin());
    }
  });
  // The checks need only the triangles near a candidate: those whose box is near the box
  // of a triangle with a split edge grown to hold the candidates on its edges.
  std::vector<Eigen::AlignedBox3d> probes;
  auto box_of = [&](const std::array<int, 3>& t) {
    Eigen::AlignedBox3d b(m2.position[t[0]]);
    b.extend(m2.position[t[1]]);
    b.extend(m2.position[t[2]]);
    return b;
  };
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    bool any = false;
    Eigen::AlignedBox3d b = box_of(triangles[f]);
    for (std::size_t e : sides[f])
      if (mid[e] >= 0) {
        b.extend(to[mid[e] - first_new]);
        any = true;
      }
    if (any) probes.push_back(b);
  }
  const mg::detail::BoxGrid grid(probes);
  std::vector<std::array<int, 3>> local;
  std::vector<std::array<std::size_t, 3>> local_sides;
  for (std::size_t f = 0; f < triangles.size(); ++f)
    if (grid.near(box_of(triangles[f]))) {
      local.push_back(triangles[f]);
      local_sides.push_back(sides[f]);
    }
  PolygonSoup soup;
  soup.points = m2.position;
  soup.points.insert(soup.points.end(), to.begin(), to.end());
  // Each pass that undoes something undoes at least one candidate: this ends.
  while (true) {
    const std::vector<std::array<int, 3>> out =
        split_triangles(local, local_sides, mid, soup.points);
    std::vector<int> touched;  // the triangles at candidate vertices
    for (std::size_t f = 0; f < out.size(); ++f)
      if (std::any_of(out[f].begin(), out[f].end(),
                      [&](int v) { return v >= static_cast<int>(first_new); }))
        touched.push_back(static_cast<int>(f));
    soup.faces.clear();
    for (const auto& t : out) soup.faces.push_back({t[0], t[1], t[2]});
    const TriangleDefects d = find_triangle_defects(soup, touched);
    bool undone = false;
    for (int v : involved_vertices(d, out))
      if (v >= static_cast<int>(first_new) && mid[split[v - first_new]] >= 0) {
        mid[split[v - first_new]] = -1;
        ++stats.gap_undone;
        undone = true;
      }
    if (!undone) break;
  }
  // Keep the accepted candidates, renumbered in edge order.
  std::size_t kept = 0;
  for (std::size_t j = 0; j < count; ++j) {
    const std::size_t e = split[j];
    if (mid[e] < 0) continue;
    const auto [a, b] = edges[e];
    mid[e] = static_cast<int>(first_new + kept++);
    // The repair's last resort returns vertices to their start: for a new vertex, the
    // midpoint of its edge's starts, so the starts stay the fold-free dual of M1, subdivided.
    m2.start.push_back((m2.start[a] + m2.start[b]) / 2);
    m2.position.push_back(to[j]);
    m2.locale.push_back(std::move(locale[j]));
    count_outcome(outcome[j], stats);
  }
  if (kept == 0) return false;
  stats.vertices_migrated += kept;
  stats.gap_splits += kept;
  triangles = split_triangles(triangles, sides, mid, m2.position);
  return true;
}

}  // namespace mg::garbing::refine
