// Step 1: the octree builder (criteria 1-4 in rounds, the children's sphere and cone lists).
#include "garbing/octree.h"

#include "core/errors.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace mg::garbing {
namespace {

using Vec3 = Eigen::Vector3d;

/// Builds the octree by rounds: each round evaluates the criteria on the new leaves (in
/// parallel, reading the tree only), then splits every marked cell in index order. The marks
/// are a pure function of the tree, so the result does not depend on thread count or order.
class OctreeBuilder {
 public:
  OctreeBuilder(const TargetShape& g, const OctreeOptions& opt) : g_(g), opt_(opt) {
    if (g_.cone_count() > 0) index_cones();
  }

  Octree run() {
    set_frame();
    OctreeCell root;
    root.spheres.resize(g_.sphere_count());
    for (std::size_t i = 0; i < root.spheres.size(); ++i) root.spheres[i] = static_cast<int>(i);
    root.inside_one_ball = inside_one_ball(root);
    tree_.cells.push_back(std::move(root));

    std::vector<int> candidates = {0};
    while (!candidates.empty()) {
      std::vector<std::pair<int, int>> marks = evaluate(candidates);  // (cell, criterion)
      candidates = split(marks);
    }
    finish();
    return std::move(tree_);
  }

 private:
  void set_frame() {
    tree_.frame = g_.frame();
    tree_.root_side = g_.frame().cube_side;
    tree_.max_depth = opt_.max_depth;
    tree_.rc = characteristic_radius(g_.atoms());
    if (opt_.min_depth > 0) {
      tree_.min_depth = opt_.min_depth;
    } else {
      tree_.min_depth = automatic_min_depth(tree_.root_side, tree_.rc, opt_.max_depth);
    }
  }

  /// For the pruned lists, per entry p of G's atom-to-cones index (atom a, cone k):
  /// cone_other_[p], k's other atom, and cone_reach_[p], how far k's crease fill reaches outside
  /// a's ball (so B(c_a, r_a + reach) holds a's ball and the fill), cone_kappa_[p] = L^2 -
  /// (r_b - r_a)^2 (prune_covered_balls); reach_[a], the largest reach of a's. Floats rounded
  /// up: both only ever weaken a test.
  void index_cones() {
    const std::size_t n = g_.sphere_count();
    const PrimitiveId* const base = g_.cones_of_atom(0).first;
    const std::size_t entries =
        static_cast<std::size_t>(g_.cones_of_atom(static_cast<int>(n) - 1).second - base);
    reach_.assign(n, 0.0);
    cone_other_.resize(entries);
    cone_reach_.resize(entries);
    cone_kappa_.resize(entries);
    // Slack far above the rounding of the distances a reach is compared with.
    const double slack = 1e-12 * g_.frame().cube_side;
    tbb::parallel_for(
        tbb::blocked_range<std::size_t>(0, n, 1024), [&](const tbb::blocked_range<std::size_t>& r) {
          for (std::size_t a = r.begin(); a != r.end(); ++a) {
            const auto [first, last] = g_.cones_of_atom(static_cast<int>(a));
            double most = 0;
            for (const PrimitiveId* id = first; id != last; ++id) {
              const Cone k = g_.cone(*id);
              const bool low = k.a == static_cast<int>(a);
              const double reach = fill_reach(k, low) * (1 + 1e-9) + slack;
              const std::size_t p = static_cast<std::size_t>(id - base);
              cone_other_[p] = low ? k.b : k.a;
              cone_reach_[p] = std::nextafter(static_cast<float>(reach), INFINITY);
              const double kappa = k.length * k.length - k.dr * k.dr;
              cone_kappa_[p] =
                  std::nextafter(static_cast<float>(kappa * (1 + 1e-9) + slack * slack), INFINITY);
              most = std::max(most, static_cast<double>(cone_reach_[p]));
            }
            reach_[a] = most;
          }
        });
  }

  /// How far the cone's fill reaches outside the ball of its first (low) or second atom: the
  /// fill lies in the profile triangle of the crease point and the two rims (primitives.h),
  /// and the distance from the ball's centre is convex, so largest at a corner. A waist (an
  /// envelope's disjoint balls): the frustum's bounding ball.
  static double fill_reach(const Cone& k, bool low) {
    const double r = low ? k.r1 : k.r2;
    if (k.disjoint) {
      const Vec3 c = low ? k.c1 : k.centre(1);
      return std::max(0.0, (k.bound_centre - c).norm() + std::sqrt(k.bound_radius2) - r);
    }
    const double at = low ? 0 : k.length;  // the ball's centre on the profile's axis
    const double far =
        std::max({std::hypot(k.crease.along - at, k.crease.radius),
                  std::hypot(k.t_lo - at, k.rho_lo), std::hypot(k.t_hi - at, k.rho_hi)});
    return std::max(0.0, far - r);
  }

  bool criterion(int k) const { return opt_.criteria[k - 1]; }

  Vec3 cell_lo(const OctreeCell& c) const { return tree_.cube(c).min(); }

  bool ball_contains_cell(int i, const Vec3& lo, double side) const {
    const Vec3& p = g_.sphere(i).centre;
    double d2 = 0;
    for (int a = 0; a < 3; ++a) {
      const double d = std::max(std::abs(p[a] - lo[a]), std::abs(p[a] - lo[a] - side));
      d2 += d * d;
    }
    const double r = g_.sphere(i).radius;
    return d2 <= r * r;
  }

  bool inside_one_ball(const OctreeCell& c) const {
    const Vec3 lo = cell_lo(c);
    const double side = tree_.side(c.level);
    for (int i : c.spheres)
      if (ball_contains_cell(i, lo, side)) return true;
    return false;
  }

  bool balls_intersect(int i, int j) const {
    const double r = g_.sphere(i).radius + g_.sphere(j).radius;
    return (g_.sphere(i).centre - g_.sphere(j).centre).squaredNorm() <= r * r;
  }

