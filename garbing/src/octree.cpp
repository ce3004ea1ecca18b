#include "garbing/octree.h"

#include "garbing/detail/convex_search.h"
#include "garbing/errors.h"

#include <Eigen/Eigenvalues>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>

namespace mg {

double Octree::side(int level) const { return std::ldexp(root_side, -level); }

Eigen::AlignedBox3d Octree::cube(const OctreeCell& cell) const {
  const double s = side(cell.level);
  // Both corners as integer x side, each rounded once: the same doubles as any other point
  // of the lattice computed that way (an M1 face's corner, M2's dual vertex), which lo + side
  // can miss by an ulp.
  Eigen::Vector3d lo, hi;
  for (int a = 0; a < 3; ++a) {
    lo[a] = cell.ijk[a] * s;
    hi[a] = (cell.ijk[a] + 1.0) * s;
  }
  return {lo, hi};
}

Eigen::Vector3d Octree::to_local(const Eigen::Vector3d& world) const {
  return axes.transpose() * (world - origin);
}

Eigen::Vector3d Octree::to_world(const Eigen::Vector3d& local) const {
  return origin + axes * local;
}

int find_cell(const Octree& tree, int level, const std::array<std::int64_t, 3>& ijk) {
  const std::int64_t n = std::int64_t(1) << level;
  for (int a = 0; a < 3; ++a)
    if (ijk[a] < 0 || ijk[a] >= n) return -1;
  int c = 0;
  while (!tree.cells[c].is_leaf() && tree.cells[c].level < level) {
    const int shift = level - tree.cells[c].level - 1;
    int k = 0;
    for (int a = 0; a < 3; ++a) k |= static_cast<int>((ijk[a] >> shift) & 1) << a;
    c = tree.cells[c].first_child + k;
  }
  return c;
}

void leaves_facing(const Octree& tree, int c, const std::array<int, 3>& offset,
                   std::vector<int>& out) {
  const OctreeCell& cell = tree.cells[c];
  if (cell.is_leaf()) {
    out.push_back(c);
    return;
  }
  for (int k = 0; k < 8; ++k) {
    bool facing = true;
    for (int a = 0; a < 3; ++a) {
      const int bit = (k >> a) & 1;
      if ((offset[a] > 0 && bit != 0) || (offset[a] < 0 && bit != 1)) facing = false;
    }
    if (facing) leaves_facing(tree, cell.first_child + k, offset, out);
  }
}

void touching_leaves(const Octree& tree, int c, std::vector<int>& out) {
  out.clear();
  const OctreeCell& cell = tree.cells[c];
  const int n = cell.level;
  const std::int64_t size = std::int64_t(1) << n;
  for (int dz = -1; dz <= 1; ++dz)
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        if (dx == 0 && dy == 0 && dz == 0) continue;
        const std::array<int, 3> offset = {dx, dy, dz};
        std::array<std::int64_t, 3> nb;
        bool inside = true;
        int climb = 0;  // levels up to the common ancestor
        for (int a = 0; a < 3; ++a) {
          nb[a] = static_cast<std::int64_t>(cell.ijk[a]) + offset[a];
          if (nb[a] < 0 || nb[a] >= size) inside = false;
          else {
            const std::uint64_t diff = static_cast<std::uint64_t>(nb[a]) ^ cell.ijk[a];
            if (diff != 0) climb = std::max(climb, 64 - __builtin_clzll(diff));
          }
        }
        if (!inside) continue;
        int anc = c;
        for (int k = 0; k < climb; ++k) anc = tree.cells[anc].parent;
        // Descend from the common ancestor toward (n, nb).
        int d = anc;
        while (!tree.cells[d].is_leaf() && tree.cells[d].level < n) {
          const int shift = n - tree.cells[d].level - 1;
          int k = 0;
          for (int a = 0; a < 3; ++a) k |= static_cast<int>((nb[a] >> shift) & 1) << a;
          d = tree.cells[d].first_child + k;
        }
        leaves_facing(tree, d, offset, out);
      }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

namespace {

using Vec3 = Eigen::Vector3d;

using detail::box_distance;
using detail::convex_reaches_zero;

/// The solid of a cone (make_cone: axis, rims), the convex hull of its two balls, as the union
/// of the balls B(c(t), r(t)), c and r linear in t in [0, 1]; every function of t below is
/// convex.
struct Hull {
  Cone k;
  double dr = 0;         ///< second radius - first
  double lipschitz = 0;  ///< |c2 - c1| + |dr|: bounds the slope in t of every function below
  /// The crease: the circle where the two spheres meet (axial coordinate x0 from c1, radius
  /// rho0). In the profile half-plane (along the axis, from the axis) the part of the hull
  /// outside both balls lies inside the triangle of the crease point and the two rims.
  double x0 = 0, rho0 = 0;
  std::array<double, 2> fill_lo = {0, 0}, fill_hi = {0, 0};  ///< the triangle's box (x, radius)
  Vec3 centre(double t) const { return k.c1 + (t * k.length) * k.u; }
  double radius(double t) const { return k.r1 + t * dr; }
};

Hull make_hull(const MedialAtom& first, const MedialAtom& second) {
  Hull h;
  h.k = make_cone(first, second, -1, -1);
  const double L = h.k.length, r1 = first.radius, r2 = second.radius;
  h.dr = r2 - r1;
  h.lipschitz = L + std::abs(h.dr);
  h.x0 = (L * L + r1 * r1 - r2 * r2) / (2 * L);
  h.rho0 = std::sqrt(std::max(0.0, r1 * r1 - h.x0 * h.x0));
  h.fill_lo = {std::min({h.x0, h.k.t_lo, h.k.t_hi}), std::min({h.rho0, h.k.rho_lo, h.k.rho_hi})};
  h.fill_hi = {std::max({h.x0, h.k.t_lo, h.k.t_hi}), std::max({h.rho0, h.k.rho_lo, h.k.rho_hi})};
  return h;
}

/// The hull's distance function (target_shape.h): <= 0 exactly when p is inside.
double hull_distance(const Hull& h, const Vec3& p) { return mg::hull_distance(h.k, p); }

/// Squared distance from the point (x, y) to the segment (ax, ay)-(bx, by).
double segment_distance2(double x, double y, double ax, double ay, double bx, double by) {
  const double ux = bx - ax, uy = by - ay;
  const double len2 = ux * ux + uy * uy;
  double t = len2 > 0 ? ((x - ax) * ux + (y - ay) * uy) / len2 : 0;
  t = std::clamp(t, 0.0, 1.0);
  const double dx = x - ax - t * ux, dy = y - ay - t * uy;
  return dx * dx + dy * dy;
}

/// False when the cube [lo, lo + side] is too far from the crease fill to meet it: the fill,
/// revolved about the axis, lies in the triangle (crease point, rim 1, rim 2) of the profile
/// half-plane, so the distance from the cube's centre to the fill is at least its distance to
/// that triangle in the centre's own meridian half-plane; compared with the half diagonal.
/// Monotone: a cube is near whenever one of its children is.
bool near_crease(const Hull& h, const Vec3& lo, double side) {
  const double half_diagonal = side * (std::sqrt(3.0) / 2);
  const Vec3 q = lo + Vec3::Constant(side / 2) - h.k.c1;
  const double x = q.dot(h.k.u);
  if (x < h.fill_lo[0] - half_diagonal || x > h.fill_hi[0] + half_diagonal) return false;
  // The distance from the axis, squared first: a looser test (by a relative 1e-12, more than
  // the rounding of the squares) spares most square roots and rejects nothing kept below.
  const double y2 = q.cross(h.k.u).squaredNorm();
  const double y_hi = h.fill_hi[1] + half_diagonal, y_lo = h.fill_lo[1] - half_diagonal;
  if (y2 > y_hi * y_hi * (1 + 1e-12) || (y_lo > 0 && y2 < y_lo * y_lo * (1 - 1e-12))) return false;
  const double y = std::sqrt(y2);
  if (y < y_lo || y > y_hi) return false;  // off the triangle's box
  const double bound2 = 0.75 * side * side;  // (half diagonal)^2
  // Inside the triangle: the same side of its three edges.
  const Cone& k = h.k;
  auto cross = [&](double ax, double ay, double bx, double by) { return (bx - ax) * (y - ay) - (by - ay) * (x - ax); };
  const double c1 = cross(h.x0, h.rho0, k.t_lo, k.rho_lo);
  const double c2 = cross(k.t_lo, k.rho_lo, k.t_hi, k.rho_hi);
  const double c3 = cross(k.t_hi, k.rho_hi, h.x0, h.rho0);
  if ((c1 >= 0 && c2 >= 0 && c3 >= 0) || (c1 <= 0 && c2 <= 0 && c3 <= 0)) return true;
  return segment_distance2(x, y, h.x0, h.rho0, k.t_lo, k.rho_lo) <= bound2 ||
         segment_distance2(x, y, k.t_lo, k.rho_lo, k.t_hi, k.rho_hi) <= bound2 ||
         segment_distance2(x, y, k.t_hi, k.rho_hi, h.x0, h.rho0) <= bound2;
}

/// Whether the closed cube [lo, lo + side], which meets neither of the two balls, meets the
/// hull (up to 1e-9 of its slope bound, counted as meeting).
bool hull_meets_cube_outside_balls(const Hull& h, const Vec3& lo, double side) {
  if (!near_crease(h, lo, side)) return false;
  const Vec3 centre = lo + Vec3::Constant(side / 2);
  const double from_centre = hull_distance(h, centre);
  if (from_centre <= side / 2) return true;                      // inscribed ball
  if (from_centre > side * (std::sqrt(3.0) / 2)) return false;   // circumscribed ball
  return convex_reaches_zero(
      [&, hi = Vec3(lo + Vec3::Constant(side))](double t) { return box_distance(lo, hi, h.centre(t)) - h.radius(t); },
      h.lipschitz);
}

/// Whether two hulls meet: min over (s, t) of |c(s) - c'(t)| - r(s) - r'(t) <= 0, jointly
/// convex, its inner minimum in closed form (hull_distance).
bool hulls_meet(const Hull& a, const Hull& b) {
  return convex_reaches_zero([&](double s) { return hull_distance(b, a.centre(s)) - a.radius(s); },
                             a.lipschitz);
}

/// Principal axes of the atom centres as right-handed columns, largest variance first, each
/// of the first two with its largest component positive; identity when two eigenvalues are
/// repeated (one atom, two atoms, a ring, a regular solid...).
Eigen::Matrix3d principal_axes(const MedialSurface& s) {
  Vec3 mean = Vec3::Zero();
  for (const auto& a : s.atoms) mean += a.centre;
  mean /= static_cast<double>(s.atoms.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& a : s.atoms) cov += (a.centre - mean) * (a.centre - mean).transpose();
  cov /= static_cast<double>(s.atoms.size());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  const Vec3 l = eig.eigenvalues();  // ascending
  const double tolerance = 1e-9 * std::max(std::abs(l[2]), 1e-300);
  if (!(l[1] - l[0] > tolerance && l[2] - l[1] > tolerance)) return Eigen::Matrix3d::Identity();
  Eigen::Matrix3d axes;
  for (int k = 0; k < 2; ++k) {
    Vec3 e = eig.eigenvectors().col(2 - k);
    Eigen::Index big = 0;
    e.cwiseAbs().maxCoeff(&big);
    if (e[big] < 0) e = -e;
    axes.col(k) = e.normalized();
  }
  axes.col(2) = axes.col(0).cross(axes.col(1)).normalized();
  return axes;
}

/// Builds the octree by rounds: each round evaluates the criteria on the new leaves (in
/// parallel, reading the tree only), then splits every marked cell in index order. The marks
/// are a pure function of the tree, so the result does not depend on thread count or order.
class OctreeBuilder {
 public:
  OctreeBuilder(const MedialSurface& atoms, const OctreeOptions& opt) : atoms_(atoms), opt_(opt) {}

