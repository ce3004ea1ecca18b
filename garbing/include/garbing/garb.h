#pragma once
/// \file garb.h
/// The garbing as one call (docs/algorithm.md): the target shape G, then the paper's three
/// steps (octree, coarse mesh M1, refined mesh M2). Used by the `garb` program; each stage is
/// also callable on its own (target_shape.h, octree.h, coarse_mesh.h, refine_mesh.h).

#include "garbing/coarse_mesh.h"
#include "garbing/octree.h"
#include "garbing/refine_mesh.h"
#include "garbing/target_shape.h"

namespace mg::garbing {

/// Options of every stage.
struct GarbOptions {
  ConeOptions cones;     ///< which cones G has with PrimitiveSet::atoms (its balls are the atoms)
  OctreeOptions octree;  ///< step 1
  RefineOptions refine;  ///< step 3
  /// Which primitives G has: a medial mesh's envelope, or the atoms' balls and cones.
  PrimitiveSet primitives = PrimitiveSet::automatic;
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
};

/// Garbs the atoms: with S = spatially_sorted(atoms), G = make_target_shape(S, opt.primitives,
/// opt.cones, bounding_cube_frame(S)), then
/// T = build_octree(G), M1 = extract_coarse_mesh(T), M2 = refine_mesh(M1, T, G). The result
/// is the same at any thread count and for the atoms in any order (atoms with equal centre and
/// radius but different edges or faces aside).
/// @pre options as each stage documents
/// @throws InvalidInput if the atoms are invalid (validate(); messages name the caller's
///         indices) or the stages refuse them
Garbing garb(const MedialSurface& atoms, const GarbOptions& opt = {});

}  // namespace mg::garbing