  /// Whether two listed balls meet in the criteria's graph: they intersect, or (an envelope)
  /// a cone joins them. That cone holds both balls, so it meets every cell either meets: it
  /// belongs to the cell's full primitive set, where it joins them; the lists leave it out
  /// only because its balls stand for it. Without this, balls joined by an edge that touch
  /// or just miss each other look apart in every cell holding both, down to the depth stop.
  /// (The paper's cones join intersecting balls only: no change there.)
  bool balls_meet(int i, int j) const {
    if (balls_intersect(i, j)) return true;
    if (!joined_by_edges_) return false;
    const auto [first, last] = g_.cones_of_atom(i);
    for (const PrimitiveId* c = first; c != last; ++c)
      if (g_.cone_atoms(*c)[0] == j || g_.cone_atoms(*c)[1] == j) return true;
    return false;
  }

  /// Primitive ids of the criteria, as G's: sphere i is i, cone k is n + k (n atoms).
  int sphere_count() const { return static_cast<int>(g_.sphere_count()); }

  /// The atoms of a hull (cone or slab), -1 padded.
  std::array<int, 3> corners(int p) const {
    if (g_.is_slab(p)) return g_.slab(p).atoms;
    const auto [a, b] = g_.cone_atoms(p);
    return {a, b, -1};
  }

  static bool share_atom(const std::array<int, 3>& x, const std::array<int, 3>& y) {
    for (int a : x)
      for (int b : y)
        if (a >= 0 && a == b) return true;
    return false;
  }

  /// Whether two primitives meet (closed solids). A hull (cone or slab) meets its own balls
  /// and any hull sharing one; otherwise exact up to 1e-9 of the searches' slope bounds,
  /// counted as meeting.
  bool primitives_meet(int p, int q) const {
    const int n = sphere_count();
    if (p > q) std::swap(p, q);
    if (q < n) return balls_meet(p, q);
    if (g_.is_slab(q)) {  // ids: spheres, cones, slabs
      const Slab& sq = g_.slab(q);
      if (p < n) {
        if (p == sq.atoms[0] || p == sq.atoms[1] || p == sq.atoms[2]) return true;
        return slab_meets_ball(sq, g_.sphere(p));
      }
      if (share_atom(corners(p), sq.atoms)) return true;
      return g_.is_slab(p) ? slabs_meet(g_.slab(p), sq) : slab_meets_cone(sq, g_.cone(p));
    }
    const Cone kq = g_.cone(q);
    if (p < n) {
      if (p == kq.a || p == kq.b) return true;
      return hull_distance(kq, g_.sphere(p).centre) <= g_.sphere(p).radius;
    }
    const Cone kp = g_.cone(p);
    if (kp.a == kq.a || kp.a == kq.b || kp.b == kq.a || kp.b == kq.b) return true;
    return hulls_meet(kp, kq);
  }

  /// Primitives(c): Spheres(c) then n + Cones(c), sorted; Spheres(c) itself when there are
  /// no cones, else built in `scratch`.
  const std::vector<int>& primitives(const OctreeCell& cell, std::vector<int>& scratch) const {
    if (cell.cones.empty() && cell.slabs.empty()) return cell.spheres;
    scratch.assign(cell.spheres.begin(), cell.spheres.end());
    for (int k : cell.cones) scratch.push_back(sphere_count() + k);
    for (int k : cell.slabs) scratch.push_back(g_.slab_id(k));
    return scratch;
  }

  /// Criterion 1: the intersection graph of Primitives(c) is connected. Breadth-first search
  /// that scans only the primitives not reached yet, so dense overlaps cost about linear time.
  bool primitives_connected(const std::vector<int>& prims) const {
    if (prims.size() < 2) return true;
    std::vector<int> unreached(prims.begin() + 1, prims.end());
    std::vector<int> stack = {prims.front()};
    while (!stack.empty() && !unreached.empty()) {
      const int s = stack.back();
      stack.pop_back();
      auto keep = unreached.begin();
      for (int t : unreached) {
        if (primitives_meet(s, t))
          stack.push_back(t);
        else
          *keep++ = t;
      }
      unreached.erase(keep, unreached.end());
    }
    return unreached.empty();
  }

  /// An envelope's cells, criteria 1 and 3, first by shared atoms. A cell's full primitive set
  /// is its lists plus every hull (cone, slab) of one of its balls: such a hull holds the ball,
  /// so it meets the cell too; the lists leave it out only because the ball stands for it.
  /// Primitives sharing an atom meet, so the atoms of each primitive of the full set, a listed
  /// ball with all its neighbours in the medial mesh, fall in one class (union-find): when the
  /// listed primitives' atoms make one class, the full set is connected. Per thread, over atom
  /// ids, reset by stamps.
  class AtomClasses {
   public:
    /// Starts an empty partition of the atoms of g (stamps: no clearing of the arrays, which
    /// outlive a build as thread-locals; a generation never repeats).
    void clear(const TargetShape& g) {
      g_ = &g;
      if (parent_.size() != g.sphere_count()) {
        parent_.assign(g.sphere_count(), 0);
        stamp_.assign(g.sphere_count(), 0);
      }
      ++generation_;
    }
    int find(int a) {
      if (stamp_[a] != generation_) {
        stamp_[a] = generation_;
        parent_[a] = a;
        return a;
      }
      while (parent_[a] != a) a = parent_[a] = parent_[parent_[a]];
      return a;
    }
    void unite(int a, int b) {
      a = find(a);
      b = find(b);
      if (a != b) parent_[std::max(a, b)] = std::min(a, b);
    }
    /// The cell's full set: its balls with their neighbours, its cones and slabs.
    void add_cell(const OctreeCell& cell) {
      const int n = static_cast<int>(g_->sphere_count());
      for (int i : cell.spheres) {
        find(i);
        const auto [first, last] = g_->cones_of_atom(i);
        for (const PrimitiveId* c = first; c != last; ++c) {
          const auto [a, b] = g_->cone_atoms(*c);
          unite(a, b);
        }
        const auto [first_slab, last_slab] = g_->slabs_of_atom(i);
        for (const PrimitiveId* c = first_slab; c != last_slab; ++c) unite_corners(*c);
      }
      for (int k : cell.cones) {
        const auto [a, b] = g_->cone_atoms(n + k);
        unite(a, b);
      }
      for (int k : cell.slabs) unite_corners(g_->slab_id(k));
    }
    /// Whether the listed primitives' atoms are one class.
    bool one_class(const OctreeCell& cell) {
      const int n = static_cast<int>(g_->sphere_count());
      int root = -1;
      auto same = [&](int atom) {
        const int r = find(atom);
        if (root < 0) root = r;
        return r == root;
      };
      for (int i : cell.spheres)
        if (!same(i)) return false;
      for (int k : cell.cones)
        if (!same(g_->cone_atoms(n + k)[0])) return false;
      for (int k : cell.slabs)
        if (!same(g_->slab(g_->slab_id(k)).atoms[0])) return false;
      return true;
    }
    /// Whether an atom of the cell's full set was added already.
    bool shares_an_atom(const OctreeCell& cell) const {
      const int n = static_cast<int>(g_->sphere_count());
      auto seen = [&](int atom) { return stamp_[atom] == generation_; };
      for (int i : cell.spheres) {
        if (seen(i)) return true;
        const auto [first, last] = g_->cones_of_atom(i);
        for (const PrimitiveId* c = first; c != last; ++c)
          if (seen(g_->cone_atoms(*c)[0]) || seen(g_->cone_atoms(*c)[1])) return true;
        const auto [first_slab, last_slab] = g_->slabs_of_atom(i);
        for (const PrimitiveId* c = first_slab; c != last_slab; ++c)
          for (int a : g_->slab(*c).atoms)
            if (seen(a)) return true;
      }
      for (int k : cell.cones)
        if (seen(g_->cone_atoms(n + k)[0]) || seen(g_->cone_atoms(n + k)[1])) return true;
      for (int k : cell.slabs)
        for (int a : g_->slab(g_->slab_id(k)).atoms)
          if (seen(a)) return true;
      return false;
    }

