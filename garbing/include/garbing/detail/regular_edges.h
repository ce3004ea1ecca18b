#pragma once
/// \file detail/regular_edges.h
/// Internal (cone_pairs.cpp, and its test): the edges of the atoms' regular triangulation.

#include "core/medial_surface.h"

#include <array>
#include <vector>

namespace mg::garbing::detail {

/// Edges of the regular triangulation of the atoms (weights r^2), as pairs (i < j), sorted,
/// each once. Hidden atoms have no edge; of atoms with equal weighted points only the lowest
/// index takes part. Built and read in parallel; the same edges at any thread count.
/// @pre atoms valid
std::vector<std::array<int, 2>> regular_edges(const MedialSurface& atoms);

}  // namespace mg::garbing::detail
