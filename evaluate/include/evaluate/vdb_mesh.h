#pragma once
/// \file vdb_mesh.h
/// The OpenVDB baseline (`evaluate vdb`): the atoms' spheres rasterised into a narrow-band level
/// set (ParticlesToLevelSet, CSG union) and meshed at the zero level (volumeToMesh, adaptivity
/// 0), quads split along their shorter diagonal, faces turned outward (OpenVDB's come out
/// inward). Plus the voxel searches that match a vertex count or a Hausdorff distance.

#include "core/medial_surface.h"
#include "core/mesh.h"
#include "evaluate/mesh_distance.h"

#include <cstddef>
#include <vector>

namespace mg::evaluate {

struct VdbOptions {
  /// Voxel size, model units; 0 = spheres_bbox_diagonal(atoms) / 400.
  double voxel = 0;
  /// Narrow-band half-width, voxels (OpenVDB's default).
  double half_width = 3;
};

struct VdbMesh {
  PolygonSoup mesh;  ///< closed triangle mesh, faces CCW from outside
  double voxel = 0;  ///< the voxel size used, model units
  /// Spheres OpenVDB skipped because their radius is below its minimum of 1.5 voxels (counted
  /// here: OpenVDB's own counter is racy with more than one thread). They are absent from the
  /// mesh.
  std::size_t dropped_spheres = 0;
  std::size_t quads = 0;  ///< quads from volumeToMesh (each split in two)
};

/// Length of the diagonal of the spheres' bounding box (centres +- radii), model units.
double spheres_bbox_diagonal(const MedialSurface& atoms);

/// @pre atoms valid; voxel >= 0 and finite; half_width >= 1; at most 2^31 voxels along an axis
/// @throws InvalidInput (also when every sphere is under 1.5 voxels: nothing to mesh)
VdbMesh vdb_mesh(const MedialSurface& atoms, const VdbOptions& opt = {});

/// One voxel size tried by a search.
struct VdbProbe {
  double voxel = 0;  ///< model units
  double value = 0;  ///< the matched quantity: vertices, or Hausdorff in %
  std::size_t vertices = 0;
};

struct VdbMatch {
  VdbMesh best;                  ///< the probe closest to the target (in log ratio)
  double value = 0;              ///< its matched quantity
  std::vector<VdbProbe> probes;  ///< in the order tried
  bool clamped = false;          ///< a probe hit the voxel range [diag / 2000, diag / 20]
};

/// Searches the voxel size whose mesh has about `vertices` vertices: at most `max_probes`
/// probes, stopping within 1%. Starts at the default voxel, then a safeguarded secant in
/// log-log space (V ~ h^-2 until two probes give a slope; bisection in log h once the target
/// is bracketed and the secant step leaves the bracket).
/// @pre vertices >= 1; 1 <= max_probes <= 20   @throws InvalidInput
VdbMatch vdb_match_vertices(const MedialSurface& atoms, std::size_t vertices, int max_probes = 5);

/// The same search for a two-sided Hausdorff distance to `reference` of `percent` % of the
/// reference's bounding-box diagonal (H ~ h to start). Distances as mesh_distance(mesh, reference,
/// distance), except that a non-zero sample count is raised to twice the larger point count of
/// the two meshes when Metro sampling needs it (it takes every vertex).
/// @pre percent > 0; 1 <= max_probes <= 20   @throws InvalidInput
VdbMatch vdb_match_hausdorff(const MedialSurface& atoms, double percent,
                             const PolygonSoup& reference, const MeshDistanceOptions& distance,
                             const std::string& reference_name, int max_probes = 5);

}  // namespace mg::evaluate