   private:
    void unite_corners(PrimitiveId slab) {
      const auto& a = g_->slab(slab).atoms;
      unite(a[0], a[1]);
      unite(a[0], a[2]);
    }
    const TargetShape* g_ = nullptr;
    std::vector<int> parent_;
    std::vector<std::uint64_t> stamp_;
    std::uint64_t generation_ = 0;
  };

  AtomClasses& atom_classes() const {
    thread_local AtomClasses classes;
    classes.clear(g_);
    return classes;
  }

  /// Criterion 1: the listed primitives are connected, or (an envelope) the full set is, by
  /// shared atoms. The lists' test first: it settles nearly every cell.
  bool cell_connected(const OctreeCell& cell, std::vector<int>& scratch) const {
    if (primitives_connected(primitives(cell, scratch))) return true;
    if (!joined_by_edges_) return false;
    AtomClasses& classes = atom_classes();
    classes.add_cell(cell);
    return classes.one_class(cell);
  }

  /// Criterion 3: the lists meet, or (an envelope) the two full sets share an atom, so that two
  /// of their primitives meet. The lists' test first.
  bool cells_intersect(const OctreeCell& a, const OctreeCell& b) const {
    if (sets_intersect(a, b)) return true;
    if (!joined_by_edges_) return false;
    AtomClasses& classes = atom_classes();
    classes.add_cell(a);
    return classes.shares_an_atom(b);
  }

  /// Criterion 3's test: some primitive of cell `a` meets some primitive of cell `b` (a
  /// shared one counts), read from the cells' sorted sphere and cone lists without merging
  /// them. Spheres are tried against spheres first.
  bool sets_intersect(const OctreeCell& a, const OctreeCell& b) const {
    if (share_one(a.spheres, b.spheres) || share_one(a.cones, b.cones)) return true;
    for (int s : a.spheres)
      for (int t : b.spheres)
        if (balls_meet(s, t)) return true;
    const int n = sphere_count();
    for (int k : a.cones) {  // cones of a against everything of b
      for (int t : b.spheres)
        if (primitives_meet(n + k, t)) return true;
      for (int l : b.cones)
        if (primitives_meet(n + k, n + l)) return true;
    }
    for (int l : b.cones)  // cones of b against the spheres of a
      for (int s : a.spheres)
        if (primitives_meet(s, n + l)) return true;
    if (a.slabs.empty() && b.slabs.empty()) return false;
    if (share_one(a.slabs, b.slabs)) return true;
    for (int k : a.slabs) {  // slabs of a against everything of b
      const int p = g_.slab_id(k);
      for (int t : b.spheres)
        if (primitives_meet(p, t)) return true;
      for (int l : b.cones)
        if (primitives_meet(p, n + l)) return true;
      for (int l : b.slabs)
        if (primitives_meet(p, g_.slab_id(l))) return true;
    }
    for (int l : b.slabs) {  // slabs of b against the spheres and cones of a
      const int q = g_.slab_id(l);
      for (int s : a.spheres)
        if (primitives_meet(s, q)) return true;
      for (int k : a.cones)
        if (primitives_meet(n + k, q)) return true;
    }
    return false;
  }

  /// Whether two sorted lists share an element.
  static bool share_one(const std::vector<int>& a, const std::vector<int>& b) {
    auto i = a.begin();
    auto j = b.begin();
    while (i != a.end() && j != b.end()) {
      if (*i == *j) return true;
      if (*i < *j)
        ++i;
      else
        ++j;
    }
    return false;
  }

  /// Dimension of the intersection of two touching closed cells: 0 corner, 1 edge, 2 face.
  static int contact_dimension(const OctreeCell& a, const OctreeCell& b) {
    const int level = std::max(a.level, b.level);
    int dim = 0;
    for (int k = 0; k < 3; ++k) {
      const std::int64_t alo = std::int64_t(a.ijk[k]) << (level - a.level);
      const std::int64_t ahi = std::int64_t(a.ijk[k] + 1) << (level - a.level);
      const std::int64_t blo = std::int64_t(b.ijk[k]) << (level - b.level);
      const std::int64_t bhi = std::int64_t(b.ijk[k] + 1) << (level - b.level);
      if (std::min(ahi, bhi) > std::max(alo, blo)) ++dim;
    }
    return dim;
  }

