#pragma once
/// \file poles.h
/// Medial atoms from a closed mesh: the inner Voronoi poles of surface samples (the power shape
/// of Amenta, Choi and Kolluri 2001, as the paper's section 4). See ALGORITHM.md
/// "Skeletonization".

#include "garbing/medial_surface.h"
#include "garbing/mesh.h"

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace mg::skeletonize {

struct SkeletonOptions {
  bool edge_midpoints = false;     ///< add the midpoint of every edge to the samples
  std::size_t random_samples = 0;  ///< add this many area-uniform random points on the faces
  std::uint64_t seed = 1;          ///< of the random samples (counter-based: reproducible)
  /// Merge tolerance T, model units (negative: 1e-3 of the mesh's bounding-box diagonal).
  /// Poles within T / 2 of a larger pole join its atom, and a ball inside another up to T / 2
  /// is dropped: every sample lies within T of the surface of its atom.
  double merge_tol = -1;
  /// Radius = exact distance from the centre to the mesh, so no ball leaves the object; clamped
  /// balls under 1e-2 of the diagonal that meet no other ball are dropped.
  bool clamp_radius = false;
  /// Also output the edges and triangles of the regular triangulation of the atoms (weights
  /// r^2) that lie inside the object (midpoint, resp. centroid, inside).
  bool connectivity = false;
};

struct SkeletonStats {
  std::size_t samples = 0;
  std::size_t duplicate_samples = 0;   ///< samples at the same point as an earlier one
  std::size_t hull_samples = 0;        ///< on the convex hull (incident to infinite cells)
  std::size_t skipped_samples = 0;     ///< no inside Voronoi vertex: no pole
  std::size_t cells = 0;               ///< finite Delaunay cells
  std::size_t exact_circumcentres = 0; ///< cells whose inexact circumcentre failed the check
  std::size_t rejected_cells = 0;      ///< circumcentre not representable (numerical only)
  std::size_t poles = 0;               ///< inner poles found
  std::size_t merged = 0;              ///< poles merged into another pole's atom
  std::size_t pruned = 0;              ///< atoms inside another ball (up to merge_tol)
  std::size_t dropped_small = 0;       ///< small isolated balls dropped after clamping
  std::size_t hidden_atoms = 0;        ///< atoms without a vertex in the regular triangulation
  std::size_t atoms = 0;
  double diagonal = 0, merge_tol = 0;  ///< model units
  double rmin = 0, rmax = 0;           ///< model units
  double worst_overshoot = 0;          ///< max of r - distance(centre, mesh), model units
  double seconds_delaunay = 0, seconds_poles = 0, seconds_merge = 0, seconds_clamp = 0,
         seconds_connectivity = 0;
};

struct Skeleton {
  MedialSurface atoms;
  std::vector<Eigen::Vector3d> samples;  ///< the samples used, model units
  std::vector<int> atom_of_sample;       ///< the atom each sample's pole became; -1: none
  SkeletonStats stats;
};

/// Inside tests and distances for a closed mesh (CGAL Side_of_triangle_mesh and AABB tree
/// over its triangles). Immutable after construction; queries are thread-safe.
class SolidQuery {
 public:
  /// @pre a closed mesh (polygons are fan-triangulated)
  explicit SolidQuery(const PolygonSoup& mesh);
  ~SolidQuery();
  SolidQuery(const SolidQuery&) = delete;
  SolidQuery& operator=(const SolidQuery&) = delete;
  /// Strictly inside the solid the mesh bounds.
  bool contains(const Eigen::Vector3d& p) const;
  /// Unsigned distance to the mesh, model units.
  double distance(const Eigen::Vector3d& p) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Inner poles of a closed mesh.
/// @param mesh  a closed, oriented 2-manifold (any polygons; they are fan-triangulated)
/// @param name  used in messages
/// @pre mesh closed, manifold, oriented, with at least 4 non-coplanar samples
/// @throws InvalidInput naming `name` and the problem (open, non-manifold, empty, flat)
Skeleton skeletonize(const PolygonSoup& mesh, const SkeletonOptions& opt, const std::string& name);

}  // namespace mg::skeletonize
