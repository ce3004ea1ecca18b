#pragma once
/// \file mesh_normals.h
/// Normals of a polygon soup computed from its faces alone (the soup need not be a manifold,
/// closed or consistently oriented mesh): the one implementation behind `render`'s shading and
/// `evaluate normals`' smooth reference.

#include "core/mesh.h"

#include <vector>

namespace mg {

/// How the faces around a vertex contribute to its normal.
enum class NormalWeighting {
  angle,  ///< by the face's interior angle at the vertex (Thuermer and Wuethrich 1998):
          ///< independent of how a flat region is triangulated
  area,   ///< by the face's area
};

/// Twice the vector area of a polygon (Newell's method): exact for planar polygons, robust for
/// non-planar ones, oriented by the vertex order. @pre indices in range
Eigen::Vector3d newell_vector(const PolygonSoup& soup, int face);

/// Unit normal of a polygon (Newell), or the zero vector for a degenerate face: one whose area
/// is negligible against its longest side (collinear corners give a rounding-noise direction
/// otherwise). @pre indices in range
Eigen::Vector3d face_normal(const PolygonSoup& soup, int face);

/// The weight of face `face`'s corner `corner` in its vertex's normal: its interior angle
/// (radians) or its face's area, and 0 for a degenerate face. `normal` is face_normal(face).
double corner_weight(const PolygonSoup& soup, int face, int corner, const Eigen::Vector3d& normal,
                     NormalWeighting weighting);

/// Vertex normals: per vertex, the weighted sum of the normals of its faces, in face order,
/// normalised; the zero vector where the sum vanishes (no face, only degenerate faces, or
/// opposite faces that cancel: norm <= 1e-12).
/// @pre the soup passes validate_soup   @throws InvalidInput otherwise
std::vector<Eigen::Vector3d> vertex_normals(const PolygonSoup& soup,
                                            NormalWeighting weighting = NormalWeighting::angle);

}  // namespace mg