  Octree run() {
    set_frame();
    OctreeCell root;
    root.spheres.resize(atoms_.atoms.size());
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
    tree_.axes = principal_axes(atoms_);
    tree_.max_depth = opt_.max_depth;
    local_.reserve(atoms_.atoms.size());
    Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
    for (const auto& a : atoms_.atoms) {
      const Vec3 p = tree_.axes.transpose() * a.centre;
      local_.push_back(p);
      lo = lo.cwiseMin(p - Vec3::Constant(a.radius));
      hi = hi.cwiseMax(p + Vec3::Constant(a.radius));
    }
    tree_.root_side = (hi - lo).maxCoeff();
    const Vec3 corner = (lo + hi) / 2 - Vec3::Constant(tree_.root_side / 2);
    for (Vec3& p : local_) p -= corner;
    tree_.origin = tree_.axes * corner;
    tree_.rc = characteristic_radius(atoms_);
    const auto t0 = std::chrono::steady_clock::now();
    tree_.cone_pairs = cone_pairs(atoms_, opt_.cones);
    tree_.seconds_cone_pairs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    hulls_.reserve(tree_.cone_pairs.size());
    for (const auto& [a, b] : tree_.cone_pairs)
      hulls_.push_back(make_hull({local_[a], atoms_.atoms[a].radius}, {local_[b], atoms_.atoms[b].radius}));
    cones_by_atom_start_.assign(atoms_.atoms.size() + 1, 0);
    for (const auto& [a, b] : tree_.cone_pairs) {
      ++cones_by_atom_start_[a + 1];
      ++cones_by_atom_start_[b + 1];
    }
    for (std::size_t i = 0; i < atoms_.atoms.size(); ++i) cones_by_atom_start_[i + 1] += cones_by_atom_start_[i];
    cones_by_atom_.resize(2 * tree_.cone_pairs.size());
    std::vector<int> fill(cones_by_atom_start_.begin(), cones_by_atom_start_.end() - 1);
    for (std::size_t k = 0; k < tree_.cone_pairs.size(); ++k)
      for (int i : tree_.cone_pairs[k]) cones_by_atom_[fill[i]++] = static_cast<int>(k);
    if (opt_.min_depth > 0) {
      tree_.min_depth = opt_.min_depth;
    } else {
      int d = 0;
      while (tree_.side(d) > tree_.rc / 8) ++d;
      if (d > opt_.max_depth)
        throw InvalidInput("automatic minimal depth d = " + std::to_string(d) +
                           " exceeds the maximal depth " + std::to_string(opt_.max_depth) +
                           " (raise --max-depth or set --min-depth)");
      tree_.min_depth = d;
    }
  }

