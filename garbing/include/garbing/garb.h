#pragma once
/// \file garb.h
/// The garbing as one call (docs/algorithm.md): the target shape G, then the paper's three
/// steps (octree, coarse mesh M1, refined mesh M2). Used by the `garb` program; each stage is
/// also callable on its own (target_shape.h, octree.h, coarse_mesh.h, refine_mesh.h).

#include "garbing/coarse_mesh.h"
#include "garbing/octree.h"
#include "garbing/refine_mesh.h"
#include "garbing/target_shape.h"
#include "garbing/thin_atoms.h"

namespace mg::garbing {

/// Options of every stage.
struct GarbOptions {
  ConeOptions cones;     ///< which cones G has with PrimitiveSet::atoms (its balls are the atoms)
  OctreeOptions octree;  ///< step 1
  RefineOptions refine;  ///< step 3
  /// Which primitives G has: a medial mesh's envelope, or the atoms' balls and cones.
  PrimitiveSet primitives = PrimitiveSet::automatic;
  /// Thinning of dense atoms (thin_atoms.h), in leaf sides at the minimal depth d: before G is
  /// built, balls are left out by `thinning` with slack tolerance * side(d) (the union of the
  /// balls moves by at most that much), and d stays the given atoms' (the output's resolution
  /// does not change). rc, the cone collar's unit and the octree's reported rc, is the kept
  /// atoms'. 0: every atom, G exact. Atoms' G only (not an envelope). @pre >= 0 and finite
  double tolerance = 0;
  /// How (with tolerance > 0): cover (thin_atoms_by_cover(): the kept count is set by the
  /// tolerance) or contain (thin_atoms(): fewer balls left out, the same bound).
  ThinMethod thinning = ThinMethod::cover;
};

/// Wall-clock seconds of each stage.
struct GarbSeconds {
  double target_shape = 0;  ///< choosing the cones (and slabs), building G's hierarchy
  double octree = 0, m1 = 0, m2 = 0;
  double total() const { return target_shape + octree + m1 + m2; }
};

/// The process's peak resident memory (MB of 2^20 bytes, getrusage's high-water mark) at the
/// end of each stage: where the peak is reached. Process-wide: it includes what the caller held
/// before.
struct GarbMemory {
  double target_shape = 0, octree = 0, m1 = 0, m2 = 0;
};

/// Every stage's result, in the order they are computed.
struct Garbing {
  TargetShape g;   ///< in the atoms' bounding cube frame; its balls in Z-order (spatially_sorted)
  Octree tree;     ///< step 1
  CoarseMesh m1;   ///< step 2, world coordinates
  RefinedMesh m2;  ///< step 3, world coordinates, with its statistics
  GarbSeconds seconds;
  GarbMemory peak_mb;
  ThinStats thinning;  ///< opt.tolerance > 0 only (its seconds are part of seconds.target_shape)
};

/// Garbs the atoms: with S = spatially_sorted(atoms), G = make_target_shape(S, opt.primitives,
/// opt.cones, bounding_cube_frame(S)), then
/// T = build_octree(G), M1 = extract_coarse_mesh(T), M2 = refine_mesh(M1, T, G). With
/// opt.tolerance > 0, G is built from thin_atoms_by_cover(S, tolerance * side(d)) (or
/// thin_atoms(), opt.thinning) in the same frame, d
/// the minimal depth of S (opt.octree.min_depth, or automatic_min_depth of S's frame and rc),
/// and the octree is given that d (S's edges and faces, unused by G then, are left out). The result
/// is the same at any thread count and for the atoms in any order (atoms with equal centre and
/// radius but different edges or faces aside).
/// @pre options as each stage documents
/// @throws InvalidInput if the atoms are invalid (validate(); messages name the caller's
///         indices) or the stages refuse them, or opt.tolerance is negative, not finite, or
///         given for an envelope or with the cones of the file's edges
Garbing garb(const MedialSurface& atoms, const GarbOptions& opt = {});

}  // namespace mg::garbing
