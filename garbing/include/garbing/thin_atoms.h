#pragma once
/// \file thin_atoms.h
/// Thinning of dense atoms before G is built (`garb --tolerance`, docs/algorithm.md "Thinned
/// atoms"): the balls that a nearby kept ball contains up to a slack are left out, so that the
/// union of the balls moves by at most the slack and G is built from a number of atoms set by
/// the slack rather than by the input's density.

#include "core/medial_surface.h"

#include <cstddef>
#include <vector>

namespace mg::garbing {

/// What thin_atoms() did.
struct ThinStats {
  double slack = 0;         ///< model units
  std::size_t kept = 0;     ///< atoms kept
  std::size_t dropped = 0;  ///< atoms left out
  double seconds = 0;       ///< wall clock
};

/// The atoms less the balls that a nearby kept ball contains up to `slack`, greedily: the atoms
/// are visited in a fixed order (grid blocks of side 64 slack, or coarser when the atoms span
/// more than 2^24 grid cells of 8 slack, in Morton order; in a block, decreasing radius, ties by
/// index), and ball i goes when a ball kept before it with centre near c_i (those within
/// 4 slack, up to rounding, and perhaps farther ones) contains it up to the slack: |c_i - c_j|
/// + r_i <= r_j + slack. So every dropped ball has a kept container. Hence, U and U' the unions
/// of the given and the kept balls: U' is part of U, and every point of U lies within `slack`
/// of U' (their Hausdorff distance is at most `slack`, up to rounding). A ball inside a larger
/// one whose centre lies farther stays. slack 0 keeps every atom. The kept atoms keep their
/// order. The result depends on the atoms, their order (ties) and the slack, not on the thread
/// count (garb() passes them in Z-order: any permutation gives the same).
/// @param kept_index  if given, receives the input index of each kept atom
/// @pre atoms without edges or faces (a medial mesh's envelope is not a union of balls), radii
///      > 0 and finite, finite centres (validate()); slack >= 0 and finite
/// @throws InvalidInput if a precondition fails
MedialSurface thin_atoms(const MedialSurface& atoms, double slack, ThinStats* stats = nullptr,
                         std::vector<int>* kept_index = nullptr);

}  // namespace mg::garbing
