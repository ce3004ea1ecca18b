#include "garbing/target_shape.h"

#include "garbing/detail/convex_search.h"
#include "garbing/detail/line_box.h"
#include "garbing/errors.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <queue>

#include <tbb/parallel_for.h>

namespace mg {

using Vec3 = Eigen::Vector3d;

ConeSource parse_cone_source(const std::string& name) {
  if (name == "rt") return ConeSource::regular_triangulation;
  if (name == "all") return ConeSource::all_pairs;
  if (name == "edges") return ConeSource::ma_edges;
  if (name == "none") return ConeSource::none;
  throw InvalidInput("unknown cone source '" + name + "' (expected rt, all, edges or none)");
}

Cone make_cone(const MedialAtom& first, const MedialAtom& second, int a, int b) {
  Cone c;
  c.a = a;
  c.b = b;
  c.c1 = first.centre;
  c.r1 = first.radius;
  c.r2 = second.radius;
  const Vec3 axis = second.centre - first.centre;
  c.length = axis.norm();
  c.u = axis / c.length;
  c.sin_phi = (first.radius - second.radius) / c.length;
  c.cos_phi = std::sqrt(std::max(0.0, 1 - c.sin_phi * c.sin_phi));
  c.t_lo = first.radius * c.sin_phi;
  c.rho_lo = first.radius * c.cos_phi;
  c.t_hi = c.length + second.radius * c.sin_phi;
  c.rho_hi = second.radius * c.cos_phi;
  const double half = (c.t_hi - c.t_lo) / 2, rim = std::max(c.rho_lo, c.rho_hi);
  c.bound_centre = c.c1 + (c.t_lo + half) * c.u;
  c.bound_radius2 = half * half + rim * rim;
  return c;
}

double hull_distance(const Cone& k, const Vec3& p) {
  const Vec3 q = p - k.c1;
  const double x = q.dot(k.u), y = q.cross(k.u).norm();  // a cross product: accurate near the axis
  const double dr = k.r2 - k.r1;
  // cos(phi) = 0 only when rounding makes one ball hold the other: the hull is the larger.
  double t = k.cos_phi > 0 ? (x - k.sin_phi * y / k.cos_phi) / k.length : (dr > 0 ? 1.0 : 0.0);
  t = std::clamp(t, 0.0, 1.0);
  return (p - (k.c1 + (t * k.length) * k.u)).norm() - (k.r1 + t * dr);
}

Vec3 migration_vector(const MedialAtom& sphere, const Vec3& v) {
  const Vec3 d = v - sphere.centre;
  const double d2 = d.squaredNorm();
  if (d2 == 0) return Vec3::Zero();
  return sphere.radius * d / d2;
}

Vec3 migration_vector(const Cone& cone, const Vec3& v) {
  const Vec3 w = v - cone.c1;
  const double x = w.dot(cone.u);
  const double rho = (w - x * cone.u).norm();
  if (rho == 0) return Vec3::Zero();
  const double t = x - rho * cone.sin_phi / cone.cos_phi;  // foot of the normal on the axis
  if (t < 0 || t > cone.length) return Vec3::Zero();
  const Vec3 d = v - (cone.c1 + t * cone.u);
  const double r = cone.r1 - t * cone.sin_phi;  // radius of the ball tangent there
  return r * d / d.squaredNorm();
}

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Box {
  Vec3 lo = Vec3::Constant(kInf), hi = Vec3::Constant(-kInf);
  void grow(const Box& b) {
    lo = lo.cwiseMin(b.lo);
    hi = hi.cwiseMax(b.hi);
  }
  double squared_distance(const Vec3& p) const {
    return (lo - p).cwiseMax(p - hi).cwiseMax(0.0).squaredNorm();
  }
  bool overlaps(const Vec3& a, const Vec3& b) const {
    return (lo.array() <= b.array()).all() && (a.array() <= hi.array()).all();
  }
  /// Parameter range of the ray o + t d inside the box, clipped to [t0, t1].
  bool clip(const Vec3& o, const Vec3& inv_d, double& t0, double& t1) const {
    return detail::clip_line_to_box(lo, hi, o, inv_d, t0, t1);
  }
};

Box sphere_box(const MedialAtom& s) {
  return {s.centre - Vec3::Constant(s.radius), s.centre + Vec3::Constant(s.radius)};
}

using detail::box_distance;

/// Interval of the ray o + t d inside the closed ball; false if it misses.
bool ray_sphere(const MedialAtom& s, const Vec3& o, const Vec3& d, double& t0, double& t1) {
  const Vec3 oc = o - s.centre;
  const double a = d.squaredNorm();
  const double half_b = oc.dot(d);
  const double c = oc.squaredNorm() - s.radius * s.radius;
  const double disc = half_b * half_b - a * c;
  if (disc < 0 || a == 0) return false;
  const double root = std::sqrt(disc);
  // Stable pair of roots.
  const double q = half_b >= 0 ? -(half_b + root) : -(half_b - root);
  double x0 = q / a, x1 = q != 0 ? c / q : -half_b / a;
  if (x0 > x1) std::swap(x0, x1);
  t0 = x0;
  t1 = x1;
  return true;
}

/// Interval of the ray o + t d inside the solid truncated cone; false if it misses.
bool ray_cone(const Cone& k, const Vec3& o, const Vec3& d, double& t0, double& t1) {
  const Vec3 w = o - k.c1;
  const double ot = w.dot(k.u), dt = d.dot(k.u);
  {
    // Cheap rejection: a line missing the frustum's bounding ball (with slack for rounding)
    // misses the frustum.
    const Vec3 wm = o - k.bound_centre;
    const double wd = wm.dot(d);
    if (wm.squaredNorm() - wd * wd / d.squaredNorm() > k.bound_radius2 * (1 + 1e-9)) return false;
  }
  const Vec3 op = w - ot * k.u, dp = d - dt * k.u;
  // Slab t_lo <= axial <= t_hi.
  double lo = -kInf, hi = kInf;
  if (dt != 0) {
    double a = (k.t_lo - ot) / dt, b = (k.t_hi - ot) / dt;
    if (a > b) std::swap(a, b);
    lo = a;
    hi = b;
  } else if (ot < k.t_lo || ot > k.t_hi) {
    return false;
  }
  // rho(t)^2 <= R(t)^2 with R(axial) = (r1 - axial sin) / cos, linear in t: alpha + beta t.
  const double alpha = (k.r1 - ot * k.sin_phi) / k.cos_phi;
  const double beta = -dt * k.sin_phi / k.cos_phi;
  const double A = dp.squaredNorm() - beta * beta;
  const double B = 2 * (op.dot(dp) - alpha * beta);
  const double C = op.squaredNorm() - alpha * alpha;
  const double scale = d.squaredNorm();
  double qlo = -kInf, qhi = kInf;
  if (std::abs(A) <= 1e-14 * scale) {  // parallel to a generator: linear
    if (B > 0) qhi = -C / B;
    else if (B < 0) qlo = -C / B;
    else if (C > 0) return false;
  } else {
    const double disc = B * B - 4 * A * C;
    if (A > 0) {
      if (disc < 0) return false;
      const double root = std::sqrt(disc);
      qlo = (-B - root) / (2 * A);
      qhi = (-B + root) / (2 * A);
    } else if (disc >= 0) {
      // q <= 0 outside the roots: two rays, one per nappe; keep the one where R >= 0.
      const double root = std::sqrt(disc);
      const double s0 = (-B + root) / (2 * A), s1 = (-B - root) / (2 * A);  // s0 <= s1
      const double ra = std::max(lo, -kInf), rb = std::min(hi, s0);
      const double sa = std::max(lo, s1), sb = std::min(hi, kInf);
      auto radius_ok = [&](double x0, double x1) {
        if (!(x0 <= x1)) return false;
        const double mid = std::isfinite(x0) && std::isfinite(x1) ? (x0 + x1) / 2
                           : std::isfinite(x0) ? x0 : x1;
        return alpha + beta * mid >= 0;
      };
      if (radius_ok(ra, rb)) {
        qhi = s0;
      } else if (radius_ok(sa, sb)) {
        qlo = s1;
      } else {
        return false;
      }
    }  // disc < 0 with A < 0: q < 0 everywhere
  }
  t0 = std::max(lo, qlo);
  t1 = std::min(hi, qhi);
  return t0 <= t1;
}

/// Closest point of the solid cone to p, and whether p is inside it.
Vec3 cone_closest_solid_point(const Cone& k, const Vec3& p) {
  const Vec3 w = p - k.c1;
  const double x = w.dot(k.u);
  Vec3 radial = w - x * k.u;
  double rho = radial.norm();
  const Vec3 e = rho > 0 ? Vec3(radial / rho) : Vec3(k.u.unitOrthogonal());
  // In the (axial, radial) half-plane the solid is the quadrilateral
  // (t_lo, 0) (t_hi, 0) (t_hi, rho_hi) (t_lo, rho_lo).
  const double R = (k.r1 - x * k.sin_phi) / k.cos_phi;
  if (x >= k.t_lo && x <= k.t_hi && rho <= R) return p;
  // Candidates: clamp to caps, to the generator segment.
  auto to3 = [&](double t, double r) { return Vec3(k.c1 + t * k.u + r * e); };
  double best = kInf;
  Vec3 out = p;
  auto consider = [&](double t, double r) {
    const double d2 = (t - x) * (t - x) + (r - rho) * (r - rho);
    if (d2 < best) {
      best = d2;
      out = to3(t, r);
    }
  };
  consider(k.t_lo, std::min(rho, k.rho_lo));
  consider(k.t_hi, std::min(rho, k.rho_hi));
  const double gt = k.t_hi - k.t_lo, gr = k.rho_hi - k.rho_lo;
  const double s = std::clamp(((x - k.t_lo) * gt + (rho - k.rho_lo) * gr) / (gt * gt + gr * gr), 0.0, 1.0);
  consider(k.t_lo + s * gt, k.rho_lo + s * gr);
  return out;
}

/// Closest point on the cone's lateral surface to p (p may be inside).
Vec3 cone_closest_lateral_point(const Cone& k, const Vec3& p) {
  const Vec3 w = p - k.c1;
  const double x = w.dot(k.u);
  const Vec3 radial = w - x * k.u;
  const double rho = radial.norm();
  const Vec3 e = rho > 0 ? Vec3(radial / rho) : Vec3(k.u.unitOrthogonal());
  const double gt = k.t_hi - k.t_lo, gr = k.rho_hi - k.rho_lo;
  const double s = std::clamp(((x - k.t_lo) * gt + (rho - k.rho_lo) * gr) / (gt * gt + gr * gr), 0.0, 1.0);
  return k.c1 + (k.t_lo + s * gt) * k.u + (k.rho_lo + s * gr) * e;
}

/// The 26 directions of a cube's faces, edges and corners, unit length.
const std::vector<Vec3>& probe_directions() {
  static const std::vector<Vec3> dirs = [] {
    std::vector<Vec3> out;
    for (int x = -1; x <= 1; ++x)
      for (int y = -1; y <= 1; ++y)
        for (int z = -1; z <= 1; ++z)
          if (x || y || z) out.push_back(Vec3(x, y, z).normalized());
    return out;
  }();
  return dirs;
}

}  // namespace

