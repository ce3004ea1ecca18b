#pragma once
/// \file mesh_checks.h
/// Validity of a mesh file read as a polygon soup (`evaluate check`): the combinatorial report
/// of mg::mesh_topology plus the geometric checks: intersecting triangle pairs, degenerate
/// triangles (counted apart), the minimum angle and the valence histogram.

#include "core/mesh_topology.h"

#include <cstddef>
#include <map>
#include <string>

namespace mg::evaluate {

struct MeshCheck {
  MeshTopology topology;      ///< closed, 2-manifold (edges and vertex links), oriented, genus...
  std::size_t triangles = 0;  ///< after fanning polygons
  std::size_t non_triangle_faces = 0;  ///< faces with 4+ corners (fanned for the checks below)
  /// Triangles whose three corners are collinear (exact predicate; includes coincident
  /// corners). They are left out of the intersection test.
  std::size_t degenerate_triangles = 0;
  /// Unordered pairs of distinct faces whose triangles intersect other than along what they
  /// share: disjoint-index pairs that meet at all, pairs sharing one vertex that meet elsewhere,
  /// pairs sharing an edge that overlap (coplanar, same side), and duplicated faces. Exact
  /// predicates (CGAL Epick).
  std::size_t intersecting_pairs = 0;
  /// Smallest corner angle over the non-degenerate triangles, degrees (0 if none).
  double min_angle_deg = 0;
  /// Number of vertices per valence (distinct neighbours through face edges), by valence.
  std::map<std::size_t, std::size_t> valence_histogram;
  std::string first_degenerate;    ///< "face 12 is degenerate (collinear corners)", or empty
  std::string first_intersection;  ///< "faces 3 and 17 intersect", or empty
};

/// @pre faces valid (read_polygon_soup guarantees it)
MeshCheck check_mesh(const PolygonSoup& soup);

}  // namespace mg::evaluate
