#include "garbing/octree.h"

#include "garbing/errors.h"

#include <Eigen/Eigenvalues>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace mg {

double Octree::side(int level) const { return std::ldexp(root_side, -level); }

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

void active_leaves_containing(const Octree& tree, const Eigen::Vector3d& local, std::vector<int>& out) {
  out.clear();
  if (tree.cells.empty()) return;
  int stack[64 * 8];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const int c = stack[--top];
    const OctreeCell& cell = tree.cells[c];
    const double side = tree.side(cell.level);
    bool inside = true;
    for (int a = 0; a < 3; ++a) {
      const double lo = cell.ijk[a] * side;
      if (local[a] < lo || local[a] > lo + side) inside = false;
    }
    if (!inside) continue;
    if (cell.is_leaf()) {
      if (cell.is_active()) out.push_back(c);
    } else {
      for (int k = 0; k < 8; ++k) stack[top++] = cell.first_child + k;
    }
  }
  std::sort(out.begin(), out.end());
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

  Vec3 cell_lo(const OctreeCell& c) const {
    const double s = tree_.side(c.level);
    return Vec3(c.ijk[0] * s, c.ijk[1] * s, c.ijk[2] * s);
  }

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

  /// Criterion 1: the intersection graph of Spheres(c) is connected. Breadth-first search
  /// that scans only the spheres not reached yet, so dense overlaps cost about linear time.
  bool spheres_connected(const std::vector<int>& spheres) const {
    if (spheres.size() < 2) return true;
    std::vector<int> unreached(spheres.begin() + 1, spheres.end());
    std::vector<int> stack = {spheres.front()};
    while (!stack.empty() && !unreached.empty()) {
      const int s = stack.back();
      stack.pop_back();
      auto keep = unreached.begin();
      for (int t : unreached) {
        if (balls_intersect(s, t))
          stack.push_back(t);
        else
          *keep++ = t;
      }
      unreached.erase(keep, unreached.end());
    }
    return unreached.empty();
  }

  /// Criterion 3's test: some sphere of `a` intersects some sphere of `b` (a shared sphere
  /// counts). Both lists are sorted.
  bool sets_intersect(const std::vector<int>& a, const std::vector<int>& b) const {
    auto i = a.begin();
    auto j = b.begin();
    while (i != a.end() && j != b.end()) {
      if (*i == *j) return true;
      if (*i < *j) ++i; else ++j;
    }
    for (int s : a)
      for (int t : b)
        if (balls_intersect(s, t)) return true;
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

  /// Criterion marks of one candidate leaf (reads the tree only).
  void evaluate_cell(int c, std::vector<std::pair<int, int>>& marks,
                     std::vector<int>& touching) const {
    const OctreeCell& cell = tree_.cells[c];
    if (!cell.is_active()) return;
    const bool exempt = opt_.skip_interior_cells && cell.inside_one_ball;
    const int d = tree_.min_depth;
    if (criterion(2) && cell.level < d && !exempt) marks.emplace_back(c, 2);
    if (criterion(1) && cell.level >= d && !cell.inside_one_ball && !spheres_connected(cell.spheres))
      marks.emplace_back(c, 1);
    if (!criterion(3) && !criterion(4)) return;
    touching_leaves(tree_, c, touching);
    for (int t : touching) {
      const OctreeCell& other = tree_.cells[t];
      if (!other.is_active()) continue;
      if (criterion(4) && std::abs(cell.level - other.level) > 1 && contact_dimension(cell, other) >= 1)
        marks.emplace_back(cell.level < other.level ? c : t, 4);
      if (criterion(3) && cell.level >= d && other.level >= d && !cell.inside_one_ball &&
          !other.inside_one_ball && !sets_intersect(cell.spheres, other.spheres)) {
        if (cell.level <= other.level) marks.emplace_back(c, 3);
        if (other.level <= cell.level) marks.emplace_back(t, 3);
      }
    }
  }

  std::vector<std::pair<int, int>> evaluate(const std::vector<int>& candidates) const {
    std::vector<std::vector<std::pair<int, int>>> per(candidates.size());
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, candidates.size(), 64),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        std::vector<int> touching;
                        for (std::size_t i = r.begin(); i != r.end(); ++i)
                          evaluate_cell(candidates[i], per[i], touching);
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
    for (int i : parent.spheres) {
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
        OctreeCell& child = out[k];
        child.spheres.push_back(i);
        if (!child.inside_one_ball) {
          double e2 = 0;
          e2 += far[0][b0];
          e2 += far[1][b1];
          e2 += far[2][b2];
          child.inside_one_ball = e2 <= r2;
        }
      }
    }
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