/// A binary bounding-volume hierarchy over the primitives' boxes (median split on the longest
/// axis of the box centres; up to 4 primitives per leaf).
struct TargetShape::Bvh {
  struct Node {
    Box box;
    int first = 0, count = 0;  // leaf: primitives order[first .. first + count)
    int right = -1;            // inner node: left child is the next node, right child here
  };
  std::vector<Node> nodes;
  std::vector<int> order;
  std::vector<Box> boxes;  // during build: by primitive id; after: in `order`

  /// Over the primitives `ids` (their boxes indexed by id).
  void build(std::vector<Box> primitive_boxes, std::vector<int> ids) {
    boxes = std::move(primitive_boxes);
    order = std::move(ids);
    nodes.reserve(2 * order.size() / 4 + 2);
    if (!order.empty()) build(0, static_cast<int>(order.size()), 0);
    // From now on boxes[i] is the box of primitive order[i]: a leaf's boxes are contiguous.
    std::vector<Box> in_order(order.size());
    for (std::size_t i = 0; i < order.size(); ++i) in_order[i] = boxes[order[i]];
    boxes = std::move(in_order);
  }

  static double half_area(const Box& b) {
    const Vec3 e = (b.hi - b.lo).cwiseMax(0.0);
    return e[0] * e[1] + e[1] * e[2] + e[2] * e[0];
  }

