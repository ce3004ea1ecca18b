#pragma once
/// \file octree.h
/// Step 1 of the garbing: the adaptive octree T wrapping G (paper section 3.1,
/// docs/algorithm.md "Step 1"), driven by four subdivision criteria iterated to a fixed point.

#include "garbing/target_shape.h"

#include <Eigen/Geometry>

#include <array>
#include <cstdint>
#include <vector>

namespace mg::garbing {

/// Options of build_octree().
struct OctreeOptions {
  /// Minimal active depth d (criterion 2), in levels; 0 = automatic: the first level whose
  /// cube side is <= rc / 8, rc = (rmin + rmax) / 2.
  int min_depth = 0;
  /// Safety stop, in levels: no cell is split beyond it; Octree::hit_max_depth reports whether
  /// a criterion wanted to. @pre 1 <= max_depth <= 20
  int max_depth = 14;
  /// criteria[k - 1] switches criterion k (1..4) on or off, for ablations.
  std::array<bool, 4> criteria = {true, true, true, true};
  /// A cell inside one closed ball holds no boundary face: do not split it beyond what grading
  /// (criterion 4) demands. Changes no boundary leaf and no M1 face; only for tests and timing.
  bool skip_interior_cells = true;
  /// Leave out of a cell's sphere list the balls that another listed ball covers inside the
  /// cube, with their cones (power dominance, docs/algorithm.md "Pruned lists"): the union of
  /// the listed primitives within the cube stays G's, and dense atoms list a fraction of the
  /// balls (bumpy torus at a million atoms: 413 of 4,469 per active leaf). Criteria 1 and 3
  /// read the shorter lists (they can only split more), and so does the migration's P(c).
  /// false: the paper's lists, every ball meeting the cube. An envelope's lists are never
  /// pruned.
  bool prune_lists = true;
};

/// An octree cell. Integer coordinates: the cell spans [ijk, ijk + 1] * side(level). Only a
/// leaf keeps its lists (Spheres, Cones, Slabs): a split hands them down to the children and
/// releases the parent's, so is_active() means something for leaves only.
struct OctreeCell {
  int level = 0;
  std::array<std::uint32_t, 3> ijk = {0, 0, 0};
  int parent = -1;       ///< index in Octree::cells; -1 for the root
  int first_child = -1;  ///< children are cells first_child .. first_child + 7; -1 for a leaf
  bool inside_one_ball = false;  ///< the closed cube lies inside one closed ball
  /// An envelope's cells only (TargetShape::is_envelope()): the closed cube lies inside the
  /// solid of one of its listed cones or the prism of one of its listed slabs, or its parent's
  /// did. Like a cell inside one ball it holds no boundary of G: criterion 2 exempts it
  /// (skip_interior_cells), criteria 1 and 3 skip it, and its children list no cones or slabs
  /// (they are active all the same).
  bool inside_one_hull = false;
  /// The cube holds no boundary of G: inside one ball or one hull.
  bool holds_no_boundary() const { return inside_one_ball || inside_one_hull; }
  /// Spheres(c): atoms whose closed ball meets the closed cube, sorted; with pruned lists
  /// (OctreeOptions::prune_lists, atoms' G) less those that another listed ball covers inside
  /// the cube together with their cones: the listed primitives' union within the cube is G's.
  std::vector<int> spheres;
  /// Cones(c): the cones of G (index k: primitive id sphere_count + k) whose solid meets the
  /// closed cube where neither ball does (through the fill of the crease between the balls),
  /// sorted. A cone one of whose balls meets the cube is not listed: its ball stands for it in
  /// the criteria. Pruned lists: a cone is not listed where a listed ball holds it within the
  /// cube, and can be listed where a ball of it meets the cube but was dropped higher up
  /// (neither ball is then listed). Empty in a cell inside one ball and its descendants (they
  /// hold no boundary, and the criteria skip them).
  std::vector<int> cones;
  /// Slabs(c): the slabs of G (index k: primitive id g.slab_id(k)) whose prism (slab.h: the
  /// slab's solid less its balls and edge hulls, which G holds as balls and cones) meets the
  /// closed cube where none of their three balls does, sorted. A slab met only through an edge
  /// hull is not listed: that cone, or its ball, stands for it.
  std::vector<int> slabs;
  bool is_leaf() const { return first_child < 0; }
  /// The cube meets G's solid: a listed primitive, or a hull holding it.
  bool is_active() const {
    return inside_one_hull || !spheres.empty() || !cones.empty() || !slabs.empty();
  }
};

/// The octree, in G's frame. Child k of a cell has offset (k & 1, k >> 1 & 1, k >> 2 & 1).
struct Octree {
  /// G's frame: world = frame.to_world(local), the root cube is local [0, root_side]^3.
  Frame frame;
  double root_side = 0;        ///< model units: the tight cube around the balls, no padding
  double rc = 0;               ///< characteristic radius (rmin + rmax) / 2, model units
  int min_depth = 0;           ///< d actually used
  int max_depth = 0;           ///< the safety stop given
  int depth = 0;               ///< deepest level present
  bool hit_max_depth = false;  ///< a criterion wanted to split a cell at max_depth
  long depth_stopped = 0;      ///< how many cells a criterion wanted to split at max_depth
  std::array<long, 4> splits = {0, 0, 0, 0};  ///< cells split by criterion k (first reason)
  std::vector<OctreeCell> cells;              ///< cells[0] is the root
  std::vector<int> leaves;                    ///< leaf indices, sorted by (Morton order, level)

