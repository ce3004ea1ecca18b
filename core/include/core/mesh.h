#pragma once
/// \file mesh.h
/// The project's two mesh representations: an indexed polygon soup (what files hold, what
/// checks read) and an OpenMesh half-edge mesh in double precision (what algorithms edit).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include <array>
#include <cstddef>
#include <string>
#include <vector>

namespace mg {

/// OpenMesh's defaults store floats; every 1e-9 check downstream needs doubles.
struct MeshTraits : OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
};

/// Half-edge polygon mesh, double precision. Faces CCW seen from outside.
using Mesh = OpenMesh::PolyMesh_ArrayKernelT<MeshTraits>;

/// Indexed face list, exactly as a file holds it: no face is ever dropped or merged.
struct PolygonSoup {
  std::vector<Eigen::Vector3d> points;  ///< model units
  std::vector<std::vector<int>> faces;  ///< 0-based indices into points, 3+ per face
};

/// Checks what every reader and algorithm assumes of a soup: finite points, and faces of 3 or
/// more distinct in-range indices.
/// @param name used in messages
/// @throws InvalidInput naming `name` and the first offending vertex or face, e.g.
///         `name: vertex 3 has a non-finite coordinate`, `name: face 2 has 2 vertices (3 or
///         more needed)`, `name: face 2: vertex index 8 out of range [0, 8)`, `name: face 2
///         repeats vertex 5`
void validate_soup(const PolygonSoup& soup, const std::string& name);

/// The triangles of a polygon soup: each polygon fanned from its first corner.
struct Triangles {
  std::vector<std::array<int, 3>> corners;  ///< indices into the soup's points
  std::vector<std::size_t> face;            ///< the soup face each triangle comes from
  /// Where in its face: the triangle joins the face's corners 0, fan and fan + 1 (fan >= 1).
  std::vector<int> fan;
};

/// Fans every face of the soup (triangles are kept as they are, in order): polygon
/// (v0, v1, ..., vk) gives (v0, v1, v2), (v0, v2, v3), ...
Triangles fan_triangles(const PolygonSoup& soup);

/// The soup of a half-edge mesh (vertex and face order kept).
PolygonSoup soup_from_mesh(const Mesh& mesh);

/// Builds a half-edge mesh from a soup.
/// @param name used in messages
/// @pre validate_soup passes; every edge is used by at most two faces, in opposite directions;
///      every vertex has one fan of faces.
/// @throws InvalidInput naming the first offending face, edge or vertex
Mesh mesh_from_soup(const PolygonSoup& soup, const std::string& name);

/// Builds a half-edge mesh from a soup the caller constructed as an oriented 2-manifold
/// (M1, M2): no analysis beyond what adding each face checks.
/// @throws TopologyError naming the first face the half-edge mesh refuses
Mesh mesh_from_manifold_soup(const PolygonSoup& soup, const std::string& name);

/// Length of the diagonal of the axis-aligned bounding box of `points` (0 if empty).
double bbox_diagonal(const std::vector<Eigen::Vector3d>& points);

}  // namespace mg