  /// Partitions order[first, last) and returns the split point: the binned surface-area
  /// heuristic over 16 bins of box centres per axis (overlapping ball boxes make median splits
  /// poor), the median on the longest axis when no bin boundary separates the centres or
  /// `heuristic` is off.
  int split(int first, int last, const Box& centres, bool heuristic) {
    constexpr int kBins = 16;
    double best_cost = kInf;
    int best_axis = -1, best_bin = -1;
    for (int axis = 0; heuristic && axis < 3; ++axis) {
      const double lo = centres.lo[axis], extent = centres.hi[axis] - lo;
      if (!(extent > 0)) continue;
      std::array<Box, kBins> bin_box;
      std::array<int, kBins> bin_count{};
      for (int i = first; i < last; ++i) {
        const Box& b = boxes[order[i]];
        const int k = bin_of(b, axis, lo, extent, kBins);
        bin_box[k].grow(b);
        ++bin_count[k];
      }
      std::array<double, kBins> right_cost{};
      Box acc;
      int n = 0;
      for (int k = kBins - 1; k > 0; --k) {
        acc.grow(bin_box[k]);
        n += bin_count[k];
        right_cost[k] = n ? half_area(acc) * n : 0;
      }
      acc = Box();
      n = 0;
      for (int k = 0; k + 1 < kBins; ++k) {  // left = bins [0, k], right = bins [k + 1, end)
        acc.grow(bin_box[k]);
        n += bin_count[k];
        if (n == 0 || n == last - first) continue;
        const double cost = half_area(acc) * n + right_cost[k + 1];
        if (cost < best_cost) {
          best_cost = cost;
          best_axis = axis;
          best_bin = k;
        }
      }
    }
    if (best_axis >= 0) {
      const double lo = centres.lo[best_axis], extent = centres.hi[best_axis] - lo;
      const auto mid = std::stable_partition(order.begin() + first, order.begin() + last, [&](int id) {
        return bin_of(boxes[id], best_axis, lo, extent, kBins) <= best_bin;
      });
      return static_cast<int>(mid - order.begin());
    }
    Eigen::Index axis;
    (centres.hi - centres.lo).maxCoeff(&axis);
    const int mid = (first + last) / 2;
    std::nth_element(order.begin() + first, order.begin() + mid, order.begin() + last,
                     [&](int a, int b) {
                       const double ca = boxes[a].lo[axis] + boxes[a].hi[axis];
                       const double cb = boxes[b].lo[axis] + boxes[b].hi[axis];
                       return ca < cb || (ca == cb && a < b);
                     });
    return mid;
  }

