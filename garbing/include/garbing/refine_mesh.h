#pragma once
/// \file refine_mesh.h
/// Step 3 of the garbing: M2, the dual of M1 migrated onto the target shape G (paper section
/// 3.3, docs/algorithm.md "Step 3"). Its parts, in the order they run: the dual of M1, the
/// migration of every vertex onto G, gap splitting, fold repair (src/m2_*.cpp).

#include "garbing/coarse_mesh.h"
#include "garbing/octree.h"
#include "garbing/target_shape.h"

#include <cstddef>

namespace mg::garbing {

struct RefineOptions {
  bool dual = true;         ///< false: migrate M1 itself, triangulated (Figure 11's ablation)
  int subdivisions = 0;     ///< rounds of 1-to-4 subdivision followed by migration (Figure 14)
  double max_travel = 4.0;  ///< in sides of the vertex's leaf; a longer ray falls back
  int repair_rounds = 8;    ///< rounds of each repair stage (relaxation on G, then pull-back)
  /// Gap splitting, after the migration and before the repair: an edge whose midpoint lies
  /// provably farther than max_gap sides of its (smaller) leaf from G is split there, the new
  /// vertex migrated like --refine's, for up to gap_rounds rounds (triangles split 1-to-2,
  /// 1-to-3 or 1-to-4 by their split edges). Catches edges bridging a notch of G narrower than
  /// a leaf. 0: off.
  double max_gap = 0.5;
  int gap_rounds = 3;
  /// Find where a vertex's ray first enters G from the octree's lists (P of its leaf, then of
  /// the leaves the ray crosses) before asking the hierarchy over all primitives. The same
  /// result either way; false only for tests and timing.
  bool local_queries = true;
};

struct RefineStats {
  std::size_t vertices_migrated = 0;
  std::size_t fallback_zero_direction = 0;  ///< |m(v)| ~ 0: closest point of G instead
  std::size_t fallback_missed = 0;          ///< the ray met no primitive
  std::size_t fallback_too_far = 0;         ///< the ray reached G beyond max_travel
  std::size_t collapsed_digons = 0;         ///< valence-2 M1 vertices (dual 2-gons) dropped
  std::size_t centroid_fans = 0;  ///< dual faces fanned from an added centre (see triangulate)
  std::size_t gap_splits = 0;     ///< edges split by the gap test (max_gap), all rounds
  std::size_t gap_undone = 0;     ///< candidate gap splits undone: their vertex folded
  /// Defects found right after each migration pass (the first, then one per subdivision
  /// round), summed; and what is left at the end.
  std::size_t intersecting_before = 0, degenerate_before = 0;
  std::size_t intersecting_after = 0, degenerate_after = 0;
  std::size_t repaired_vertices = 0;  ///< vertices moved by the repair (on G or pulled back)
  std::size_t pulled_back = 0;        ///< pull-back steps taken (leave a vertex off G)
  std::size_t left_off_g = 0;         ///< vertices the repair's stages 2-3 left off G (pulled back)
  /// The dual, migration, triangulation, gap splitting and subdivision; the fold check and
  /// repair. Seconds.
  double seconds_migration = 0, seconds_repair = 0;
};

struct RefinedMesh {
  Mesh mesh;  ///< M2: closed oriented triangle mesh, world coordinates, CCW from outside
  RefineStats stats;
};

/// Step 3: M2. With `opt.dual`, one vertex per M1 face at the centre of its square and one
/// face per M1 vertex, triangulated (V(M2) = F(M1); faces from valence-2 M1 vertices collapse
/// to an edge). Each vertex moves along m(v) = -sum of m_g(v) over the primitives P of its
/// leaf onto G: outside the union, to where the line first enters it; inside, back to where
/// it leaves. Edges bridging a notch of G are split (opt.max_gap); fold-overs are detected and
/// repaired.
/// @param m1    from extract_coarse_mesh(tree)
/// @param tree  from build_octree(g)
/// @param g     the target shape the tree was built from (its frame is the tree's)
/// @pre opt.subdivisions >= 0, opt.max_travel > 0, opt.repair_rounds >= 0, opt.max_gap >= 0,
///      opt.gap_rounds >= 0; tree and g agree  @throws InvalidInput
/// @post a closed oriented triangle mesh in world coordinates; every vertex on G but those
///       counted in stats (fallbacks, left_off_g)
RefinedMesh refine_mesh(const CoarseMesh& m1, const Octree& tree, const TargetShape& g,
                        const RefineOptions& opt = {});

}  // namespace mg::garbing
