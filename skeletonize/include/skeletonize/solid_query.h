#pragma once
/// \file solid_query.h
/// Inside tests and distances for a closed mesh, as the skeletonization needs them: which
/// Voronoi vertices are inside (the inner poles), how far a centre is from the mesh (overshoot,
/// clamping), and which regular-triangulation edges and triangles stay inside (connectivity).

#include "core/mesh.h"

#include <Eigen/Core>

#include <memory>

namespace mg::skeletonize {

/// Inside tests and distances for a closed mesh (CGAL Side_of_triangle_mesh and AABB tree
/// over its triangles). Immutable after construction; queries are thread-safe.
class SolidQuery {
 public:
  /// How distances and closest points are computed: `cgal`, CGAL's filtered predicates and
  /// projection (what the poles' clamped radii have always used); `plain`, plain doubles
  /// (core/detail/plain_distance_traits.h), several times faster on flat meshes and equal up to
  /// the last bits; it builds a second tree.
  enum class Distances { cgal, plain };
  /// @pre a closed mesh (polygons are fan-triangulated), indices in range
  explicit SolidQuery(const PolygonSoup& mesh, Distances distances = Distances::cgal);
  ~SolidQuery();
  SolidQuery(const SolidQuery&) = delete;
  SolidQuery& operator=(const SolidQuery&) = delete;
  /// Strictly inside the solid the mesh bounds.
  bool contains(const Eigen::Vector3d& p) const;
  /// Unsigned distance to the mesh, model units.
  double distance(const Eigen::Vector3d& p) const;
  /// The same, starting the search from `hint`, a point on the mesh (a sample) near the answer.
  double distance(const Eigen::Vector3d& p, const Eigen::Vector3d& hint) const;
  /// Whether some point of the mesh lies closer than `radius` to p (false for radius <= 0).
  bool within(const Eigen::Vector3d& p, double radius) const;
  /// The closest point of the mesh to p.
  Eigen::Vector3d closest_point(const Eigen::Vector3d& p) const;
  /// The same, starting the search from `hint`, a point on the mesh near the answer.
  Eigen::Vector3d closest_point(const Eigen::Vector3d& p, const Eigen::Vector3d& hint) const;
  /// The triangle closest to p: its index in fan_triangles(mesh) (ties: the tree's first).
  int closest_triangle(const Eigen::Vector3d& p) const;
  /// Segment [a, b] meets no mesh face and its midpoint is inside.
  bool segment_inside(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const;
  /// Triangle (a, b, c) meets no mesh face and its centroid is inside.
  bool triangle_inside(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                       const Eigen::Vector3d& c) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mg::skeletonize