  static int bin_of(const Box& b, int axis, double lo, double extent, int bins) {
    const double c = (b.lo[axis] + b.hi[axis]) / 2;
    const int k = static_cast<int>(bins * ((c - lo) / extent));
    return std::clamp(k, 0, bins - 1);
  }

  /// Depth stays under 48 + 31 (median splits below 48): the traversal stacks hold 128.
  int build(int first, int last, int depth) {
    const int id = static_cast<int>(nodes.size());
    nodes.emplace_back();
    Box box, centres;
    for (int i = first; i < last; ++i) {
      box.grow(boxes[order[i]]);
      const Vec3 c = (boxes[order[i]].lo + boxes[order[i]].hi) / 2;
      centres.grow({c, c});
    }
    nodes[id].box = box;
    if (last - first <= 4) {
      nodes[id].first = first;
      nodes[id].count = last - first;
      return id;
    }
    const int mid = split(first, last, centres, depth < 48);
    build(first, mid, depth + 1);
    const int right = build(mid, last, depth + 1);
    nodes[id].right = right;
    return id;
  }

  /// Visits the primitives whose boxes the segment origin + t dir, t in [0, t_max], crosses, in
  /// increasing order of the parameter where the segment enters their leaf node's box, until
  /// `more(t_entry)` says no node entered at t_entry or later can matter.
  template <class More, class Visit>
  void visit_along_ray(const Vec3& origin, const Vec3& dir, double t_max, More&& more,
                       Visit&& visit_primitive) const {
    if (nodes.empty()) return;
    const Vec3 inv = dir.cwiseInverse();
    using Entry = std::pair<double, int>;
    std::priority_queue<Entry, std::vector<Entry>, std::greater<>> queue;
    auto push = [&](int id) {
      double a = 0, z = t_max;
      if (nodes[id].box.clip(origin, inv, a, z)) queue.push({a, id});
    };
    push(0);
    while (!queue.empty()) {
      const auto [t, id] = queue.top();
      queue.pop();
      if (!more(t)) return;
      const Node& n = nodes[id];
      if (n.right < 0) {
        for (int i = n.first; i < n.first + n.count; ++i) visit_primitive(order[i]);
      } else {
        push(id + 1);
        push(n.right);
      }
    }
  }

  /// Depth first along the segment origin + t dir, t in [0, limit()], the nearer child first;
  /// `limit()` may shrink as primitives are visited, and nodes entered beyond it are skipped.
  /// Stops when `visit_primitive` returns false.
  template <class Limit, class Visit>
  void visit_segment(const Vec3& origin, const Vec3& dir, Limit&& limit, Visit&& visit_primitive) const {
    if (nodes.empty()) return;
    const Vec3 inv = dir.cwiseInverse();
    // Slabs by the direction's signs (the same products as Box::clip, without its swaps);
    // Box::clip itself when a component of dir is 0 (its NaN guard).
    const bool generic = dir[0] != 0 && dir[1] != 0 && dir[2] != 0;
    int near_side[3];
    for (int k = 0; k < 3; ++k) near_side[k] = inv[k] < 0;
    auto clip = [&](const Box& b, double& t0, double& t1) {
      if (!generic) return b.clip(origin, inv, t0, t1);
      for (int k = 0; k < 3; ++k) {
        const double enter = ((near_side[k] ? b.hi : b.lo)[k] - origin[k]) * inv[k];
        const double leave = ((near_side[k] ? b.lo : b.hi)[k] - origin[k]) * inv[k];
        t0 = std::max(t0, enter);
        t1 = std::min(t1, leave);
      }
      return t0 <= t1;
    };
    std::pair<int, double> stack[128];  // (node, parameter where the segment enters its box)
    int top = 0;
    double a = 0, z = limit();
    if (!clip(nodes[0].box, a, z)) return;
    stack[top++] = {0, a};
    while (top > 0) {
      const auto [id, entry] = stack[--top];
      if (entry > limit()) continue;
      const Node& n = nodes[id];
      if (n.right < 0) {
        for (int i = n.first; i < n.first + n.count; ++i) {
          double b0 = 0, b1 = limit();
          if (clip(boxes[i], b0, b1) && !visit_primitive(order[i])) return;
        }
        continue;
      }
      double l0 = 0, l1 = limit(), r0 = 0, r1 = limit();
      const bool left = clip(nodes[id + 1].box, l0, l1);
      const bool right = clip(nodes[n.right].box, r0, r1);
      if (left && right) {
        if (l0 <= r0) {
          stack[top++] = {n.right, r0};
          stack[top++] = {id + 1, l0};
        } else {
          stack[top++] = {id + 1, l0};
          stack[top++] = {n.right, r0};
        }
      } else if (left) {
        stack[top++] = {id + 1, l0};
      } else if (right) {
        stack[top++] = {n.right, r0};
      }
    }
  }

