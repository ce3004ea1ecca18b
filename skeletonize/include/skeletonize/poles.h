#pragma once
/// \file poles.h
/// Medial atoms from a closed mesh: the inner Voronoi poles of surface samples (the power shape
/// of Amenta, Choi and Kolluri 2001, as the paper's section 4). See docs/algorithm.md
/// "Skeletonization".

#include "core/medial_surface.h"
#include "core/mesh.h"
#include "skeletonize/solid_query.h"
#include "skeletonize/union_topology.h"

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace mg::skeletonize {

struct SkeletonOptions {
  bool edge_midpoints = false;     ///< add the midpoint of every edge to the samples
  std::size_t random_samples = 0;  ///< add this many area-uniform random points on the faces
  std::uint64_t seed = 1;          ///< of the random samples (counter-based: reproducible)
  /// Merge tolerance T, model units (negative: 1e-3 of the mesh's bounding-box diagonal).
  /// Poles within T / 2 of a larger pole join its atom, and a ball inside another kept ball up
  /// to T / 2 is dropped: every sample then lies within T of the surface of its atom.
  double merge_tol = -1;
  /// Radius = exact distance from the centre to the mesh (AABB tree), so no ball leaves the
  /// object. Clamping can cut small balls off the rest (see isolated_fraction).
  bool clamp_radius = false;
  /// With clamp_radius: a group of clamped balls that meets no other ball (a component of their
  /// union) and whose largest ball is under this fraction of the bounding-box diagonal is
  /// dropped, unless it holds the largest ball. 0: keep every ball.
  double isolated_fraction = 1e-2;
  /// Also output the edges and triangles of the regular triangulation of the atoms (weights
  /// r^2) that lie inside the object (the closed segment or triangle meets no mesh face and its
  /// midpoint, resp. centroid, is inside).
  bool connectivity = false;
};

struct SkeletonStats {
  std::size_t samples = 0;              ///< vertices + midpoints + random points
  std::size_t duplicate_samples = 0;    ///< at the same point as another sample (one is kept)
  std::size_t hull_samples = 0;         ///< on the convex hull (incident to infinite cells)
  std::size_t skipped_samples = 0;      ///< no Voronoi vertex inside the object: no pole
  std::size_t cells = 0;                ///< finite Delaunay cells
  std::size_t exact_circumcentres = 0;  ///< cells whose interval circumcentre was too wide
  std::size_t rejected_cells = 0;       ///< exact circumcentre not a finite double (numerical only)
  std::size_t poles = 0;                ///< inner poles found (one per distinct sample at most)
  std::size_t merged = 0;               ///< poles merged into another pole's atom
  std::size_t pruned = 0;               ///< atoms inside another ball (up to merge_tol / 2)
  std::size_t dropped_small = 0;        ///< balls of small isolated groups dropped after clamping
  std::size_t hidden_atoms = 0;         ///< atoms without a vertex in the regular triangulation
                                        ///< (computed with opt.connectivity only)
  std::size_t atoms = 0;
  double diagonal = 0, merge_tol = 0;  ///< model units
  double rmin = 0, rmax = 0;           ///< of the output atoms, model units
  double pole_overshoot = 0;           ///< max of r - distance(centre, mesh) before clamping
  double worst_overshoot = 0;          ///< the same for the output atoms (0 when clamped)
  double seconds_setup = 0, seconds_delaunay = 0, seconds_poles = 0, seconds_merge = 0,
         seconds_distances = 0, seconds_connectivity = 0;
};

struct Skeleton {
  MedialSurface atoms;
  std::vector<Eigen::Vector3d> samples;  ///< the samples used, model units
  std::vector<int> atom_of_sample;       ///< the atom each sample's pole became; -1: none
  /// With opt.connectivity: the regular triangulation's tetrahedra whose four triangles are all
  /// kept (inside the object), sorted (i < j < k < l). Not written to `.ma` files; they fill the
  /// complex the simplification (simplify.h) works on.
  std::vector<std::array<int, 4>> cells;
  /// With opt.connectivity: the union's dual complex of `atoms` (union_complex(atoms)), from the
  /// same regular triangulation as the connectivity; its topology is union_topology(atoms).
  std::optional<UnionComplex> union_complex;
  SkeletonStats stats;
};

/// Inner poles of a closed mesh. Output is identical at any thread count and for any vertex or
/// face order (except for random samples, drawn face by face): atoms by decreasing pole radius
/// (ties by sample position), connectivity sorted.
/// @param mesh  a closed, oriented 2-manifold (any polygons; they are fan-triangulated)
/// @param name  used in messages
/// @pre mesh non-empty, finite coordinates, indices in range, closed, manifold, oriented, with
///      at least 4 non-coplanar samples; opt.merge_tol finite; opt.isolated_fraction >= 0
/// @throws InvalidInput naming `name` and the problem (open, non-manifold, empty, flat, ...)
Skeleton skeletonize(const PolygonSoup& mesh, const SkeletonOptions& opt, const std::string& name);

}  // namespace mg::skeletonize