  double side(int level) const;  ///< cube side at `level`
  /// The closed cube of a cell in the root frame: [ijk, ijk + 1] * side(level).
  Eigen::AlignedBox3d cube(const OctreeCell& cell) const;
  Eigen::Vector3d to_local(const Eigen::Vector3d& world) const { return frame.to_local(world); }
  Eigen::Vector3d to_world(const Eigen::Vector3d& local) const { return frame.to_world(local); }
};

/// The automatic minimal depth d (OctreeOptions::min_depth 0): the first level whose cube side
/// root_side / 2^d is <= rc / 8.
/// @pre root_side > 0, rc >= 0
/// @throws InvalidInput if root_side is infinite (the atoms span more than a double holds) or
///         d exceeds max_depth
int automatic_min_depth(double root_side, double rc, int max_depth);

/// Checks the options build_octree() takes (its @pre on them).
/// @throws InvalidInput naming the bad option
void check_octree_options(const OctreeOptions& opt);

/// Step 1: builds T wrapping G. A cell is active when it meets a ball, the solid of a cone
/// (the convex hull of its two balls) or the prism of a slab (so, the hull of its three balls);
/// criteria 1 and 3 see the
/// cones of Cones(c) and the slabs of Slabs(c) as primitives too (two primitives sharing an
/// atom meet; other meetings are tested exactly). So M1 lies outside G within a leaf everywhere,
/// also over the creases the cones fill, and no migration crosses a crease. G without cones: the
/// union of the balls.
/// @param g  G, built in its atoms' bounding cube frame (make_target_shape(atoms, cones,
///           bounding_cube_frame(atoms)))
/// @pre g.frame().cube_side > 0; 1 <= opt.max_depth <= 20; 0 <= opt.min_depth <= max_depth
///      (automatic d above max_depth is refused too)
/// @throws InvalidInput naming the bad option
/// @post criteria 1-4 (those switched on) hold at every active leaf, unless hit_max_depth
Octree build_octree(const TargetShape& g, const OctreeOptions& opt = {});

/// The deepest cell covering the cell (level, ijk) (itself if it exists, else the leaf
/// ancestor), or -1 if ijk lies outside the root.
int find_cell(const Octree& tree, int level, const std::array<std::int64_t, 3>& ijk);

/// The leaves under cell `c` that touch a neighbour lying in direction -offset from `c` (e.g.
/// offset (1, 0, 0): the leaves on c's low-x side), appended to `out` in child order.
void leaves_facing(const Octree& tree, int c, const std::array<int, 3>& offset,
                   std::vector<int>& out);

/// Leaves whose closed cells touch the closed cell `c` (share at least a point), any level,
/// sorted by index, without `c` itself.
void touching_leaves(const Octree& tree, int c, std::vector<int>& out);

}  // namespace mg::garbing