  bool criterion(int k) const { return opt_.criteria[k - 1]; }

  Vec3 cell_lo(const OctreeCell& c) const { return tree_.cube(c).min(); }

  bool ball_contains_cell(int i, const Vec3& lo, double side) const {
    const Vec3& p = local_[i];
    double d2 = 0;
    for (int a = 0; a < 3; ++a) {
      const double d = std::max(std::abs(p[a] - lo[a]), std::abs(p[a] - lo[a] - side));
      d2 += d * d;
    }
    const double r = atoms_.atoms[i].radius;
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
    const double r = atoms_.atoms[i].radius + atoms_.atoms[j].radius;
    return (local_[i] - local_[j]).squaredNorm() <= r * r;
  }

  /// Primitive ids of the criteria: sphere i is i, cone k is n + k (n atoms).
  int sphere_count() const { return static_cast<int>(atoms_.atoms.size()); }

  /// Whether two primitives meet (closed solids). A cone meets its own balls and any cone
  /// sharing one; otherwise exact up to 1e-9 of the hull's slope bound, counted as meeting.
  bool primitives_meet(int p, int q) const {
    const int n = sphere_count();
    if (p > q) std::swap(p, q);
    if (q < n) return balls_intersect(p, q);
    const auto& kq = tree_.cone_pairs[q - n];
    if (p < n) {
      if (p == kq[0] || p == kq[1]) return true;
      return hull_distance(hulls_[q - n], local_[p]) <= atoms_.atoms[p].radius;
    }
    const auto& kp = tree_.cone_pairs[p - n];
    if (kp[0] == kq[0] || kp[0] == kq[1] || kp[1] == kq[0] || kp[1] == kq[1]) return true;
    return hulls_meet(hulls_[p - n], hulls_[q - n]);
  }