  /// Criterion marks of one candidate leaf (reads the tree only). The candidates are the
  /// cells from `first_candidate` on; the tests of a pair of touching leaves are symmetric,
  /// so a pair of two candidates is tested from the higher index only.
  void evaluate_cell(int c, int first_candidate, std::vector<std::pair<int, int>>& marks,
                     std::vector<int>& touching, std::vector<int>& mine) const {
    const OctreeCell& cell = tree_.cells[c];
    if (!cell.is_active()) return;
    const bool exempt = opt_.skip_interior_cells && cell.holds_no_boundary();
    const int d = tree_.min_depth;
    if (criterion(2) && cell.level < d && !exempt) marks.emplace_back(c, 2);
    const bool test_1 = criterion(1) && cell.level >= d && !cell.holds_no_boundary();
    const bool test_3 = criterion(3) && cell.level >= d && !cell.holds_no_boundary();
    if (test_1 && !cell_connected(cell, mine)) marks.emplace_back(c, 1);
    if (!criterion(3) && !criterion(4)) return;
    touching_leaves(tree_, c, touching);
    for (int t : touching) {
      const OctreeCell& other = tree_.cells[t];
      if (!other.is_active() || (t >= first_candidate && t > c)) continue;
      if (criterion(4) && std::abs(cell.level - other.level) > 1 &&
          contact_dimension(cell, other) >= 1)
        marks.emplace_back(cell.level < other.level ? c : t, 4);
      if (test_3 && other.level >= d && !other.holds_no_boundary()) {
        if (!cells_intersect(cell, other)) {
          if (cell.level <= other.level) marks.emplace_back(c, 3);
          if (other.level <= cell.level) marks.emplace_back(t, 3);
        }
      }
    }
  }

