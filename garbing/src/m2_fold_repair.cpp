// Step 3, fold repair: intersecting and degenerate triangles found with exact predicates and
// undone in stages, first on G, then off it.
#include "m2.h"

#include "core/timer.h"

#include <tbb/parallel_for.h>

#include <algorithm>

namespace mg::garbing::refine {

PolygonSoup soup_of(const Triangles& triangles, const Vertices& m2) {
  PolygonSoup soup;
  soup.points = m2.position;
  soup.faces.reserve(triangles.size());
  for (const auto& t : triangles) soup.faces.push_back({t[0], t[1], t[2]});
  return soup;
}

/// Vertices of the intersecting and degenerate triangles, sorted.
std::vector<int> involved_vertices(const TriangleDefects& d, const Triangles& triangles) {
  std::vector<int> out;
  for (const auto& p : d.intersecting_pairs)
    for (int f : p) out.insert(out.end(), triangles[f].begin(), triangles[f].end());
  for (int f : d.degenerate_faces) out.insert(out.end(), triangles[f].begin(), triangles[f].end());
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

/// Repairs fold-overs in stages, re-detecting after each round:
/// 1. on G: the vertices of defective triangles and their neighbours move to the closest
///    point of G to the centroid of their neighbours (untangles while staying on G);
/// 2. off G, as a last resort: the vertices still involved are pulled back along their
///    migration path, halving their step each round;
/// 3. if some are still folded: they (and, round by round, their neighbours) return to their
///    starting point, the fold-free dual of M1.
/// The vertices stages 2-3 moved are off G; they are counted (`left_off_g`).
void repair_folds(const Triangles& triangles, const Context& ctx, Vertices& m2,
                  RefineStats& stats) {
  const Stopwatch clock;
  PolygonSoup soup = soup_of(triangles, m2);  // faces fixed; points refreshed before each check
  TriangleDefects d = find_triangle_defects(soup);
  stats.intersecting_before += d.intersecting_pairs.size();
  stats.degenerate_before += d.degenerate_faces.size();
  stats.intersecting_after = d.intersecting_pairs.size();
  stats.degenerate_after = d.degenerate_faces.size();
  if (d.intersecting_pairs.empty() && d.degenerate_faces.empty()) {
    stats.seconds_repair += clock.seconds();
    return;
  }

  std::vector<std::vector<int>> ring(m2.position.size());
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) {
      ring[t[k]].push_back(t[(k + 1) % 3]);
      ring[t[k]].push_back(t[(k + 2) % 3]);
    }
  for (auto& r : ring) {
    std::sort(r.begin(), r.end());
    r.erase(std::unique(r.begin(), r.end()), r.end());
  }
  std::vector<std::vector<int>> faces_of(m2.position.size());
  for (std::size_t f = 0; f < triangles.size(); ++f)
    for (int v : triangles[f]) faces_of[v].push_back(static_cast<int>(f));
  // Defects can only change around moved vertices: re-detect there, keep the rest.
  auto redetect = [&](const std::vector<int>& moved_now) {
    std::vector<int> dirty;
    for (int v : moved_now) dirty.insert(dirty.end(), faces_of[v].begin(), faces_of[v].end());
    std::sort(dirty.begin(), dirty.end());
    dirty.erase(std::unique(dirty.begin(), dirty.end()), dirty.end());
    auto is_dirty = [&](int f) { return std::binary_search(dirty.begin(), dirty.end(), f); };
    soup.points = m2.position;
    TriangleDefects local = find_triangle_defects(soup, dirty);
    for (const auto& p : d.intersecting_pairs)
      if (!is_dirty(p[0]) && !is_dirty(p[1])) local.intersecting_pairs.push_back(p);
    for (int f : d.degenerate_faces)
      if (!is_dirty(f)) local.degenerate_faces.push_back(f);
    std::sort(local.intersecting_pairs.begin(), local.intersecting_pairs.end());
    std::sort(local.degenerate_faces.begin(), local.degenerate_faces.end());
    d = std::move(local);
  };
  std::vector<char> moved(m2.position.size(), 0);
  for (int round = 0; round < ctx.opt.repair_rounds; ++round) {
    if (d.intersecting_pairs.empty() && d.degenerate_faces.empty()) break;
    std::vector<int> involved = involved_vertices(d, triangles);
    std::vector<int> grown = involved;
    for (int v : involved) grown.insert(grown.end(), ring[v].begin(), ring[v].end());
    std::sort(grown.begin(), grown.end());
    grown.erase(std::unique(grown.begin(), grown.end()), grown.end());
    std::vector<Vec3> next(grown.size());
    tbb::parallel_for(std::size_t(0), grown.size(), [&](std::size_t i) {
      Vec3 centroid = Vec3::Zero();
      for (int w : ring[grown[i]]) centroid += m2.position[w];
      next[i] = ctx.g.closest_point(centroid / static_cast<double>(ring[grown[i]].size()));
    });
    for (std::size_t i = 0; i < grown.size(); ++i) {
      m2.position[grown[i]] = next[i];
      moved[grown[i]] = 1;
    }
    redetect(grown);
  }
  std::vector<char> off_g(m2.position.size(), 0);
  const std::vector<Vec3> target = m2.position;
  std::vector<double> step(m2.position.size(), 1.0);
  for (int round = 0; round < ctx.opt.repair_rounds; ++round) {
    if (d.intersecting_pairs.empty() && d.degenerate_faces.empty()) break;
    const std::vector<int> involved = involved_vertices(d, triangles);
    for (int v : involved) {
      step[v] /= 2;
      moved[v] = 1;
      off_g[v] = 1;
      m2.position[v] = m2.start[v] + step[v] * (target[v] - m2.start[v]);
      ++stats.pulled_back;
    }
    redetect(involved);
  }
  // Still folded: put the vertices involved back where they started (the dual of M1 is
  // fold-free), spreading to their neighbours round by round.
  for (int round = 0; round < ctx.opt.repair_rounds; ++round) {
    if (d.intersecting_pairs.empty() && d.degenerate_faces.empty()) break;
    std::vector<int> involved = involved_vertices(d, triangles);
    if (round > 0) {
      const std::size_t n = involved.size();
      for (std::size_t k = 0; k < n; ++k)
        involved.insert(involved.end(), ring[involved[k]].begin(), ring[involved[k]].end());
      std::sort(involved.begin(), involved.end());
      involved.erase(std::unique(involved.begin(), involved.end()), involved.end());
    }
    for (int v : involved) {
      m2.position[v] = m2.start[v];
      moved[v] = 1;
      off_g[v] = 1;
      ++stats.pulled_back;
    }
    redetect(involved);
  }
  // Tried: moving these back to the closest point of G where that folds nothing; on hand's
  // vertex poles 2 of 3,517 could move (the rest lie in cones whose nearest surface point
  // belongs to another sheet), so they stay where the fold-free stages put them.
  stats.left_off_g += static_cast<std::size_t>(std::count(off_g.begin(), off_g.end(), 1));
  stats.intersecting_after = d.intersecting_pairs.size();
  stats.degenerate_after = d.degenerate_faces.size();
  stats.repaired_vertices += static_cast<std::size_t>(std::count(moved.begin(), moved.end(), 1));
  stats.seconds_repair += clock.seconds();
}

}  // namespace mg::garbing::refine
