#pragma once
/// \file vertex_normals.h
/// Shading normals of a polygon soup, computed from the faces alone: the soup need not be a
/// manifold, closed or even consistently oriented mesh (a render shows whatever a file holds).

#include "core/mesh.h"
#include "core/mesh_normals.h"

#include <vector>

namespace mg::render {

using mg::NormalWeighting;

/// Options of shading_normals().
struct NormalOptions {
  NormalWeighting weighting = NormalWeighting::angle;
  /// Crease angle, degrees in [0, 180]: a face's corner averages only the faces around the
  /// vertex whose normal is within this angle of its own. 180 = one normal per vertex (smooth
  /// everywhere), 0 = the face's own normal (flat).
  double crease_angle = 180.0;
};

/// Normals of a soup for smooth shading, per face corner.
struct ShadingNormals {
  /// Unit vectors. The first #V entries are the vertex normals (all faces around the vertex,
  /// whatever the crease angle); further entries are corner normals that differ from them.
  std::vector<Eigen::Vector3d> normals;
  /// corners[f][k]: index into `normals` of corner k of face f (same shape as soup.faces).
  std::vector<std::vector<int>> corners;
  /// True if corners[f][k] == soup.faces[f][k] everywhere: the vertex normals suffice.
  bool per_vertex = true;
};

/// Shading normals of every face corner of `soup`.
/// A vertex whose weighted sum vanishes (no face, only degenerate faces, or opposite faces that
/// cancel) gets the normal of its first non-degenerate face, or +z; a corner whose sum vanishes
/// gets its face's normal, so every returned vector has unit length.
/// Face and vertex normals and corner weights are mg's (mesh_normals.h).
/// @pre the soup passes validate_soup (as read_polygon_soup guarantees); opt.crease_angle in
///      [0, 180]
/// @throws InvalidInput if the crease angle is outside [0, 180] or the soup is invalid
ShadingNormals shading_normals(const PolygonSoup& soup, const NormalOptions& opt = {});

}  // namespace mg::render
