#pragma once
/// \file distances.h
/// The generic core of every distance the project reports (Metro / MESH style): each side of a
/// comparison is a set of weighted samples on its surface plus a distance oracle to the OTHER
/// side. The one-sided maximum is taken over all samples; the mean and RMS are weighted
/// integrals. `evaluate distance` plugs in two meshes (mesh_distance.h); `evaluate atoms`
/// plugs in samples of the target shape G and exact point-to-G distances, with the same
/// aggregation.
///
/// Determinism: samples are generated from a counter-based random stream (sample k depends only
/// on the seed and k), the oracles are called on fixed batches of consecutive samples whose
/// boundaries do not depend on the thread count, and the sums are taken serially in sample
/// order: the same input gives bit-identical results at any thread count.

#include "core/mesh.h"

#include <Eigen/Core>

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace mg::evaluate {

/// Points on one surface. The maximum distance is taken over every point; the mean and RMS are
/// the weighted means of d and d^2, so weights must be proportional to the surface area each
/// point stands for. A point of weight 0 only sharpens the maximum (Metro's vertex and edge
/// samples).
struct SurfaceSamples {
  std::vector<Eigen::Vector3d> points;  ///< model units
  std::vector<double> weights;          ///< one per point, finite and >= 0, not all 0
};

/// Unsigned distances from a batch of points to a surface, model units:
/// `distances[i]` = distance from `points[i]`, for i < count.
/// The core calls the oracle concurrently from several threads on disjoint batches of at most
/// kOracleBatch consecutive samples; the result for a point must not depend on the thread or on
/// the order of calls (it may depend on the batch, e.g. to use the previous answer as a hint,
/// because batch boundaries are fixed).
using DistanceOracle =
    std::function<void(const Eigen::Vector3d* points, std::size_t count, double* distances)>;

/// Batch size of the oracle calls (fixed: the results do not depend on the thread count).
constexpr std::size_t kOracleBatch = 1024;

/// The distances from the samples of one surface to another surface.
struct OneSidedDistance {
  double max = 0;   ///< over all samples, model units
  double mean = 0;  ///< weighted mean of d, model units
  double rms = 0;   ///< sqrt of the weighted mean of d^2, model units
  Eigen::Vector3d farthest = Eigen::Vector3d::Zero();  ///< the first sample reaching max
  std::size_t samples = 0;                             ///< all samples
  std::size_t weighted_samples = 0;  ///< samples with weight > 0 (those behind mean and RMS)
};

/// Both directions, aggregated as the MESH tool does: each statistic is the larger of the two
/// one-sided values.
struct TwoSidedDistance {
  OneSidedDistance a_to_b;  ///< samples of A against B
  OneSidedDistance b_to_a;  ///< samples of B against A
  double hausdorff = 0;     ///< max(a_to_b.max, b_to_a.max), model units
  double rms = 0;           ///< max(a_to_b.rms, b_to_a.rms), model units
  double mean = 0;          ///< max(a_to_b.mean, b_to_a.mean), model units
};

/// Distances from every sample of `from` to the surface behind `to` (parallel, deterministic).
/// @pre from.weights.size() == from.points.size(); weights finite, >= 0, with a positive sum;
///      the oracle returns finite values >= 0
/// @throws InvalidInput on empty samples or bad weights; NumericalError if the oracle returns a
///         negative or non-finite distance
OneSidedDistance one_sided_distance(const SurfaceSamples& from, const DistanceOracle& to);

/// Both one-sided distances and their MESH-style aggregation.
/// @param on_a  samples of surface A;  @param to_b  distances to surface B
/// @param on_b  samples of surface B;  @param to_a  distances to surface A
/// @pre as one_sided_distance for each side   @throws as one_sided_distance
TwoSidedDistance two_sided_distance(const SurfaceSamples& on_a, const DistanceOracle& to_b,
                                    const SurfaceSamples& on_b, const DistanceOracle& to_a);

/// 100 * value / diagonal: a length in percent of a bounding-box diagonal.
/// @pre diagonal > 0   @throws InvalidInput
double percent_of_diagonal(double value, double diagonal);

/// How to sample a mesh surface.
struct SamplingOptions {
  /// Total number of samples. With Metro sampling: every vertex, then of the remaining
  /// R = count - V, a quarter spread along the edges by length and the rest on the faces.
  std::size_t count = 1000000;
  std::uint64_t seed = 1;  ///< any value; the same seed gives the same samples
  /// true: Metro sampling (vertices, edge points, face points). false: face points only (what
  /// MeshLab's "Hausdorff Distance" filter does with only "Sample Faces" ticked).
  bool vertices_and_edges = true;
};

/// Samples a mesh surface, Metro style. Face points are area-uniform: systematic sampling along
/// the cumulative area of the triangles (one random offset: each triangle gets the floor or the
/// ceiling of its expected share) and a uniformly random point inside each triangle. Edge
/// points are systematic along the cumulative length of the distinct edges. Only face points
/// carry weight (1 each: they stand for equal areas), so mean and RMS estimate the
/// area integrals of d and d^2 (MESH's definition) while vertices and edge points, where
/// maxima tend to sit, sharpen the maximum.
/// @param name used in messages
/// @pre soup faces valid (read_polygon_soup); total area > 0; count >= 1 (faces only) or
///      count >= 2 V (Metro: every referenced vertex is one sample)
/// @throws InvalidInput naming `name` otherwise
SurfaceSamples sample_surface(const PolygonSoup& soup, const SamplingOptions& opt,
                              const std::string& name);

/// Area-uniform points on triangles, each with the triangle it lies on.
struct TriangleSamples {
  std::vector<Eigen::Vector3d> points;  ///< model units
  std::vector<std::size_t> triangle;    ///< index into Triangles::corners
};

/// The face part of sample_surface(): `count` area-uniform points, systematic along the
/// cumulative area (each triangle gets the floor or the ceiling of its expected share) and
/// uniformly random inside their triangle.
/// @pre count >= 1; the triangles' total area > 0   @throws InvalidInput naming `name`
TriangleSamples sample_triangles(const PolygonSoup& soup, const Triangles& triangles,
                                 std::size_t count, std::uint64_t seed, const std::string& name);

/// The default sample count of `evaluate distance`: max(1e6, 10 (V_a + V_b)) per side, with V
/// the vertices referenced by faces.
std::size_t default_sample_count(const PolygonSoup& a, const PolygonSoup& b);

}  // namespace mg::evaluate
