#pragma once
/// \file detail/regular_edges.h
/// Internal (cone_pairs.cpp, and its test): the edges of the atoms' regular triangulation.

#include "core/medial_surface.h"

#include <array>
#include <cstddef>
#include <vector>

namespace mg::garbing::detail {

/// The default of regular_edges' bucket_entries: 2^23 entries (32 MB).
constexpr std::size_t kRegularEdgeBucket = std::size_t(1) << 23;

/// Edges of the regular triangulation of the atoms (weights r^2), as pairs (i < j), sorted,
/// each once. Hidden atoms have no edge; of atoms with equal weighted points only the lowest
/// index takes part. The cells' edges are gathered by ranges of lower atoms holding at most
/// `bucket_entries` entries at a time (a pass over the cells per range; at least one atom per
/// range): the result does not depend on it. @pre atoms valid, bucket_entries >= 1
std::vector<std::array<int, 2>> regular_edges(const MedialSurface& atoms,
                                              std::size_t bucket_entries = kRegularEdgeBucket);

}  // namespace mg::garbing::detail