  /// Visits every primitive whose box passes `keep_box`, in no particular order.
  template <class KeepBox, class Visit>
  void visit(KeepBox&& keep_box, Visit&& visit_primitive) const {
    if (nodes.empty()) return;
    int stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& n = nodes[stack[--top]];
      if (!keep_box(n.box)) continue;
      if (n.right < 0) {
        for (int i = n.first; i < n.first + n.count; ++i)
          if (keep_box(boxes[i])) visit_primitive(order[i]);
      } else {
        stack[top++] = n.right;
        stack[top++] = static_cast<int>(&n - nodes.data()) + 1;
      }
    }
  }
};

TargetShape::TargetShape(const MedialSurface& atoms, const std::vector<std::array<int, 2>>& pairs)
    : spheres_(atoms.atoms), bvh_(std::make_unique<Bvh>()) {
  cones_.reserve(pairs.size());
  for (const auto& p : pairs) cones_.push_back(make_cone(atoms.atoms[p[0]], atoms.atoms[p[1]], p[0], p[1]));
  cones_by_atom_start_.assign(spheres_.size() + 1, 0);
  for (const auto& c : cones_) {
    ++cones_by_atom_start_[c.a + 1];
    ++cones_by_atom_start_[c.b + 1];
  }
  for (std::size_t i = 0; i < spheres_.size(); ++i) cones_by_atom_start_[i + 1] += cones_by_atom_start_[i];
  cones_by_atom_.resize(2 * cones_.size());
  std::vector<int> fill(cones_by_atom_start_.begin(), cones_by_atom_start_.end() - 1);
  for (std::size_t k = 0; k < cones_.size(); ++k) {
    const int id = static_cast<int>(spheres_.size() + k);
    cones_by_atom_[fill[cones_[k].a]++] = id;
    cones_by_atom_[fill[cones_[k].b]++] = id;
  }
  std::vector<Box> boxes;
  boxes.reserve(spheres_.size() + cones_.size());
  for (const auto& s : spheres_) boxes.push_back(sphere_box(s));
  for (const auto& c : cones_) {
    // The frustum's own box: the boxes of its two end disks (a disk of radius rho and unit
    // normal u spans rho * sqrt(1 - u_k^2) along axis k). Much tighter than the balls' boxes.
    const Vec3 half = c.u.cwiseAbs2().unaryExpr([](double x) { return std::sqrt(std::max(0.0, 1 - x)); });
    Box b;
    for (const auto& [t, rho] : {std::make_pair(c.t_lo, c.rho_lo), std::make_pair(c.t_hi, c.rho_hi)}) {
      const Vec3 o = c.c1 + t * c.u;
      b.grow({o - rho * half, o + rho * half});
    }
    boxes.push_back(b);
  }
  std::vector<int> ids(boxes.size());
  std::iota(ids.begin(), ids.end(), 0);
  bvh_->build(std::move(boxes), std::move(ids));
}

TargetShape::~TargetShape() = default;
TargetShape::TargetShape(TargetShape&&) noexcept = default;
TargetShape& TargetShape::operator=(TargetShape&&) noexcept = default;

Vec3 TargetShape::migration_vector(PrimitiveId i, const Vec3& v) const {
  return is_sphere(i) ? mg::migration_vector(spheres_[i], v) : mg::migration_vector(cone(i), v);
}

bool TargetShape::primitive_contains(PrimitiveId i, const Vec3& p, double eps) const {
  if (is_sphere(i)) {
    const double r = spheres_[i].radius - eps;
    return r > 0 && (p - spheres_[i].centre).squaredNorm() < r * r;
  }
  const Cone& k = cone(i);
  const Vec3 w = p - k.c1;
  const double x = w.dot(k.u);
  if (x < k.t_lo + eps || x > k.t_hi - eps) return false;
  const double rho = (w - x * k.u).norm();
  // Distance to the lateral surface in the (axial, radial) plane: (R(x) - rho) cos(phi).
  return ((k.r1 - x * k.sin_phi) / k.cos_phi - rho) * k.cos_phi > eps;
}

