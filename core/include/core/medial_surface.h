#pragma once
/// \file medial_surface.h
/// The medial surface S: a set of medial atoms (spheres) with optional connectivity, and its
/// file formats. This is the one data type every module shares.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>
#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

namespace mg {

/// A medial atom: a ball. Model units; radius finite and >= 0: zero and tiny radii are valid
/// (MATFP's sharp-feature atoms have radius 1e-12, other tools write 0).
struct MedialAtom {
  Eigen::Vector3d centre;
  double radius;
};

/// A medial surface: atoms plus the optional edges and triangles of the `.ma` format.
/// Connectivity is kept as written: an edge listed twice or reversed, an edge that is also a
/// side of a face, and a face listed twice are all valid and all kept (the garbing de-duplicates
/// edges when it builds its cones); the writer writes what S holds.
struct MedialSurface {
  std::vector<MedialAtom> atoms;
  std::vector<std::array<int, 2>> edges;  ///< indices into atoms
  std::vector<std::array<int, 3>> faces;  ///< indices into atoms
};

/// Checks every documented precondition of S.
/// @pre at least one atom; centres finite; radii finite and >= 0 (negative, NaN and infinite
///      radii are refused); edge and face indices in range; an edge joins two distinct atoms
///      and a face three distinct atoms. Duplicate edges and faces are allowed.
/// @throws InvalidInput naming the first offending atom, edge or face (0-based index), e.g.
///         `atom 4: radius must be >= 0, got -0.3`, `edge 2: joins atom 3 to itself`,
///         `face 0: repeats atom 5`.
void validate(const MedialSurface& s);

/// The characteristic radius rc = (rmin + rmax) / 2 of the atoms (paper section 3.1): the
/// automatic octree depth makes leaves <= rc / 8. @pre s has atoms
/// @note rc is 0 when every radius is 0 (radii >= 0 are valid): callers dividing by it must check.
double characteristic_radius(const MedialSurface& s);

/// The Morton code (Z-order) of three integers' 21 low bits, x in the lowest bit of each triple.
std::uint64_t morton_code(std::uint64_t x, std::uint64_t y, std::uint64_t z);

/// S with its atoms in Z-order (Morton order) of their centres: the centres quantized to 2^21
/// steps per axis over the largest side of their bounding box, ties broken by centre, radius,
/// the signs of zeros, then index. Edges and faces are renumbered and kept in their order. Nearby
/// atoms get nearby indices, so code reading the balls of a region reads contiguous memory; and the
/// atoms of any permutation of S come out in the same order (identical atoms are interchangeable
/// unless edges or faces tell them apart).
/// @param old_index if not null, receives for each new atom its index in S
/// @pre S valid
MedialSurface spatially_sorted(const MedialSurface& s, std::vector<int>* old_index = nullptr);

/// Parses a medial surface from text. Two formats, told apart by the first significant line:
/// - `.ma` (Q-MAT and successors): a header `nv ne nf`, then `v x y z r`, `e i j`, `f i j k`
///   lines (0-based indices, any order of v/e/f lines). Each may end with any number of integer
///   fields (MATFP's `v x y z r TYPE FLAG`, feature flags `e i j FLAG`, `f i j k FLAG`): they
///   are checked to be integers and dropped. Anything else after the required fields is an error;
///   so are an edge joining an atom to itself and a face repeating an atom. Duplicate edges and
///   faces are kept (see MedialSurface);
/// - plain: one `x y z r` line per atom.
/// `#` starts a comment; blank lines are ignored. The result is validated.
/// @param in   the text
/// @param name used in messages: `name:line: problem`
/// @throws InvalidInput on any malformed line, count mismatch or invalid atom
MedialSurface parse_medial_surface(std::istream& in, const std::string& name);

/// Reads a medial surface file (see parse_medial_surface).
/// @throws IoError if the file cannot be opened; InvalidInput if it is malformed
MedialSurface read_medial_surface(const std::string& path);

/// Writes S in the `.ma` format with 17 significant digits (exact double round trip), every
/// edge and face as held (no flags, no de-duplication).
void format_medial_surface(std::ostream& out, const MedialSurface& s);

/// Writes S to `path` in the `.ma` format through a temporary file renamed at the end, so a
/// failure never leaves a partial file. @throws IoError
void write_medial_surface(const MedialSurface& s, const std::string& path);

}  // namespace mg
