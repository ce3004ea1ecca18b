#include "garbing/garb.h"

#include "core/errors.h"
#include "core/timer.h"

#include <cmath>
#include <string>
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
  const bool of_atoms = resolve(opt.primitives, atoms) == PrimitiveSet::atoms;
  if (of_atoms) require_positive_radii(atoms);
  if (!(opt.tolerance >= 0) || !std::isfinite(opt.tolerance))
    throw InvalidInput("the tolerance must be finite and >= 0, got " +
                       std::to_string(opt.tolerance));
  if (opt.tolerance > 0 && !of_atoms)
    throw InvalidInput(
        "--tolerance thins the atoms' balls: a medial mesh's envelope is garbed exactly (use "
        "--primitives rt to garb its atoms)");
  if (opt.tolerance > 0 && opt.cones.source == ConeSource::ma_edges)
    throw InvalidInput(
        "--tolerance thins the atoms' balls: the cones of the file's edges (--cones edges) "
        "would lose their atoms");
  OctreeOptions octree = opt.octree;
  if (opt.tolerance > 0) check_octree_options(octree);  // before the thinning reads min_depth
  ThinStats thinning;
  // The atoms in Z-order first: a cell's balls, the octree's lists and the migration's sums
  // then read nearby memory (at a million atoms in an arbitrary order, 1.7x as fast), and the
  // same atoms in any order give the same mesh.
  TargetShape g = [&] {
    MedialSurface sorted = spatially_sorted(atoms);
    const Frame frame = bounding_cube_frame(sorted);
    if (opt.tolerance > 0) {
      // The given atoms' resolution: their d, in their frame, whatever the thinning leaves.
      if (octree.min_depth == 0)
        octree.min_depth =
            automatic_min_depth(frame.cube_side, characteristic_radius(sorted), octree.max_depth);
      const double slack = opt.tolerance * std::ldexp(frame.cube_side, -octree.min_depth);
      // G of the balls and their own cones: the file's edges and faces are not read.
      MedialSurface balls;
      balls.atoms = std::move(sorted.atoms);
      sorted = opt.thinning == ThinMethod::cover ? thin_atoms_by_cover(balls, slack, &thinning)
                                                 : thin_atoms(balls, slack, &thinning);
    }
    return make_target_shape(std::move(sorted), opt.primitives, opt.cones, frame);
  }();
  seconds.target_shape = clock.restart();
  peak.target_shape = peak_memory_mb();
  // Step 1: the adaptive octree wrapping G.
  Octree tree = build_octree(g, octree);
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
  return {std::move(g), std::move(tree), std::move(m1), std::move(m2), seconds, peak, thinning};
}

}  // namespace mg::garbing
