#pragma once
/// \file baselines.h
/// The CGAL baselines the paper compares with (Tables 1 and 2), on the same atoms: the skin
/// surface and the union of balls. Each returns the mesh; time it with time_stage() (timing.h)
/// to get the algorithm's own wall time without file input/output.

#include "core/medial_surface.h"
#include "core/mesh.h"

namespace mg::evaluate {

struct SkinOptions {
  /// Shrink factor s of the skin surface, in (0, 1). Balls are grown first (CGAL's grow_balls):
  /// a lone atom's skin is its sphere.
  double shrink = 0.5;
  int subdivisions = 0;  ///< CGAL's refinement rounds after meshing, >= 0
};

/// CGAL make_skin_surface_mesh_3 of the atoms (weights r^2, through the one conversion).
/// @pre atoms valid; 0 < shrink < 1 (CGAL silently turns shrink >= 1 into the union of balls:
///      refused here, see union_of_balls_mesh); subdivisions >= 0
/// @throws InvalidInput
/// @post a closed triangle mesh, faces CCW from outside
PolygonSoup skin_surface_mesh(const MedialSurface& atoms, const SkinOptions& opt = {});

/// CGAL Union_of_balls_3 + mesh_union_of_balls_3 (+ subdivide_union_of_balls_mesh_3).
/// @pre atoms valid; subdivisions >= 0   @throws InvalidInput
/// @post a closed triangle mesh, faces CCW from outside (it may self-intersect: check_mesh)
PolygonSoup union_of_balls_mesh(const MedialSurface& atoms, int subdivisions = 0);

}  // namespace mg::evaluate
