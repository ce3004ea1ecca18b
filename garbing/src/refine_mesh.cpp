// Step 3: M2, its parts run in the order data flows (m2.h).
#include "garbing/refine_mesh.h"

#include "core/errors.h"
#include "core/timer.h"
#include "m2.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <map>

namespace mg::garbing {
namespace {

using refine::Triangles;

/// 1-to-4 subdivision (--refine): a new vertex per edge at its midpoint, migrated onto G with
/// P from the leaves whose closed cube contains it.
Triangles subdivide(const Triangles& triangles, const refine::Context& ctx, refine::Vertices& m2,
                    RefineStats& stats) {
  std::map<std::pair<int, int>, int> midpoint;
  const std::size_t first_new = m2.position.size();
  auto mid = [&](int a, int b) {
    const auto key = std::minmax(a, b);
    auto [it, inserted] = midpoint.emplace(key, static_cast<int>(m2.start.size()));
    if (inserted) {
      m2.start.push_back((m2.position[a] + m2.position[b]) / 2);
      m2.locale.emplace_back();
    }
    return it->second;
  };
  Triangles out;
  out.reserve(4 * triangles.size());
  for (const auto& t : triangles) {
    const int ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
    out.push_back({t[0], ab, ca});
    out.push_back({ab, t[1], bc});
    out.push_back({ca, bc, t[2]});
    out.push_back({ab, bc, ca});
  }
  tbb::parallel_for(first_new, m2.start.size(),
                    [&](std::size_t i) { m2.locale[i] = refine::point_locale(ctx, m2.start[i]); });
  refine::migrate_range(ctx, m2, first_new, stats);
  return out;
}

}  // namespace

RefinedMesh refine_mesh(const CoarseMesh& m1, const Octree& tree, const TargetShape& g,
                        const RefineOptions& opt) {
  if (opt.subdivisions < 0) throw InvalidInput("refine: subdivisions must be >= 0");
  if (!(opt.max_travel > 0)) throw InvalidInput("refine: max travel must be > 0");
  if (opt.repair_rounds < 0) throw InvalidInput("refine: repair rounds must be >= 0");
  if (!(opt.max_gap >= 0)) throw InvalidInput("refine: max gap must be >= 0");
  if (opt.gap_rounds < 0) throw InvalidInput("refine: gap rounds must be >= 0");
  if (m1.faces.size() != m1.mesh.n_faces()) throw InvalidInput("refine: M1 and its faces disagree");
  if (tree.root_side != g.frame().cube_side || tree.frame.origin != g.frame().origin)
    throw InvalidInput("refine: the octree was not built from this G");

  const refine::Context ctx{tree, g, opt};
  refine::Vertices m2;
  RefineStats stats;
  Stopwatch clock;
  // The dual of M1 (or M1 itself), its vertices migrated onto G, then triangulated.
  const refine::Polygons polygons =
      opt.dual ? refine::start_from_dual(m1, ctx, m2, stats) : refine::start_from_m1(m1, ctx, m2);
  refine::migrate_range(ctx, m2, 0, stats);
  Triangles triangles = refine::triangulate(polygons, ctx, m2, stats);
  // Gap splitting: later rounds test only the edges at vertices the round before added.
  for (std::size_t round = 0, fresh = 0; opt.max_gap > 0 && round < std::size_t(opt.gap_rounds);
       ++round) {
    const std::size_t added = m2.start.size();
    if (!refine::split_gaps(triangles, fresh, ctx, m2, stats)) break;
    fresh = added;
  }
  stats.seconds_migration = clock.seconds();
  refine::repair_folds(triangles, ctx, m2, stats);
  for (int round = 0; round < opt.subdivisions; ++round) {
    clock.restart();
    triangles = subdivide(triangles, ctx, m2, stats);
    stats.seconds_migration += clock.seconds();
    refine::repair_folds(triangles, ctx, m2, stats);
  }

  PolygonSoup soup = refine::soup_of(triangles, m2);
  for (auto& p : soup.points) p = tree.to_world(p);
  RefinedMesh out;
  out.mesh = mesh_from_manifold_soup(soup, "M2");
  out.stats = stats;
  return out;
}

}  // namespace mg::garbing