bool TargetShape::contains(const Vec3& p) const {
  bool inside = false;
  bvh_->visit([&](const Box& b) { return !inside && b.squared_distance(p) == 0; },
              [&](int i) {
                if (inside) return;
                if (is_sphere(i)) {
                  const double r = spheres_[i].radius;
                  inside = (p - spheres_[i].centre).squaredNorm() <= r * r;
                } else {
                  inside = cone_closest_solid_point(cone(i), p) == p;
                }
              });
  return inside;
}

bool TargetShape::within(const Vec3& p, double tol) const {
  bool found = false;
  const double tol2 = tol * tol;
  bvh_->visit([&](const Box& b) { return !found && b.squared_distance(p) <= tol2; },
              [&](int i) {
                if (found) return;
                if (is_sphere(i)) {
                  const double r = spheres_[i].radius + tol;
                  found = (p - spheres_[i].centre).squaredNorm() <= r * r;
                } else {
                  found = hull_distance(cone(i), p) <= tol;
                }
              });
  return found;
}

bool TargetShape::ray_interval(PrimitiveId i, const Vec3& origin, const Vec3& dir, double& t0,
                               double& t1) const {
  return is_sphere(i) ? ray_sphere(spheres_[i], origin, dir, t0, t1) : ray_cone(cone(i), origin, dir, t0, t1);
}

bool TargetShape::line_to_boundary(const Vec3& v, const Vec3& dir, double t_max, double& t,
                                   bool& inside) const {
  // Outside, only the first entry matters: depth first along [0, t_max], the segment cut at
  // each entry found, nearer boxes first. An interval holding t = 0 (v inside) is never cut
  // off (its box holds v) and ends the walk. Only from inside (rare: M1 lies outside G, within
  // a leaf) is the whole segment [-t_max, t_max] collected.
  inside = false;
  double first = kInf;
  bvh_->visit_segment(v, dir, [&] { return std::min(first, t_max); }, [&](int i) {
    double a, z;
    if (!ray_interval(i, v, dir, a, z) || z < 0) return true;
    if (a <= 0) {
      inside = true;
      return false;
    }
    if (a <= t_max) first = std::min(first, a);
    return true;
  });
  if (!inside) {
    if (first > t_max) return false;
    t = first;
    return true;
  }
  thread_local std::vector<std::pair<double, double>> runs;  // in units of dir from v
  runs.clear();
  bvh_->visit_segment(v - t_max * dir, dir, [&] { return 2 * t_max; }, [&](int i) {
    double a, z;
    if (ray_interval(i, v, dir, a, z) && z >= -t_max && a <= t_max) runs.emplace_back(a, z);
    return true;
  });
  // Leave the union toward negative t: merge the runs containing 0 downward.
  std::sort(runs.begin(), runs.end(), [](const auto& x, const auto& y) { return x.second > y.second; });
  const double slack = 1e-12 * (1 + t_max);
  double end = 0;
  for (const auto& [a, z] : runs) {
    if (z < end - slack) break;
    end = std::min(end, a);
  }
  if (end < -t_max) return false;
  t = end;
  return true;
}

bool TargetShape::first_entry(const Vec3& origin, const Vec3& dir, double t_max, double& t) const {
  // Best-first along the ray: nodes entered after the best entry so far cannot improve it.
  double best = kInf;
  bvh_->visit_along_ray(origin, dir, t_max, [&](double entry) { return entry < best; },
                        [&](int i) {
                          double a, z;
                          if (ray_interval(i, origin, dir, a, z) && a >= 0 && a < best) best = a;
                        });
  if (best > t_max) return false;
  t = best;
  return true;
}

bool TargetShape::run_end(const Vec3& origin, const Vec3& dir, double t_max, double& t) const {
  // Grow the run [.., end] in order of entry: an interval joins when it starts before the end;
  // later ones wait in a heap until the end reaches them. Nodes entered after the end (plus
  // slack) cannot extend it.
  const double slack = 1e-12 * (1 + t_max);
  double end = 0;
  bool started = false;
  using Interval = std::pair<double, double>;
  std::priority_queue<Interval, std::vector<Interval>, std::greater<>> waiting;
  auto absorb = [&](double a, double z) {
    if (a <= end + slack) {
      started = started || a <= slack;
      if (z > end) {
        end = z;
        while (!waiting.empty() && waiting.top().first <= end + slack) {
          end = std::max(end, waiting.top().second);
          waiting.pop();
        }
      }
    } else {
      waiting.push({a, z});
    }
  };
  bvh_->visit_along_ray(origin, dir, t_max, [&](double entry) { return entry <= end + slack && end <= t_max; },
                        [&](int i) {
                          double a, z;
                          if (ray_interval(i, origin, dir, a, z) && z >= 0) absorb(a, z);
                        });
  if (!started || end > t_max) return false;  // not inside, or the run goes on past t_max
  t = end;
  return true;
}

