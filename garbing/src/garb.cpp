#include "garbing/garb.h"

#include "core/timer.h"

#include <utility>

namespace mg::garbing {

Garbing garb(const MedialSurface& atoms, const GarbOptions& opt) {
  GarbSeconds seconds;
  GarbMemory peak;
  Stopwatch clock;
  // G: the union of the atoms' balls and of the chosen cones (or of the medial mesh's cones
  // and slabs), in the frame of the octree.
  // Checked on the atoms as given, so that a message names the caller's index of an atom.
  validate(atoms);
  if (resolve(opt.primitives, atoms) == PrimitiveSet::atoms) require_positive_radii(atoms);
  // The atoms in Z-order first: a cell's balls, the octree's lists and the migration's sums
  // then read nearby memory (at a million atoms in an arbitrary order, 1.7x as fast), and the
  // same atoms in any order give the same mesh.
  TargetShape g = [&] {
    MedialSurface sorted = spatially_sorted(atoms);
    const Frame frame = bounding_cube_frame(sorted);
    return make_target_shape(std::move(sorted), opt.primitives, opt.cones, frame);
  }();
  seconds.target_shape = clock.restart();
  peak.target_shape = peak_memory_mb();
  // Step 1: the adaptive octree wrapping G.
  Octree tree = build_octree(g, opt.octree);
  seconds.octree = clock.restart();
  peak.octree = peak_memory_mb();
  // Step 2: M1, the boundary of the active leaves.
  CoarseMesh m1 = extract_coarse_mesh(tree);
  seconds.m1 = clock.restart();
  peak.m1 = peak_memory_mb();
  // Step 3: M2, the dual of M1 migrated onto G.
  RefinedMesh m2 = refine_mesh(m1, tree, g, opt.refine);
  seconds.m2 = clock.restart();
  peak.m2 = peak_memory_mb();
  return {std::move(g), std::move(tree), std::move(m1), std::move(m2), seconds, peak};
}

}  // namespace mg::garbing
