#pragma once
/// \file mesh_io.h
/// Mesh files: OFF, OBJ, PLY and STL, chosen by the file extension (case-insensitive).
/// Readers never drop a face: they read the face list first; writers keep 17 significant digits.

#include "core/mesh.h"

#include <iosfwd>
#include <string>
#include <vector>

namespace mg {

/// Reads the face list of a mesh file. OFF (also COFF/NOFF headers, colours ignored) is parsed
/// here with line numbers in messages; OBJ, PLY and STL go through CGAL's polygon-soup readers
/// (STL points are merged by exact coordinates). A PLY file is checked first, header and body:
/// known types, and every count within what the rest of the file can hold.
/// @throws IoError if the file cannot be opened; InvalidInput if it is malformed, has an
///         unknown extension, an index out of range, a face with fewer than 3 or repeated
///         indices, a non-finite coordinate, or no face at all
PolygonSoup read_polygon_soup(const std::string& path);

/// read_polygon_soup() then mesh_from_soup(): refuses non-manifold input, naming the element.
Mesh read_mesh(const std::string& path);

/// Formats a soup as the file `path` (by its extension): ASCII, 17 significant digits (doubles
/// round-trip exactly). STL holds triangles only: polygons are fan-triangulated.
/// @param out  a stream opened in binary mode
/// @throws InvalidInput for an unknown extension
void format_polygon_soup(std::ostream& out, const PolygonSoup& soup, const std::string& path);

/// Writes a soup (format_polygon_soup) through a temporary file renamed at the end.
/// @throws InvalidInput for an unknown extension; IoError if writing fails
void write_polygon_soup(const PolygonSoup& soup, const std::string& path);

/// write_polygon_soup() of the mesh's soup (vertex and face order kept).
void write_mesh(const Mesh& mesh, const std::string& path);

/// The extension of a file name, with its dot, in lower case ("" if none): "A/b.OFF" -> ".off".
std::string file_extension(const std::string& path);

/// True if `path` ends in .off, .obj, .ply or .stl (any case).
bool has_mesh_extension(const std::string& path);

/// check_output_path() for a mesh file, which must also have a mesh extension.
/// @throws InvalidInput
void check_mesh_output_path(const std::string& output, const std::vector<std::string>& inputs);

}  // namespace mg