Vec3 TargetShape::closest_point(const Vec3& p) const {
  if (!contains(p)) {
    // Outside: the nearest point of any primitive's solid, by branch and bound.
    double best = kInf;
    Vec3 out = p;
    std::priority_queue<std::pair<double, int>, std::vector<std::pair<double, int>>, std::greater<>> queue;
    if (!bvh_->nodes.empty()) queue.push({bvh_->nodes[0].box.squared_distance(p), 0});
    while (!queue.empty()) {
      const auto [d2, id] = queue.top();
      queue.pop();
      if (d2 >= best) break;
      const auto& n = bvh_->nodes[id];
      if (n.right >= 0) {
        queue.push({bvh_->nodes[id + 1].box.squared_distance(p), id + 1});
        queue.push({bvh_->nodes[n.right].box.squared_distance(p), n.right});
        continue;
      }
      for (int k = n.first; k < n.first + n.count; ++k) {
        const int i = bvh_->order[k];
        Vec3 q;
        if (is_sphere(i)) {
          const Vec3 d = p - spheres_[i].centre;
          q = spheres_[i].centre + spheres_[i].radius * d / d.norm();
        } else {
          q = cone_closest_solid_point(cone(i), p);
        }
        const double e2 = (q - p).squaredNorm();
        if (e2 < best) {
          best = e2;
          out = q;
        }
      }
    }
    return out;
  }
  // Inside: the nearest exposed candidate. Candidates: each containing primitive's nearest
  // surface point, tried nearest first (the first exposed one bounds the rest); the circles of
  // pairs of those spheres, which lie no nearer than either sphere's own point; and, only if
  // nothing was found, the exits along 26 directions.
  struct Candidate {
    double distance;
    int id;
    Vec3 point;
  };
  std::vector<Candidate> around;
  const double on_surface = -1e-12 * (1 + p.norm());  // p on a surface counts as inside it
  bvh_->visit([&](const Box& b) { return b.squared_distance(p) == 0; },
              [&](int i) {
                if (!primitive_contains(i, p, on_surface)) return;
                Vec3 q;
                if (is_sphere(i)) {
                  const Vec3 d = p - spheres_[i].centre;
                  q = spheres_[i].centre +
                      spheres_[i].radius * (d.squaredNorm() > 0 ? Vec3(d.normalized()) : Vec3(Vec3::UnitX()));
                } else {
                  q = cone_closest_lateral_point(cone(i), p);
                }
                around.push_back({(q - p).norm(), i, q});
              });
  std::sort(around.begin(), around.end(), [](const Candidate& a, const Candidate& b) {
    return a.distance < b.distance || (a.distance == b.distance && a.id < b.id);
  });
  auto exposed = [&](const Vec3& q, int i, int j) {
    const double eps = 1e-12 * (1 + q.norm());
    bool free = true;
    bvh_->visit([&](const Box& bb) { return free && bb.squared_distance(q) == 0; },
                [&](int k) { free = free && (k == i || k == j || !primitive_contains(k, q, eps)); });
    return free;
  };
  double best = kInf;
  Vec3 out = p;
  for (const Candidate& c : around) {
    if (c.distance >= best) break;
    if (exposed(c.point, c.id, c.id)) {
      best = c.distance;
      out = c.point;
      break;
    }
  }
  for (std::size_t x = 0; x < around.size() && around[x].distance < best; ++x) {
    if (!is_sphere(around[x].id)) continue;
    for (std::size_t y = x + 1; y < around.size() && around[y].distance < best; ++y) {
      if (!is_sphere(around[y].id)) continue;
      const MedialAtom& a = spheres_[around[x].id];
      const MedialAtom& b = spheres_[around[y].id];
      const Vec3 axis = b.centre - a.centre;
      const double L = axis.norm();
      if (!(L < a.radius + b.radius) || !(L > std::abs(a.radius - b.radius))) continue;
      const Vec3 n = axis / L;
      const double along = (L * L + a.radius * a.radius - b.radius * b.radius) / (2 * L);
      const double radius = std::sqrt(std::max(0.0, a.radius * a.radius - along * along));
      const Vec3 centre = a.centre + along * n;
      Vec3 radial = (p - centre) - (p - centre).dot(n) * n;
      if (radial.squaredNorm() == 0) radial = n.unitOrthogonal();
      const Vec3 q = centre + radius * radial.normalized();
      const double d = (q - p).norm();
      if (d < best && exposed(q, around[x].id, around[y].id)) {
        best = d;
        out = q;
      }
    }
  }
  if (std::isfinite(best)) return out;
  // Exits along probe directions, the nearest candidate's direction first: its exit bounds the
  // others, which then stop as soon as their run passes it.
  auto probe = [&](const Vec3& d) {
    double t;
    if (run_end(p, d, std::isfinite(best) ? best : 1e300, t) && t < best) {
      best = t;
      out = p + t * d;
    }
  };
  if (!around.empty() && around.front().distance > 0) probe((around.front().point - p).normalized());
  for (const Vec3& d : probe_directions()) probe(d);
  return out;
}