  /// @pre candidates are consecutive indices (the cells the last split created)
  std::vector<std::pair<int, int>> evaluate(const std::vector<int>& candidates) const {
    std::vector<std::vector<std::pair<int, int>>> per(candidates.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, candidates.size(), 64),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        std::vector<int> touching, mine;
                        for (std::size_t i = r.begin(); i != r.end(); ++i)
                          evaluate_cell(candidates[i], candidates.front(), per[i], touching, mine);
                      });
    std::vector<std::pair<int, int>> marks;
    for (auto& m : per) marks.insert(marks.end(), m.begin(), m.end());
    std::sort(marks.begin(), marks.end());
    return marks;
  }

  static void release(std::vector<int>& list) { std::vector<int>().swap(list); }

  /// Splits each marked leaf once (first reason counted), returns the new children.
  std::vector<int> split(const std::vector<std::pair<int, int>>& marks) {
    std::vector<int> to_split;
    for (std::size_t i = 0; i < marks.size(); ++i) {
      if (i > 0 && marks[i].first == marks[i - 1].first) continue;
      const int c = marks[i].first;
      if (!tree_.cells[c].is_leaf()) continue;
      if (tree_.cells[c].level >= opt_.max_depth) {
        tree_.hit_max_depth = true;
        ++tree_.depth_stopped;
        continue;
      }
      ++tree_.splits[marks[i].second - 1];
      to_split.push_back(c);
    }
    // Children's sphere lists, filtered from the parent's, in parallel. Only leaves' lists are
    // read from now on: each parent's go as soon as its children hold theirs. One parent per
    // task at the least: the first rounds split a few cells with most of the atoms each.
    std::vector<std::array<OctreeCell, 8>> children(to_split.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, to_split.size(), 1),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t i = r.begin(); i != r.end(); ++i) {
                          make_children(to_split[i], children[i]);
                          OctreeCell& parent = tree_.cells[to_split[i]];
                          release(parent.spheres);
                          release(parent.cones);
                          release(parent.slabs);
                        }
                      });
    std::vector<int> created;
    created.reserve(8 * to_split.size());
    tree_.cells.reserve(tree_.cells.size() + 8 * to_split.size());  // no spare capacity
    for (std::size_t i = 0; i < to_split.size(); ++i) {
      OctreeCell& parent = tree_.cells[to_split[i]];
      const int first = static_cast<int>(tree_.cells.size());
      parent.first_child = first;
      for (auto& child : children[i]) {
        created.push_back(static_cast<int>(tree_.cells.size()));
        tree_.cells.push_back(std::move(child));
      }
    }
    return created;
  }

  /// The eight children of a leaf with their sphere lists, in one pass over the parent's
  /// spheres: per axis, the squared distances from the centre to the lower and upper half (and
  /// to the farthest face of each half), summed per child. The same floating-point operations
  /// as a cube-ball distance test and `ball_contains_cell` on each child, so the same decisions.
  void make_children(int c, std::array<OctreeCell, 8>& out) const {
    const OctreeCell& parent = tree_.cells[c];
    const double side = tree_.side(parent.level + 1);
    double lo[3][2], hi[3][2];
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 2; ++b) {
        lo[a][b] = (2 * parent.ijk[a] + b) * side;
        hi[a][b] = lo[a][b] + side;
      }
    for (int k = 0; k < 8; ++k) {
      OctreeCell& child = out[k];
      child.level = parent.level + 1;
      for (int a = 0; a < 3; ++a) child.ijk[a] = 2 * parent.ijk[a] + ((k >> a) & 1);
      child.parent = c;
      child.inside_one_ball = false;
    }
    // masks[x]: the children met by the ball parent.spheres[x], bit k for child k; reach[x]:
    // those within reach_[i] of it, where the crease fills of its cones can lie.
    const bool has_cones = g_.cone_count() > 0;
    std::vector<std::uint8_t> masks(parent.spheres.size(), 0);
    std::vector<std::uint8_t> reach(has_cones ? parent.spheres.size() : 0, 0);
    std::array<std::size_t, 8> count = {};
    for (std::size_t x = 0; x < parent.spheres.size(); ++x) {
      const int i = parent.spheres[x];
      const Vec3& p = g_.sphere(i).centre;
      const double r = g_.sphere(i).radius;
      const double r2 = r * r;
      const double reach2 = has_cones ? (r + reach_[i]) * (r + reach_[i]) : 0;
      double near[3][2], far[3][2];
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 2; ++b) {
          const double d = std::max({lo[a][b] - p[a], 0.0, p[a] - hi[a][b]});
          near[a][b] = d * d;
          const double e = std::max(std::abs(p[a] - lo[a][b]), std::abs(p[a] - lo[a][b] - side));
          far[a][b] = e * e;
        }
      for (int k = 0; k < 8; ++k) {
        const int b0 = k & 1, b1 = (k >> 1) & 1, b2 = (k >> 2) & 1;
        double d2 = 0;
        d2 += near[0][b0];
        d2 += near[1][b1];
        d2 += near[2][b2];
        if (has_cones && d2 <= reach2) reach[x] |= static_cast<std::uint8_t>(1u << k);
        if (d2 > r2) continue;
        masks[x] |= static_cast<std::uint8_t>(1u << k);
        ++count[k];
        OctreeCell& child = out[k];
        if (!child.inside_one_ball) {
          double e2 = 0;
          e2 += far[0][b0];
          e2 += far[1][b1];
          e2 += far[2][b2];
          child.inside_one_ball = e2 <= r2;
        }
      }
    }
    // Per child, the balls whose power decides what is dropped (pruned lists only).
    thread_local std::array<std::vector<int>, 8> witnesses;
    for (auto& w : witnesses) w.clear();
    std::vector<std::uint8_t> full;  // the masks before pruning, when it drops a ball
    if (prune_) {
      full = masks;
      if (!prune_covered_balls(parent, lo, side, masks, count, witnesses)) full.clear();
    }
    const std::vector<std::uint8_t>& meets = full.empty() ? masks : full;
    // The lists, sized once, in the parent's (sorted) order.
    for (int k = 0; k < 8; ++k) out[k].spheres.reserve(count[k]);
    for (std::size_t x = 0; x < parent.spheres.size(); ++x)
      for (unsigned m = masks[x]; m != 0; m &= m - 1)
        out[__builtin_ctz(m)].spheres.push_back(parent.spheres[x]);
    // Cones(child), the cones whose solid meets the cube while neither of their balls does:
    // candidates are the parent's and those of the parent's balls (a cone meets a sub-cube
    // only if it meets the cube). A cube inside one ball holds no boundary and is never tested
    // by criteria 1 and 3: its children need none (they are active through that ball).
    if (parent.inside_one_hull)
      for (auto& child : out) child.inside_one_hull = !child.inside_one_ball;
    if (parent.holds_no_boundary() || (g_.cone_count() == 0 && g_.slab_count() == 0)) return;
    // Per thread: each atom's child mask in this parent, and a stamp per cone against repeats.
    thread_local std::vector<std::uint8_t> mask_of_atom;
    thread_local std::vector<std::uint64_t> stamp;
    thread_local std::uint64_t generation = 0;
    if (mask_of_atom.size() != g_.sphere_count()) mask_of_atom.assign(g_.sphere_count(), 0);
    if (stamp.size() != g_.cone_count() + g_.slab_count()) {
      stamp.assign(g_.cone_count() + g_.slab_count(), 0);
      generation = 0;
    }
    ++generation;
    // Children inside one ball are left without: the same reason.
    unsigned skip = 0;
    for (int j = 0; j < 8; ++j) skip |= static_cast<unsigned>(out[j].inside_one_ball) << j;
    if (skip == 0xFF) return;
    // The children each ball meets: a cone one of whose balls meets a child is not listed
    // there (a kept ball stands for it; a dropped one was dropped only with its cones covered).
    for (std::size_t x = 0; x < parent.spheres.size(); ++x)
      mask_of_atom[parent.spheres[x]] = meets[x];
    const Vec3 parent_lo(lo[0][0], lo[1][0], lo[2][0]);
    const int n = sphere_count();
    auto consider = [&](int k) {
      if (stamp[k] == generation) return;
      stamp[k] = generation;
      const auto [a, b] = g_.cone_atoms(n + k);
      const unsigned via_ball = mask_of_atom[a] | mask_of_atom[b];
      if ((via_ball | skip) == 0xFF) return;
      const Cone cone = g_.cone(n + k);
      if (!near_crease_fill(cone, parent_lo, 2 * side)) return;
      for (int j = 0; j < 8; ++j) {
        if ((skip >> j & 1) || (via_ball >> j & 1)) continue;
        const Vec3 child_lo(lo[0][j & 1], lo[1][(j >> 1) & 1], lo[2][(j >> 2) & 1]);
        if (!fill_meets_cube(cone, child_lo, side)) continue;
        // Pruned lists: a cone whose solid the child's witness ball covers there is not G's
        // boundary in it either.
        if (std::any_of(witnesses[j].begin(), witnesses[j].end(),
                        [&](int w) { return hull_dominated(cone, w, child_lo, side); }))
          continue;
        out[j].cones.push_back(k);
      }
    };
    for (int k : parent.cones) consider(k);
    // A cone's fill lies within reach_ of each of its balls: only a ball reaching a child it
    // does not meet (outside one ball) can have a cone to list there.
    const PrimitiveId* const cone_base = has_cones ? g_.cones_of_atom(0).first : nullptr;
    for (std::size_t x = 0; has_cones && x < parent.spheres.size(); ++x) {
      if ((reach[x] & ~meets[x] & ~skip & 0xFF) == 0) continue;
      const int i = parent.spheres[x];
      const Vec3& p = g_.sphere(i).centre;
      double d2[8];  // squared distances from the centre to the children
      for (int j = 0; j < 8; ++j) {
        d2[j] = 0;
        for (int a = 0; a < 3; ++a) {
          const int b = (j >> a) & 1;
          const double d = std::max({lo[a][b] - p[a], 0.0, p[a] - hi[a][b]});
          d2[j] += d * d;
        }
      }
      const auto [first, last] = g_.cones_of_atom(i);
      for (const PrimitiveId* id = first; id != last; ++id) {
        const std::size_t e = static_cast<std::size_t>(id - cone_base);
        const unsigned open = reach[x] & ~(meets[x] | skip | mask_of_atom[cone_other_[e]]) & 0xFF;
        if (open == 0) continue;
        const double grown = g_.sphere(i).radius + cone_reach_[e];
        for (int j = 0; j < 8; ++j)
          if ((open >> j & 1) && d2[j] <= grown * grown) {
            consider(*id - n);
            break;
          }
      }
    }
    // Slabs(child): the slabs whose prism meets the cube where none of their balls does (the
    // rest of a slab's solid is its edge hulls, listed above as cones or balls).
    const int first_slab = g_.slab_id(0);
    const Vec3 parent_hi = parent_lo + Vec3::Constant(2 * side);
    auto consider_slab = [&](int k) {
      const std::size_t key = g_.cone_count() + static_cast<std::size_t>(k);
      if (stamp[key] == generation) return;
      stamp[key] = generation;
      const Slab& slab = g_.slab(first_slab + k);
      const unsigned via_ball =
          mask_of_atom[slab.atoms[0]] | mask_of_atom[slab.atoms[1]] | mask_of_atom[slab.atoms[2]];
      if ((via_ball | skip) == 0xFF || !slab.has_tangent_triangles ||
          !slab.prism_box.intersects(Eigen::AlignedBox3d(parent_lo, parent_hi)))
        return;
      for (int j = 0; j < 8; ++j) {
        if ((skip >> j & 1) || (via_ball >> j & 1)) continue;
        const Vec3 child_lo(lo[0][j & 1], lo[1][(j >> 1) & 1], lo[2][(j >> 2) & 1]);
        if (prism_meets_box(slab, child_lo, Vec3(child_lo + Vec3::Constant(side))))
          out[j].slabs.push_back(k);
      }
    };
    if (g_.slab_count() > 0) {
      for (int k : parent.slabs) consider_slab(k);
      for (std::size_t x = 0; x < parent.spheres.size(); ++x)
        if (meets[x] != 0xFF) {
          const auto [first, last] = g_.slabs_of_atom(parent.spheres[x]);
          for (const PrimitiveId* id = first; id != last; ++id) consider_slab(*id - first_slab);
        }
    }
    for (int i : parent.spheres) mask_of_atom[i] = 0;
    for (auto& child : out) {
      std::sort(child.cones.begin(), child.cones.end());
      std::sort(child.slabs.begin(), child.slabs.end());
      if (g_.is_envelope() && !child.inside_one_ball)
        child.inside_one_hull = inside_a_listed_hull(child);
    }
  }

  /// min over the closed cube [clo, clo + side] of pow_i - pow_w (pow_k(x) = |x - c_k|^2 -
  /// r_k^2), from the affine difference's worst corner: where it exceeds the margin, ball w
  /// holds every point of B_i in the cube.
  double power_gap(int i, int w, const Vec3& clo, double side) const {
    return power_gap(PowerTerms(g_.sphere(i)), PowerTerms(g_.sphere(w)), clo, side);
  }

  /// A ball's centre with the two terms of its power's constant part, |c|^2 and r^2: computed
  /// once per ball when it is tested against several witnesses.
  struct PowerTerms {
    Vec3 c;
    double norm2, r2;
    explicit PowerTerms(const MedialAtom& s)
        : c(s.centre), norm2(s.centre.squaredNorm()), r2(s.radius * s.radius) {}
  };

  /// power_gap from the balls' terms: (|c_w|^2 - r_w^2 - |c_i|^2 + r_i^2) plus the worst
  /// corner's slope terms, in that order.
  static double power_gap(const PowerTerms& i, const PowerTerms& w, const Vec3& clo, double side) {
    double d = w.norm2 - w.r2 - i.norm2 + i.r2;
    for (int a = 0; a < 3; ++a) {
      const double slope = 2 * (i.c[a] - w.c[a]);
      d += slope * (slope > 0 ? clo[a] + side : clo[a]);
    }
    return -d;
  }

  /// Whether the solid of a cone meets the closed cube [clo, clo + side] only inside ball w:
  /// pow_w(x) < pow_t(x) - margin for every x of the cube and every interpolated ball t in
  /// [0, 1] (a point of the solid has pow_t <= 0 for some t). For a fixed sign pattern of
  /// c(t) - c_w the worst x is a fixed corner and pow_w - pow_t is concave in t; the patterns
  /// change at most three times along [0, 1], so the maximum is found piece by piece.
  bool hull_dominated(const Cone& k, int w, const Vec3& clo, double side) const {
    const Vec3& cw = g_.sphere(w).centre;
    const double rw = g_.sphere(w).radius;
    const Vec3 delta = k.length * k.u;  // c2 - c1
    double cuts[5] = {0, 1, 1, 1, 1};
    int count = 1;
    for (int a = 0; a < 3; ++a)
      if (delta[a] != 0) {
        const double t = (cw[a] - k.c1[a]) / delta[a];
        if (t > 0 && t < 1) cuts[count++] = t;
      }
    cuts[count++] = 1;
    for (int i = 1; i < count; ++i)  // insertion sort of at most five
      for (int j = i; j > 0 && cuts[j] < cuts[j - 1]; --j) std::swap(cuts[j], cuts[j - 1]);
    const double curvature = delta.squaredNorm() - k.dr * k.dr;  // > 0: neither ball holds
    if (!(curvature > 0)) return false;  // nearly nested balls, rounded: no claim
    for (int piece = 0; piece + 1 < count; ++piece) {
      const double t0 = cuts[piece], t1 = cuts[piece + 1];
      const Vec3 mid = k.centre((t0 + t1) / 2);
      Vec3 x;
      for (int a = 0; a < 3; ++a) x[a] = mid[a] > cw[a] ? clo[a] + side : clo[a];
      // pow_t(x) is least at t = ((x - c1).delta + r1 dr) / curvature.
      const double t = std::clamp(((x - k.c1).dot(delta) + k.r1 * k.dr) / curvature, t0, t1);
      const double rt = k.radius(t);
      const double d = (x - cw).squaredNorm() - rw * rw - (x - k.centre(t)).squaredNorm() + rt * rt;
      if (!(d < -margin_)) return false;
    }
    return true;
  }

  /// Drops from the children's sphere masks the balls another listed ball covers inside the
  /// child (OctreeOptions::prune_lists): ball i goes when, for a witness w of the child, the
  /// power pow_w(x) = |x - c_w|^2 - r_w^2 lies below pow_i(x) by a margin on the whole closed
  /// cube; then every point of the cube in B_i (pow_i <= 0) has pow_w < 0, so B_i meets the cube
  /// only inside B_w, and dropping it leaves the union of the balls within the cube as it was.
  /// The witnesses are the balls of least power at the child's centre, then (over the balls
  /// left) at its eight corners; they are never dropped. A ball dropped here is dropped in every
  /// descendant (the cube shrinks), so the children start from the parent's kept balls.
  bool prune_covered_balls(const OctreeCell& parent, const double (&lo)[3][2], double side,
                           std::vector<std::uint8_t>& masks, std::array<std::size_t, 8>& count,
                           std::array<std::vector<int>, 8>& witnesses_of) const {
    const std::size_t n = parent.spheres.size();
    bool dropped = false;
    auto power = [&](int i, const Vec3& q) {
      return (q - g_.sphere(i).centre).squaredNorm() - g_.sphere(i).radius * g_.sphere(i).radius;
    };
    double gap = 0;  // of the last ball tested, against its witness
    thread_local std::vector<PowerTerms> witness_terms;  // of witnesses[tested ..]
    // Per atom of the parent's list, the children where it is still kept (0 for the others).
    thread_local std::vector<std::uint8_t> kept;
    const bool cones = !cone_other_.empty();
    if (cones) {
      if (kept.size() != g_.sphere_count()) kept.assign(g_.sphere_count(), 0);
      for (std::size_t x = 0; x < n; ++x) kept[parent.spheres[x]] = masks[x];
    }
    // kept must be all zeros between calls, even when an exception leaves this one.
    struct Clear {
      std::vector<std::uint8_t>& kept;
      const std::vector<int>& atoms;
      bool active;
      ~Clear() {
        if (active)
          for (int i : atoms) kept[i] = 0;
      }
    } clear{kept, parent.spheres, cones};
    const PrimitiveId* const cone_base = cones ? g_.cones_of_atom(0).first : nullptr;
    // Whether every cone of atom i keeps its other ball j in the child (bit), or lies within
    // the cube in the ball of the witness w that covers i (gap_i: pow_i - pow_w >= gap_i on
    // the cube). The interpolated balls' powers are pow_t = (1 - t) pow_i + t pow_j -
    // kappa t (1 - t), kappa = |c_j - c_i|^2 - (r_j - r_i)^2, so pow_t - pow_w >= (1 - t)
    // gap_i + t gap_j - kappa t (1 - t): when its least value over t in [0, 1] exceeds the
    // margin, w holds the cone in the cube. Else the exact test (hull_dominated).
    auto cones_covered = [&](int i, double gap_i, std::uint8_t bit, int w, const Vec3& clo) {
      const double r = g_.sphere(i).radius;
      // All at once from i's largest reach (reach_[i] bounds each cone_reach_): the same
      // decision as the first test below on every cone, without reading the cones' entries.
      if (gap_i - reach_[i] * (2 * r + reach_[i]) > margin_) return true;
      const auto [first, last] = g_.cones_of_atom(i);
      for (const PrimitiveId* id = first; id != last; ++id) {
        const std::size_t p = static_cast<std::size_t>(id - cone_base);
        // First from i alone: the fill lies in B(c_i, r + reach), whose power is pow_i -
        // reach (2 r + reach); the balls themselves are held (i by w, j kept or held too).
        const double reach = cone_reach_[p];
        if (gap_i - reach * (2 * r + reach) > margin_) continue;
        const int j = cone_other_[p];
        if (kept[j] & bit) continue;
        const double gap_j = power_gap(j, w, clo, side);
        const double kappa = cone_kappa_[p];
        const double t = std::clamp((kappa + gap_i - gap_j) / (2 * kappa), 0.0, 1.0);
        if ((1 - t) * gap_i + t * gap_j - kappa * t * (1 - t) > margin_) continue;
        if (!hull_dominated(g_.cone(*id), w, clo, side)) return false;
      }
      return true;
    };
    thread_local std::vector<std::size_t> listed;  // the child's entries still listed
    for (int k = 0; k < 8; ++k) {
      std::vector<int>& witnesses = witnesses_of[k];
      if (count[k] < 2) continue;
      const std::uint8_t bit = static_cast<std::uint8_t>(1u << k);
      const Vec3 clo(lo[0][k & 1], lo[1][(k >> 1) & 1], lo[2][(k >> 2) & 1]);
      listed.clear();
      for (std::size_t x = 0; x < n; ++x)
        if (masks[x] & bit) listed.push_back(x);
      // The sample points: the centre first (round 0), then the corners (round 1), each one's
      // witness the ball of least power there, ties to the first listed (lowest id).
      std::array<Vec3, 9> samples;
      samples[0] = clo + Vec3::Constant(side / 2);
      for (int c = 0; c < 8; ++c)
        samples[1 + c] = clo + side * Vec3(c & 1, (c >> 1) & 1, (c >> 2) & 1);
      for (int round = 0; round < 2; ++round) {
        // Round 0 tests against the centre's witness, round 1 the balls left against the
        // corners' (a dropped ball is never the least power at a point of the cube).
        const std::size_t tested = witnesses.size();
        const int first = round == 0 ? 0 : 1, last = round == 0 ? 1 : 9;
        std::array<int, 9> best;
        std::array<double, 9> best_power;
        best.fill(-1);
        for (std::size_t x : listed) {  // one pass for the round's samples
          const int i = parent.spheres[x];
          for (int sample = first; sample < last; ++sample) {
            const double pw = power(i, samples[sample]);
            if (best[sample] < 0 || pw < best_power[sample]) {
              best[sample] = i;
              best_power[sample] = pw;
            }
          }
        }
        for (int sample = first; sample < last; ++sample)
          if (std::find(witnesses.begin(), witnesses.end(), best[sample]) == witnesses.end())
            witnesses.push_back(best[sample]);
        if (witnesses.size() == tested) continue;
        witness_terms.clear();
        for (std::size_t by = tested; by < witnesses.size(); ++by)
          witness_terms.emplace_back(g_.sphere(witnesses[by]));
        auto kept_entry = listed.begin();
        for (std::size_t x : listed) {
          const int i = parent.spheres[x];
          if (std::find(witnesses.begin(), witnesses.end(), i) == witnesses.end()) {
            // w covers i in the cube when pow_i - pow_w exceeds the margin on all of it.
            const PowerTerms terms(g_.sphere(i));
            std::size_t by = tested;
            while (by < witnesses.size() &&
                   !((gap = power_gap(terms, witness_terms[by - tested], clo, side)) > margin_))
              ++by;
            if (by < witnesses.size() &&
                (!cones || cones_covered(i, gap, bit, witnesses[by], clo))) {
              masks[x] = static_cast<std::uint8_t>(masks[x] & ~bit);
              if (cones) kept[i] = masks[x];
              --count[k];
              dropped = true;
              continue;
            }
          }
          *kept_entry++ = x;
        }
        listed.erase(kept_entry, listed.end());
      }
    }
    return dropped;
  }

  /// Whether the closed cube of a cell lies inside the solid of one of its listed cones or the
  /// prism of one of its listed slabs: both convex, so when its eight corners do. (A sparse
  /// medial mesh's slabs and cones are most of its volume, far from their balls: without this
  /// criterion 2 splits all of it down to depth d.)
  bool inside_a_listed_hull(const OctreeCell& cell) const {
    if (cell.cones.empty() && cell.slabs.empty()) return false;
    const Eigen::AlignedBox3d cube = tree_.cube(cell);
    std::array<Vec3, 8> corners;
    for (int k = 0; k < 8; ++k)
      corners[k] = cube.corner(static_cast<Eigen::AlignedBox3d::CornerType>(k));
    const int n = sphere_count();
    for (int k : cell.slabs) {
      const Slab& slab = g_.slab(g_.slab_id(k));
      if (std::all_of(corners.begin(), corners.end(),
                      [&](const Vec3& q) { return prism_depth(slab, q) >= 0; }))
        return true;
    }
    for (int k : cell.cones) {
      const Cone cone = g_.cone(n + k);
      if (std::all_of(corners.begin(), corners.end(),
                      [&](const Vec3& q) { return hull_distance(cone, q) <= 0; }))
        return true;
    }
    return false;
  }

  void finish() {
    for (std::size_t c = 0; c < tree_.cells.size(); ++c) {
      if (!tree_.cells[c].is_leaf()) continue;
      tree_.leaves.push_back(static_cast<int>(c));
      tree_.depth = std::max(tree_.depth, tree_.cells[c].level);
    }
    // Morton order of the cells' minimal corners at the deepest level, then level.
    const int depth = tree_.depth;
    auto morton = [&](int c) {
      const OctreeCell& cell = tree_.cells[c];
      std::uint64_t key = 0;
      for (int b = depth - 1; b >= 0; --b)
        for (int a = 2; a >= 0; --a)
          key = key << 1 | ((std::uint64_t(cell.ijk[a]) << (depth - cell.level)) >> b & 1);
      return std::make_pair(key, cell.level);
    };
    std::vector<std::pair<std::pair<std::uint64_t, int>, int>> keyed;
    keyed.reserve(tree_.leaves.size());
    for (int c : tree_.leaves) keyed.push_back({morton(c), c});
    std::sort(keyed.begin(), keyed.end());
    for (std::size_t i = 0; i < keyed.size(); ++i) tree_.leaves[i] = keyed[i].second;
  }

  const TargetShape& g_;
  const OctreeOptions& opt_;
  const bool joined_by_edges_ = g_.is_envelope();  // atoms joined by the medial mesh
  /// Balls covered in a cell by another are left out of its lists (OctreeOptions::prune_lists;
  /// not for an envelope, whose full sets read every hull of a listed ball).
  const bool prune_ = opt_.prune_lists && !g_.is_envelope();
  /// The power margin of a drop: far above the rounding of powers in the root's frame.
  const double margin_ = 1e-12 * g_.frame().cube_side * g_.frame().cube_side;
  std::vector<double> reach_;      // per atom (index_cones)
  std::vector<int> cone_other_;    // per entry of G's atom-to-cones index (index_cones)
  std::vector<float> cone_reach_;  // per entry of G's atom-to-cones index (index_cones)
  std::vector<float> cone_kappa_;  // per entry of G's atom-to-cones index (index_cones)
  Octree tree_;
};

}  // namespace

