#pragma once
// Internal to mg::garbing: the parts of step 3 (refine_mesh.h), one file each, sharing one plain
// per-vertex record. Data flows one way: the dual of M1 (m2_dual.cpp) -> migration onto G
// (m2_migration.cpp) -> gap splitting (m2_gap_splitting.cpp) -> fold repair
// (m2_fold_repair.cpp); refine_mesh.cpp runs them in that order. Everything is in G's frame.

#include "core/triangle_defects.h"
#include "garbing/coarse_mesh.h"
#include "garbing/octree.h"
#include "garbing/refine_mesh.h"
#include "garbing/target_shape.h"

#include <Eigen/Geometry>

#include <array>
#include <cstddef>
#include <memory>
#include <vector>

namespace mg::garbing::refine {

using Vec3 = Eigen::Vector3d;
using Triangles = std::vector<std::array<int, 3>>;
using Polygons = std::vector<std::vector<int>>;

struct Context;

/// P of a point, shared by the vertices that migrate with it.
using PrimitiveList = std::shared_ptr<const std::vector<PrimitiveId>>;

/// What a vertex migrates with: P, the leaf side that scales its travel, and a closed box
/// `cover` holding the vertex's start such that P lists every primitive meeting it (no box:
/// `cover` empty). P is `prims` (a point's, shared by the vertices of one leaf), or that of the
/// owning `leaf`, gathered from the octree's lists when needed (a dual vertex's: not stored,
/// the lists are the octree's), or none.
struct Locale {
  PrimitiveList prims;
  int leaf = -1;
  double side = 0;
  Eigen::AlignedBox3d cover;
  bool has_list() const { return prims || leaf >= 0; }
};

/// P of a locale, sorted, without repeats (empty when it has none): `prims`, or the leaf's
/// gathered into `scratch`.
const std::vector<PrimitiveId>& primitives_of(const Context& ctx, const Locale& locale,
                                              std::vector<PrimitiveId>& scratch);

/// Whether a ball of P lies within `tol` of p (P's balls are the leaf's list).
bool ball_within(const Context& ctx, const Locale& locale, const Vec3& p, double tol);

/// M2 under construction: per vertex, where it started (the fold-free dual of M1, or what
/// subdivision and gap splitting derive from it), where it is now, and what it migrates with.
struct Vertices {
  std::vector<Vec3> start;
  std::vector<Vec3> position;
  std::vector<Locale> locale;
};

/// What every part reads.
struct Context {
  const Octree& tree;
  const TargetShape& g;
  const RefineOptions& opt;
};

// --- the starting mesh (m2_dual.cpp) ---------------------------------------------------------

/// The dual of M1: one vertex at the centre of each M1 square (its locale: P of the owning
/// leaf) and one polygon per M1 vertex, its faces in counter-clockwise order seen from
/// outside. M1 vertices of valence 2 (pinch midpoints) give no polygon (counted).
Polygons start_from_dual(const CoarseMesh& m1, const Context& ctx, Vertices& m2,
                         RefineStats& stats);

/// M1 itself (--no-dual): its vertices (locales from the leaves holding them) and its faces.
Polygons start_from_m1(const CoarseMesh& m1, const Context& ctx, Vertices& m2);

/// Triangulates the polygons by least total diagonal length, a diagonal already in the mesh
/// forbidden; a polygon with no allowed triangulation is fanned from a new vertex at its
/// centroid, moved to the closest point of G (counted).
Triangles triangulate(const Polygons& polygons, const Context& ctx, Vertices& m2,
                      RefineStats& stats);

// --- migration (m2_migration.cpp) ------------------------------------------------------------

enum class Outcome { ray, zero_direction, missed, too_far };

/// Counts a fallback by kind.
void count_outcome(Outcome o, RefineStats& stats);

/// The locale of an M2 vertex owned by `leaf`: P(c), the leaf's side, its cube as the cover.
Locale leaf_locale(const Context& ctx, int leaf);

/// The locale of a point (vertices of --no-dual, --refine, gap splitting): the primitives
/// meeting the closed cube of any leaf that contains it; the smallest such leaf's side.
Locale point_locale(const Context& ctx, const Vec3& p);

/// Moves v along m(v) onto G (see refine_mesh.h); `out` is where it lands.
Outcome migrate(const Context& ctx, const Vec3& v, const Locale& locale, Vec3& out);
/// The same with P of the locale given (primitives_of).
Outcome migrate(const Context& ctx, const Vec3& v, const Locale& locale,
                const std::vector<PrimitiveId>& prims, Vec3& out);

/// Migrates the vertices [first, end) from their start into `position` (in parallel).
void migrate_range(const Context& ctx, Vertices& m2, std::size_t first, RefineStats& stats);

// --- gap splitting (m2_gap_splitting.cpp) ----------------------------------------------------

/// One round of gap splitting (RefineOptions::max_gap); later rounds test only edges at
/// vertices from `fresh` on. False if no edge was split.
bool split_gaps(Triangles& triangles, std::size_t fresh, const Context& ctx, Vertices& m2,
                RefineStats& stats);

// --- fold repair (m2_fold_repair.cpp) --------------------------------------------------------

/// The soup of the triangles over the current positions.
PolygonSoup soup_of(const Triangles& triangles, const Vertices& m2);

/// Vertices of the intersecting and degenerate triangles, sorted.
std::vector<int> involved_vertices(const TriangleDefects& d, const Triangles& triangles);

/// Detects and repairs fold-overs (see refine_mesh.h), counting them before and after.
void repair_folds(const Triangles& triangles, const Context& ctx, Vertices& m2, RefineStats& stats);

}  // namespace mg::garbing::refine