namespace {

/// splitmix64: a counter-based stream, so sample k depends only on (seed, k).
std::uint64_t mix(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

double uniform(std::uint64_t seed, std::uint64_t k, int j) {
  return static_cast<double>(mix(seed * 0x632be59bd9b4e019ULL + 4 * k + static_cast<std::uint64_t>(j)) >> 11) *
         0x1.0p-53;
}

}  // namespace

std::vector<Vec3> TargetShape::sample_boundary(std::size_t count, std::uint64_t seed) const {
  const std::size_t n = spheres_.size() + cones_.size();
  std::vector<double> cumulative(n);
  double total = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (is_sphere(static_cast<int>(i))) {
      total += 4 * M_PI * spheres_[i].radius * spheres_[i].radius;
    } else {
      const Cone& k = cone(static_cast<int>(i));
      const double slant = std::hypot(k.t_hi - k.t_lo, k.rho_hi - k.rho_lo);
      total += M_PI * (k.rho_lo + k.rho_hi) * slant;
    }
    cumulative[i] = total;
  }
  std::vector<Vec3> points(count);
  std::vector<char> keep(count, 0);
  tbb::parallel_for(std::size_t(0), count, [&](std::size_t k) {
    const double pick = uniform(seed, k, 0) * total;
    const int i = static_cast<int>(std::min<std::size_t>(
        std::upper_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin(), n - 1));
    const double u = uniform(seed, k, 1), v = uniform(seed, k, 2);
    Vec3 q;
    if (is_sphere(i)) {
      const double z = 2 * u - 1, phi = 2 * M_PI * v, s = std::sqrt(std::max(0.0, 1 - z * z));
      q = spheres_[i].centre + spheres_[i].radius * Vec3(s * std::cos(phi), s * std::sin(phi), z);
    } else {
      // Lateral area element ~ rho(s): invert the cumulative of a linear density on [0, 1].
      const Cone& c = cone(i);
      const double a = c.rho_lo, b = c.rho_hi;
      const double s = std::abs(b - a) < 1e-15 * (a + b)
                           ? u
                           : (std::sqrt(a * a + u * (b * b - a * a)) - a) / (b - a);
      const Vec3 e1 = c.u.unitOrthogonal(), e2 = c.u.cross(e1);
      const double phi = 2 * M_PI * v;
      q = c.c1 + (c.t_lo + s * (c.t_hi - c.t_lo)) * c.u +
          (a + s * (b - a)) * (std::cos(phi) * e1 + std::sin(phi) * e2);
    }
    const double eps = 1e-12 * (1 + q.norm());
    bool exposed = true;
    bvh_->visit([&](const Box& bb) { return exposed && bb.squared_distance(q) == 0; },
                [&](int j) { exposed = exposed && (j == i || !primitive_contains(j, q, eps)); });
    points[k] = q;
    keep[k] = exposed;
  });
  std::vector<Vec3> out;
  for (std::size_t k = 0; k < count; ++k)
    if (keep[k]) out.push_back(points[k]);
  return out;
}

void TargetShape::primitives_meeting_box(const Vec3& lo, const Vec3& hi, std::vector<PrimitiveId>& out) const {
  const std::size_t start = out.size();
  bvh_->visit([&](const Box& b) { return b.overlaps(lo, hi); },
              [&](int i) {
                if (is_sphere(i)) {
                  if (box_distance(lo, hi, spheres_[i].centre) <= spheres_[i].radius) out.push_back(i);
                  return;
                }
                const Cone& k = cone(i);
                const MedialAtom& s1 = spheres_[k.a];
                const MedialAtom& s2 = spheres_[k.b];
                if (box_distance(lo, hi, s1.centre) <= s1.radius || box_distance(lo, hi, s2.centre) <= s2.radius) {
                  out.push_back(i);
                  return;
                }
                // The hull of the two balls is the union of the interpolated balls: the gap
                // dist(c(s), box) - r(s) is convex in s, its slope at most |c2 - c1| + |r2 - r1|.
                const Vec3 d = s2.centre - s1.centre;
                const double dr = s2.radius - s1.radius;
                if (detail::convex_reaches_zero(
                        [&](double s) { return box_distance(lo, hi, s1.centre + s * d) - (s1.radius + s * dr); },
                        d.norm() + std::abs(dr)))
                  out.push_back(i);
              });
  std::sort(out.begin() + static_cast<long>(start), out.end());
}

}  // namespace mg
