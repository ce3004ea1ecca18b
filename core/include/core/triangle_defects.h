#pragma once
/// \file triangle_defects.h
/// Geometric defects of a triangle soup: intersecting triangle pairs and degenerate triangles,
/// counted separately (CGAL's does_self_intersect reports a degenerate face as a self-pair).

#include "core/mesh.h"

#include <array>
#include <vector>

namespace mg {

struct TriangleDefects {
  /// Pairs (f < g) of non-degenerate triangles that intersect other than along what they
  /// share: disjoint ones that meet; ones sharing a vertex whose opposite edge crosses the
  /// other; ones sharing an edge that fold onto each other (coplanar, same side). Sorted.
  std::vector<std::array<int, 2>> intersecting_pairs;
  std::vector<int> degenerate_faces;  ///< triangles with collinear corners (exact test), sorted
};

/// Exact predicates (CGAL Epick), box-intersection broad phase. Works on any soup (manifold
/// or not); vertices are shared by index.
/// @pre every face is a triangle with in-range indices   @throws InvalidInput otherwise
TriangleDefects find_triangle_defects(const PolygonSoup& triangles);

/// The same, restricted to the defects that involve at least one of the triangles `subset`
/// (face indices): what a local change can have created or removed.
TriangleDefects find_triangle_defects(const PolygonSoup& triangles, const std::vector<int>& subset);

}  // namespace mg
