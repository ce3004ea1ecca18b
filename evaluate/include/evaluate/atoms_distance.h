#pragma once
/// \file atoms_distance.h
/// Distances between a mesh and the target shape G of its atoms (`evaluate atoms`): the union
/// of the atoms' spheres and cones (or a medial mesh's envelope: balls, cones and slabs), whose
/// boundary the garbing aims at. This judges a mesher
/// apart from the atoms' own error (the distance from G to the original object).

#include "core/medial_surface.h"
#include "evaluate/distances.h"
#include "garbing/target_shape.h"

namespace mg::evaluate {

struct AtomsDistanceOptions {
  /// G's primitives (as `garb --primitives`): a medial mesh's envelope, or balls and cones.
  garbing::PrimitiveSet primitives = garbing::PrimitiveSet::automatic;
  garbing::ConeOptions cones;  ///< which cones join the spheres in G (as `garb --cones`)
  std::size_t samples = 0;     ///< per side; 0 = max(1e5, 10 V_mesh)
  std::uint64_t seed = 1;
};

struct AtomsDistance {
  TwoSidedDistance distance;  ///< a_to_b = mesh to G, b_to_a = G to mesh
  double diagonal = 0;        ///< the mesh's bounding-box diagonal, model units
  std::size_t mesh_samples = 0;
  std::size_t g_samples = 0;   ///< all samples of G
  std::size_t g_unbiased = 0;  ///< of which area-uniform (the rest: G's points nearest the mesh)
  std::size_t cones = 0;
  std::size_t slabs = 0;
  bool envelope = false;  ///< G was the medial mesh's envelope
};

/// Metro sampling of the mesh against exact point-to-G distances (TargetShape::distance:
/// exact outside the union, an upper bound at creases with cones inside); samples of G against
/// the mesh (AABB tree): area-uniform ones (TargetShape::sample_boundary, weight 1) and the
/// points of G nearest to up to 20,000 mesh samples (weight 0: they only sharpen the maximum).
/// @pre mesh with positive area; atoms valid   @throws InvalidInput naming `name`
AtomsDistance atoms_distance(const PolygonSoup& mesh, const MedialSurface& atoms,
                             const AtomsDistanceOptions& opt, const std::string& name);

/// The same measure against a G built once by the caller (a search measuring many meshes
/// against one G): only opt.samples and opt.seed are read; cones and slabs are the shape's
/// counts, and `envelope` is false (a TargetShape does not record what it was built from: the
/// overload above sets it).
/// @pre mesh with positive area; shape in world coordinates (shape.frame().is_world())
/// @throws InvalidInput naming `name`, or G's frame
AtomsDistance atoms_distance(const PolygonSoup& mesh, const garbing::TargetShape& shape,
                             const AtomsDistanceOptions& opt, const std::string& name);

}  // namespace mg::evaluate
