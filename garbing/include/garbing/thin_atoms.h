#pragma once
/// \file thin_atoms.h
/// Thinning of dense atoms before G is built (`garb --tolerance`, docs/algorithm.md "Thinned
/// atoms"): balls are left out so that the union of the balls moves by at most a slack. Two
/// methods: `contain` leaves out the balls that one nearby kept ball contains up to the slack
/// (the kept count still grows with the input's density); `cover` also leaves out the balls
/// that the union of nearby kept balls covers, so that the kept count is set by the slack and
/// the shape, not by the input's density.

#include "core/medial_surface.h"

#include <cstddef>
#include <vector>

namespace mg::garbing {

/// How atoms are thinned.
enum class ThinMethod {
  contain,  ///< thin_atoms(): a ball goes when one kept ball contains it up to the slack
  cover,    ///< thin_atoms_by_cover(): ... or when the union of kept balls covers it
};

/// What thin_atoms() or thin_atoms_by_cover() did.
struct ThinStats {
  double slack = 0;         ///< model units
  std::size_t kept = 0;     ///< atoms kept
  std::size_t dropped = 0;  ///< atoms left out
  std::size_t covered = 0;  ///< of those, left out by the cover pass (thin_atoms_by_cover())
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

/// Whether the balls `others`, each grown by `slack`, cover `ball`, proved through those whose
/// grown ball holds the centre c of `ball`: their grown balls meet the sphere S of `ball` in
/// caps; the caps cover S if every point of each cap's circle lies inside another cap (the
/// uncovered part, were it not empty, would be bounded by such points), tested exactly on
/// arcs (each shrunk by 1e-9 of a diamond angle, about 1e-9 radian; caps within 1e-12 of
/// another and circles nearly coaxial with another, whose arcs rounding would decide, left
/// out); then every segment from c to S lies in one grown ball (convex, holding both ends), so
/// the ball is covered. A ball one grown ball contains is covered. Sound up to the rounding of
/// the caps (an angle of about 1e-16 r / |c - c_j|), not complete: a ball covered only with
/// the help of balls that do not hold c is not found covered.
/// @pre radii > 0, slack >= 0, finite numbers
bool union_covers_ball(const MedialAtom& ball, const std::vector<MedialAtom>& others, double slack);

/// thin_atoms(atoms, slack / 2), then a cover pass at slack / 2 over the atoms it kept, in the
/// same kind of order (blocks of a grid of side h = sqrt(2 rc slack / 2) in Morton order, rc =
/// characteristic_radius() of those atoms, in a block by decreasing radius, ties by index):
/// first, greedily, every atom with no kept centre within sqrt(2 r slack / 2) of its own (r its
/// radius: the distance at which a neighbour of equal radius still covers the poles of its
/// sphere) among the 3 x 3 x 3 cells around it is kept (a seed); then each other atom goes when
/// union_covers_ball() proves that the kept atoms with centres in those cells cover it up to
/// slack / 2, and is kept otherwise. Every ball left out lies within `slack` of the union of
/// the kept balls (within slack / 2 of a ball that lies within slack / 2 of it), and the kept
/// balls are given ones: the unions' Hausdorff distance is at most `slack` (up to rounding).
/// The kept count is about the medial surface's area / (r slack) once the atoms are denser
/// than that, whatever their density. Deterministic as thin_atoms() (no dependence on the
/// thread count).
/// @param stats  slack, kept and dropped as thin_atoms(); covered: dropped by the cover pass
/// @param kept_index  if given, receives the input index of each kept atom
/// @pre as thin_atoms()
/// @throws InvalidInput if a precondition fails
MedialSurface thin_atoms_by_cover(const MedialSurface& atoms, double slack,
                                  ThinStats* stats = nullptr,
                                  std::vector<int>* kept_index = nullptr);

}  // namespace mg::garbing
