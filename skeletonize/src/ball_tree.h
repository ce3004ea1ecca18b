#pragma once
// Internal to mg::skeletonize: a static hierarchy over balls, for merging and clamping poles.

#include "core/medial_surface.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace mg::skeletonize::detail {

using Vec3 = Eigen::Vector3d;

/// Static bounding-volume hierarchy over balls (median splits of centres and radii; each node
/// keeps the box of its centres, its largest radius and a sphere enclosing its balls).
class BallTree {
 public:
  explicit BallTree(const std::vector<MedialAtom>& balls) : balls_(balls), index_(balls.size()) {
    std::iota(index_.begin(), index_.end(), 0);
    if (!balls.empty()) build(0, static_cast<int>(balls.size()));
  }

  /// Calls visit(j), in a fixed order, for every ball j that meets the ball (c, r), until visit
  /// returns true. Returns whether it did.
  template <class Visit>
  bool find_meeting(const Vec3& c, double r, Visit&& visit) const {
    return search(
        [&](const Node& n) {
          const double reach = n.max_radius + r;
          return n.box.squaredExteriorDistance(c) <= reach * reach;
        },
        [&](int j) {
          const double reach = balls_[j].radius + r;
          return (balls_[j].centre - c).squaredNorm() <= reach * reach;
        },
        visit);
  }

  /// The same for every ball j that contains the ball (c, r) up to `slack`:
  /// |c - c_j| + r <= r_j + slack.
  template <class Visit>
  bool find_containing(const Vec3& c, double r, double slack, Visit&& visit) const {
    return search(
        [&](const Node& n) {
          const double reach = n.max_radius - r + slack, room = n.sphere_radius + slack - r;
          return reach >= 0 && room >= 0 && n.box.squaredExteriorDistance(c) <= reach * reach &&
                 (c - n.sphere_centre).squaredNorm() <= room * room;
        },
        [&](int j) { return (balls_[j].centre - c).norm() + r <= balls_[j].radius + slack; },
        visit);
  }

  /// max over the balls j of r_j - |p - c_j|, starting from the lower bound `at_least` (-inf
  /// when none is known): how deep p lies in the deepest ball (negative: outside every ball, by at
  /// most its magnitude). The answer is exact; a good `at_least` only prunes more. `which`, if
  /// given, receives the ball attaining it (the smallest index among ties; untouched when none
  /// beats `at_least`).
  double deepest(const Vec3& p, double at_least = -INFINITY, int* which = nullptr) const {
    if (nodes_.empty()) return at_least;
    double best = at_least;
    auto bound = [&](const Node& n) {
      // Every ball of the node lies in its bounding sphere and has its centre in its box.
      return std::min(n.max_radius - std::sqrt(n.box.squaredExteriorDistance(p)),
                      n.sphere_radius - (p - n.sphere_centre).norm());
    };
    int stack[128];
    double stack_bound[128];
    int top = 0;
    stack[top] = 0;
    stack_bound[top++] = bound(nodes_[0]);
    while (top > 0) {
      --top;
      if (stack_bound[top] <= best) continue;
      const Node& n = nodes_[stack[top]];
      if (n.left < 0) {
        for (int k = n.begin; k < n.end; ++k) {
          const MedialAtom& b = balls_[index_[k]];
          const double d = b.radius - (p - b.centre).norm();
          if (d > best || (which && d == best && index_[k] < *which)) {
            best = d;
            if (which) *which = index_[k];
          }
        }
        continue;
      }
      const double bl = bound(nodes_[n.left]), br = bound(nodes_[n.right]);
      // The more promising child on top.
      if (bl >= br) {
        stack[top] = n.right;
        stack_bound[top++] = br;
        stack[top] = n.left;
        stack_bound[top++] = bl;
      } else {
        stack[top] = n.left;
        stack_bound[top++] = bl;
        stack[top] = n.right;
        stack_bound[top++] = br;
      }
    }
    return best;
  }

 private:
  struct Node {
    Eigen::AlignedBox3d box;
    double max_radius = 0;
    Vec3 sphere_centre = Vec3::Zero();
    double sphere_radius = 0;
    int begin = 0, end = 0, left = -1, right = -1;
  };

  template <class NodeTest, class BallTest, class Visit>
  bool search(NodeTest&& node_may_hold, BallTest&& ball_matches, Visit&& visit) const {
    if (nodes_.empty()) return false;
    int stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& n = nodes_[stack[--top]];
      if (!node_may_hold(n)) continue;
      if (n.left < 0) {
        for (int k = n.begin; k < n.end; ++k)
          if (ball_matches(index_[k]) && visit(index_[k])) return true;
      } else {
        stack[top++] = n.right;
        stack[top++] = n.left;
      }
    }
    return false;
  }

  int build(int begin, int end) {
    const int id = static_cast<int>(nodes_.size());
    nodes_.emplace_back();
    Node n;
    n.begin = begin;
    n.end = end;
    for (int k = begin; k < end; ++k) {
      n.box.extend(balls_[index_[k]].centre);
      n.max_radius = std::max(n.max_radius, balls_[index_[k]].radius);
    }
    n.sphere_centre = n.box.center();
    for (int k = begin; k < end; ++k) {
      const MedialAtom& b = balls_[index_[k]];
      n.sphere_radius = std::max(n.sphere_radius, (b.centre - n.sphere_centre).norm() + b.radius);
    }
    n.sphere_radius *= 1 + 1e-12;  // the rounding of the norms above
    if (end - begin > 16) {
      // Split the longest of the four extents (x, y, z, radius): nodes of similar radii keep
      // the containment bound max_radius - r tight.
      double min_radius = INFINITY;
      for (int k = begin; k < end; ++k) min_radius = std::min(min_radius, balls_[index_[k]].radius);
      int axis = 0;
      const double extent = n.box.sizes().maxCoeff(&axis);
      if (n.max_radius - min_radius > extent) axis = 3;
      auto key = [&](int a) { return axis < 3 ? balls_[a].centre[axis] : balls_[a].radius; };
      const int mid = (begin + end) / 2;
      std::nth_element(
          index_.begin() + begin, index_.begin() + mid, index_.begin() + end,
          [&](int a, int b) { return key(a) < key(b) || (key(a) == key(b) && a < b); });
      n.left = build(begin, mid);
      n.right = build(mid, end);
    }
    nodes_[id] = n;
    return id;
  }

  const std::vector<MedialAtom>& balls_;
  std::vector<int> index_;
  std::vector<Node> nodes_;
};

}  // namespace mg::skeletonize::detail
