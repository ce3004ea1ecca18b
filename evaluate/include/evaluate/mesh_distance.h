#pragma once
/// \file mesh_distance.h
/// Distances between two meshes (`evaluate distance`): Metro sampling of both surfaces
/// (distances.h) and exact closest points on the other mesh through a CGAL AABB tree.

#include "evaluate/distances.h"

#include <memory>

namespace mg::evaluate {

/// Closest-point queries on the triangles of a polygon soup (polygons fanned). Holds a CGAL
/// AABB tree (hidden here). Immutable after construction; queries are thread-safe.
class TriangleIndex {
 public:
  /// A closest point and the triangle it lies on (index into triangles().corners).
  struct Hit {
    Eigen::Vector3d point = Eigen::Vector3d::Zero();
    std::size_t triangle = 0;
  };

  /// @param name used in messages
  /// @pre at least one non-degenerate triangle   @throws InvalidInput naming `name`
  explicit TriangleIndex(const PolygonSoup& soup, const std::string& name = "mesh");
  ~TriangleIndex();
  TriangleIndex(const TriangleIndex&) = delete;
  TriangleIndex& operator=(const TriangleIndex&) = delete;

  const PolygonSoup& soup() const;
  const Triangles& triangles() const;

  /// Closest points of a batch of queries. Each query after the first is hinted with the
  /// previous answer (consecutive samples lie close to each other: large speed-up); the first
  /// uses CGAL's internal k-d tree. Exact up to floating-point rounding of the final projection.
  /// @param[out] hits  count entries
  void closest_points(const Eigen::Vector3d* queries, std::size_t count, Hit* hits) const;

  /// Unsigned distances of a batch of queries, model units (closest_points without the hits,
  /// and the previous answer hints a query only when it lies within the previous distance plus
  /// two mean edge lengths: random-order queries would otherwise search far).
  void distances(const Eigen::Vector3d* queries, std::size_t count, double* out) const;

  /// This index as a DistanceOracle (references *this: keep the index alive while it is used).
  DistanceOracle oracle() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

struct MeshDistanceOptions {
  /// Samples per side; 0 = default_sample_count(mesh, reference).
  std::size_t samples = 0;
  std::uint64_t seed = 1;
  /// false = faces only (to match MeshLab's face-only sampling).
  bool vertices_and_edges = true;
};

/// Two-sided distances between MESH (side A) and REFERENCE (side B).
struct MeshDistance {
  TwoSidedDistance distance;  ///< a_to_b = mesh to reference
  double diagonal = 0;        ///< REFERENCE's bounding-box diagonal, model units
  std::size_t samples = 0;    ///< per side
};

/// Samples both meshes (same options on both sides) and measures both ways in parallel.
/// @param mesh_name, reference_name  used in messages
/// @pre both soups non-empty with positive area   @throws InvalidInput naming the file
MeshDistance mesh_distance(const PolygonSoup& mesh, const PolygonSoup& reference,
                           const MeshDistanceOptions& opt = {},
                           const std::string& mesh_name = "mesh",
                           const std::string& reference_name = "reference");

}  // namespace mg::evaluate