  /// Primitives(c): Spheres(c) then n + Cones(c), sorted; Spheres(c) itself when there are
  /// no cones, else built in `scratch`.
  const std::vector<int>& primitives(const OctreeCell& cell, std::vector<int>& scratch) const {
    if (cell.cones.empty()) return cell.spheres;
    scratch.assign(cell.spheres.begin(), cell.spheres.end());
    for (int k : cell.cones) scratch.push_back(sphere_count() + k);
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

  /// Criterion 3's test: some primitive of cell `a` meets some primitive of cell `b` (a
  /// shared one counts), read from the cells' sorted sphere and cone lists without merging
  /// them. Spheres are tried against spheres first.
  bool sets_intersect(const OctreeCell& a, const OctreeCell& b) const {
    if (share_one(a.spheres, b.spheres) || share_one(a.cones, b.cones)) return true;
    for (int s : a.spheres)
      for (int t : b.spheres)
        if (balls_intersect(s, t)) return true;
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
    return false;
  }

  /// Whether two sorted lists share an element.
  static bool share_one(const std::vector<int>& a, const std::vector<int>& b) {
    auto i = a.begin();
    auto j = b.begin();
    while (i != a.end() && j != b.end()) {
      if (*i == *j) return true;
      if (*i < *j) ++i; else ++j;
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
    const bool exempt = opt_.skip_interior_cells && cell.inside_one_ball;
    const int d = tree_.min_depth;
    if (criterion(2) && cell.level < d && !exempt) marks.emplace_back(c, 2);
    const bool test_1 = criterion(1) && cell.level >= d && !cell.inside_one_ball;
    const bool test_3 = criterion(3) && cell.level >= d && !cell.inside_one_ball;
    if (test_1 && !primitives_connected(primitives(cell, mine))) marks.emplace_back(c, 1);
    if (!criterion(3) && !criterion(4)) return;
    touching_leaves(tree_, c, touching);
    for (int t : touching) {
      const OctreeCell& other = tree_.cells[t];
      if (!other.is_active() || (t >= first_candidate && t > c)) continue;
      if (criterion(4) && std::abs(cell.level - other.level) > 1 && contact_dimension(cell, other) >= 1)
        marks.emplace_back(cell.level < other.level ? c : t, 4);
      if (test_3 && other.level >= d && !other.inside_one_ball) {
        if (!sets_intersect(cell, other)) {
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

  /// Splits each marked leaf once (first reason counted), returns the new children.
  std::vector<int> split(const std::vector<std::pair<int, int>>& marks) {
    std::vector<int> to_split;
    for (std::size_t i = 0; i < marks.size(); ++i) {
      if (i > 0 && marks[i].first == marks[i - 1].first) continue;
      const int c = marks[i].first;
      if (!tree_.cells[c].is_leaf()) continue;
      if (tree_.cells[c].level >= opt_.max_depth) {
        tree_.hit_max_depth = true;
        continue;
      }
      ++tree_.splits[marks[i].second - 1];
      to_split.push_back(c);
    }
    // Children's sphere lists, filtered from the parent's, in parallel.
    std::vector<std::array<OctreeCell, 8>> children(to_split.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, to_split.size(), 16),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t i = r.begin(); i != r.end(); ++i)
                          make_children(to_split[i], children[i]);
                      });
    std::vector<int> created;
    created.reserve(8 * to_split.size());
    for (std::size_t i = 0; i < to_split.size(); ++i) {
      const int first = static_cast<int>(tree_.cells.size());
      tree_.cells[to_split[i]].first_child = first;
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
    // masks[x]: the children met by the ball parent.spheres[x], bit k for child k.
    std::vector<std::uint8_t> masks(parent.spheres.size(), 0);
    std::array<std::size_t, 8> count = {};
    for (std::size_t x = 0; x < parent.spheres.size(); ++x) {
      const int i = parent.spheres[x];
      const Vec3& p = local_[i];
      const double r = atoms_.atoms[i].radius;
      const double r2 = r * r;
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
    // The lists, sized once, in the parent's (sorted) order.
    for (int k = 0; k < 8; ++k) out[k].spheres.reserve(count[k]);
    for (std::size_t x = 0; x < parent.spheres.size(); ++x)
      for (unsigned m = masks[x]; m != 0; m &= m - 1) out[__builtin_ctz(m)].spheres.push_back(parent.spheres[x]);
    // Cones(child), the cones whose solid meets the cube while neither of their balls does:
    // candidates are the parent's and those of the parent's balls (a cone meets a sub-cube
    // only if it meets the cube). A cube inside one ball holds no boundary and is never tested
    // by criteria 1 and 3: its children need none (they are active through that ball).
    if (parent.inside_one_ball || tree_.cone_pairs.empty()) return;
    // Per thread: each atom's child mask in this parent, and a stamp per cone against repeats.
    thread_local std::vector<std::uint8_t> mask_of_atom;
    thread_local std::vector<std::uint64_t> stamp;
    thread_local std::uint64_t generation = 0;
    if (mask_of_atom.size() != atoms_.atoms.size()) mask_of_atom.assign(atoms_.atoms.size(), 0);
    if (stamp.size() != tree_.cone_pairs.size()) {
      stamp.assign(tree_.cone_pairs.size(), 0);
      generation = 0;
    }
    ++generation;
    // Children inside one ball are left without: the same reason.
    unsigned skip = 0;
    for (int j = 0; j < 8; ++j) skip |= static_cast<unsigned>(out[j].inside_one_ball) << j;
    if (skip == 0xFF) return;
    for (std::size_t x = 0; x < parent.spheres.size(); ++x) mask_of_atom[parent.spheres[x]] = masks[x];
    const Vec3 parent_lo(lo[0][0], lo[1][0], lo[2][0]);
    auto consider = [&](int k) {
      if (stamp[k] == generation) return;
      stamp[k] = generation;
      const auto& [a, b] = tree_.cone_pairs[k];
      const unsigned via_ball = mask_of_atom[a] | mask_of_atom[b];
      if ((via_ball | skip) == 0xFF || !near_crease(hulls_[k], parent_lo, 2 * side)) return;
      for (int j = 0; j < 8; ++j)
        if (!(skip >> j & 1) && !(via_ball >> j & 1) &&
            hull_meets_cube_outside_balls(hulls_[k], Vec3(lo[0][j & 1], lo[1][(j >> 1) & 1], lo[2][(j >> 2) & 1]),
                                          side))
          out[j].cones.push_back(k);
    };
    for (int k : parent.cones) consider(k);
    for (std::size_t x = 0; x < parent.spheres.size(); ++x)
      if (masks[x] != 0xFF) {
        const int i = parent.spheres[x];
        for (int e = cones_by_atom_start_[i]; e < cones_by_atom_start_[i + 1]; ++e) consider(cones_by_atom_[e]);
      }
    for (int i : parent.spheres) mask_of_atom[i] = 0;
    for (auto& child : out) std::sort(child.cones.begin(), child.cones.end());
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

  const MedialSurface& atoms_;
  const OctreeOptions& opt_;
  std::vector<Vec3> local_;  // atom centres in the root frame
  std::vector<Hull> hulls_;  // the cones' solids in the root frame, by index in cone_pairs
  std::vector<int> cones_by_atom_start_, cones_by_atom_;  // CSR: atom -> its cones, sorted
  Octree tree_;
};

}  // namespace

Octree build_octree(const MedialSurface& atoms, const OctreeOptions& opt) {
  validate(atoms);
  if (opt.max_depth < 1 || opt.max_depth > 20)
    throw InvalidInput("max depth " + std::to_string(opt.max_depth) + " must be in [1, 20]");
  if (opt.min_depth < 0 || opt.min_depth > opt.max_depth)
    throw InvalidInput("min depth " + std::to_string(opt.min_depth) + " must be in [0, max depth " +
                       std::to_string(opt.max_depth) + "]");
  return OctreeBuilder(atoms, opt).run();
}

}  // namespace mg
