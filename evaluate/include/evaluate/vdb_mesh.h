#pragma once
/// \file vdb_mesh.h
/// The OpenVDB baseline (`evaluate vdb`): a narrow-band level set meshed at the zero level
/// (volumeToMesh, adaptivity 0), quads split along their shorter diagonal, faces turned outward
/// (OpenVDB's come out inward). The level set is the atoms' spheres rasterised
/// (ParticlesToLevelSet, CSG union), or, for a medial mesh, the signed distance of its envelope
/// G (balls, cones, slabs: target_shape.h) sampled at the voxels near G. Plus the voxel searches
/// that match a vertex count, a Hausdorff distance to a reference mesh, or one to G itself.

#include "core/medial_surface.h"
#include "core/mesh.h"
#include "evaluate/atoms_distance.h"
#include "evaluate/mesh_distance.h"
#include "garbing/target_shape.h"

#include <cstddef>
#include <vector>

namespace mg::evaluate {

struct VdbOptions {
  /// Voxel size, model units; 0 = spheres_bbox_diagonal(atoms) / 400.
  double voxel = 0;
  /// Narrow-band half-width, voxels (OpenVDB's default).
  double half_width = 3;
  /// What is meshed: `atoms` ("rt") the spheres alone, rasterised (edges and faces ignored);
  /// `envelope` ("ma") G of the edges and faces, its signed distance sampled; automatic:
  /// envelope when the atoms have edges or faces (garbing::resolve).
  garbing::PrimitiveSet primitives = garbing::PrimitiveSet::automatic;
};

struct VdbMesh {
  PolygonSoup mesh;  ///< closed triangle mesh, faces CCW from outside
  double voxel = 0;  ///< the voxel size used, model units
  /// Spheres OpenVDB skipped because their radius is below its minimum of 1.5 voxels (counted
  /// here: OpenVDB's own counter is racy with more than one thread). They are absent from the
  /// mesh.
  std::size_t dropped_spheres = 0;
  std::size_t quads = 0;   ///< quads from volumeToMesh (each split in two)
  bool envelope = false;   ///< G's signed distance was sampled (the envelope), not the spheres
  std::size_t cones = 0;   ///< G's cones (envelope only)
  std::size_t slabs = 0;   ///< G's slabs (envelope only)
  std::size_t leaves = 0;  ///< envelope only: 8^3-voxel leaves sampled (with a voxel in the band)
};

/// Length of the diagonal of the spheres' bounding box (centres +- radii), model units.
double spheres_bbox_diagonal(const MedialSurface& atoms);

/// The level set of opt.primitives (resolved on the atoms), meshed. The spheres' path is
/// OpenVDB's rasteriser; the envelope's is vdb_mesh(make_target_shape(atoms, envelope, {}), opt).
/// @pre atoms valid; voxel >= 0 and finite; half_width >= 1; at most 2^31 voxels along an axis
/// @throws InvalidInput (also when every sphere is under 1.5 voxels, or the mesh is empty)
VdbMesh vdb_mesh(const MedialSurface& atoms, const VdbOptions& opt = {});

/// The envelope's path on a G built once (opt.primitives unused): every voxel within
/// half_width voxels of G gets min over the primitives near it of their signed distances (ball
/// |p - c| - r, hull_distance, slab_distance: exact outside G, inside negative and at most the
/// depth), the rest of the grid -/+ half_width by signedFloodFill; voxel 0 = diagonal of the
/// balls' box / 400. Voxel (i, j, k) sits at (i, j, k) * voxel, model units. Parallel (TBB)
/// over 8^3-voxel leaves, each written apart: the same mesh at any thread count.
/// @pre g in world coordinates (g.frame().is_world()); voxel, half_width as above
/// @throws InvalidInput
VdbMesh vdb_mesh(const garbing::TargetShape& g, const VdbOptions& opt);

/// One voxel size tried by a search.
struct VdbProbe {
  double voxel = 0;  ///< model units
  double value = 0;  ///< the matched quantity: vertices, or a Hausdorff distance in %
  std::size_t vertices = 0;
};

struct VdbMatch {
  VdbMesh best;                  ///< the probe closest to the target (in log ratio)
  double value = 0;              ///< its matched quantity
  std::vector<VdbProbe> probes;  ///< in the order tried
  bool clamped = false;          ///< a probe hit the voxel range [diag / 2000, diag / 20]
  /// vdb_match_envelope only: the search stopped early, a step of 25% or more in h having left
  /// the measure (nearly) unmoved on the same side of the target, a floor or ceiling out of
  /// the voxel's reach.
  bool out_of_reach = false;
};

/// Searches the voxel size whose mesh has about `vertices` vertices: at most `max_probes`
/// probes, stopping within 1%. Starts at the default voxel, then a safeguarded secant in
/// log-log space (V ~ h^-2 until two probes give a slope; once the target is bracketed, the
/// secant through the closest probe on either side, or bisection in log h when that nearly
/// repeats one). `primitives` as VdbOptions's (an envelope's G is built once for all probes).
/// @pre vertices >= 1; 1 <= max_probes <= 20   @throws InvalidInput
VdbMatch vdb_match_vertices(const MedialSurface& atoms, std::size_t vertices, int max_probes = 5,
                            garbing::PrimitiveSet primitives = garbing::PrimitiveSet::automatic);

/// The same search for a two-sided Hausdorff distance to `reference` of `percent` % of the
/// reference's bounding-box diagonal (H ~ h to start). Distances as mesh_distance(mesh, reference,
/// distance), except that a non-zero sample count is raised to twice the larger point count of
/// the two meshes when Metro sampling needs it (it takes every vertex).
/// @pre percent > 0; 1 <= max_probes <= 20   @throws InvalidInput
VdbMatch vdb_match_hausdorff(const MedialSurface& atoms, double percent,
                             const PolygonSoup& reference, const MeshDistanceOptions& distance,
                             const std::string& reference_name, int max_probes = 5,
                             garbing::PrimitiveSet primitives = garbing::PrimitiveSet::automatic);

/// The same search for a two-sided Hausdorff distance between the mesh and G itself of
/// `percent` % of `diagonal` (H ~ h to start), e.g. a garbing's distance to G from `evaluate
/// atoms`: the voxel at which OpenVDB comes as close to G. What is meshed is distance.primitives
/// (as VdbOptions's); G is what atoms_distance(mesh, atoms, distance) measures against: the
/// envelope (one G, built once, both meshed and measured against), or on the spheres' path the
/// balls and the cones distance.cones chooses (`evaluate atoms --primitives rt`; the mesh stays the
/// spheres alone, so H stays above the cones' reach outside the balls, and a smaller target ends
/// clamped or out_of_reach). Unlike the two searches above, it stops as out_of_reach when a step
/// of 25% or more in h toward the target moves H less than a tenth of the model's prediction.
/// Distances as atoms_distance(mesh, G, distance) (samples 0 = max(1e5, 10 V_mesh); a non-zero
/// count is raised to twice the mesh's vertex count when below it), G built once for all probes.
/// @param diagonal  for the percentages, model units; 0 = spheres_bbox_diagonal(atoms), the
///                  same at every probe (the mesh's own box changes with the voxel)
/// @pre percent > 0; diagonal >= 0; both finite; 1 <= max_probes <= 20   @throws InvalidInput
VdbMatch vdb_match_envelope(const MedialSurface& atoms, double percent, double diagonal = 0,
                            const AtomsDistanceOptions& distance = {}, int max_probes = 5);

}  // namespace mg::evaluate