int automatic_min_depth(double root_side, double rc, int max_depth) {
  if (!std::isfinite(root_side))
    throw InvalidInput("the atoms' bounding cube has an infinite side: coordinates too large");
  int d = 0;
  while (std::ldexp(root_side, -d) > rc / 8) ++d;  // Octree::side(d)
  if (d > max_depth)
    throw InvalidInput("automatic minimal depth d = " + std::to_string(d) +
                       " exceeds the maximal depth " + std::to_string(max_depth) +
                       " (raise --max-depth or set --min-depth)");
  return d;
}

void check_octree_options(const OctreeOptions& opt) {
  if (opt.max_depth < 1 || opt.max_depth > 20)
    throw InvalidInput("max depth " + std::to_string(opt.max_depth) + " must be in [1, 20]");
  if (opt.min_depth < 0 || opt.min_depth > opt.max_depth)
    throw InvalidInput("min depth " + std::to_string(opt.min_depth) + " must be in [0, max depth " +
                       std::to_string(opt.max_depth) + "]");
}

Octree build_octree(const TargetShape& g, const OctreeOptions& opt) {
  if (!(g.frame().cube_side > 0))
    throw InvalidInput(
        "build_octree: G must be built in its atoms' bounding cube frame (bounding_cube_frame)");
  check_octree_options(opt);
  return OctreeBuilder(g, opt).run();
}

}  // namespace mg::garbing
