#pragma once
// Internal to mg::garbing (target_shape*.cpp): the bounding-volume hierarchy over G's primitives.

#include "garbing/target_shape.h"

#include "garbing/detail/line_box.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <queue>
#include <utility>
#include <vector>

namespace mg::garbing {
namespace detail {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// An axis-aligned box of the hierarchy (empty when lo > hi).
struct Box {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(kInf), hi = Eigen::Vector3d::Constant(-kInf);
  void grow(const Box& b) {
    lo = lo.cwiseMin(b.lo);
    hi = hi.cwiseMax(b.hi);
  }
  double squared_distance(const Eigen::Vector3d& p) const {
    return (lo - p).cwiseMax(p - hi).cwiseMax(0.0).squaredNorm();
  }
  bool overlaps(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const {
    return (lo.array() <= b.array()).all() && (a.array() <= hi.array()).all();
  }
  /// Parameter range of the ray o + t d inside the box, clipped to [t0, t1].
  bool clip(const Eigen::Vector3d& o, const Eigen::Vector3d& inv_d, double& t0, double& t1) const {
    return detail::clip_line_to_box(lo, hi, o, inv_d, t0, t1);
  }
};

/// A box as the hierarchy keeps it after the build: floats, each bound rounded outward (never
/// inside the double box it stands for), so a test against it errs only toward "may meet".
/// Half the memory of Box (at a million atoms, 4.3 million primitives' boxes and their nodes').
struct StoredBox {
  Eigen::Vector3f lo, hi;
  StoredBox() = default;
  explicit StoredBox(const Box& b) {
    for (int k = 0; k < 3; ++k) {
      lo[k] = down(b.lo[k]);
      hi[k] = up(b.hi[k]);
    }
  }
  static float down(double x) {
    const float f = static_cast<float>(x);
    return f > x ? std::nextafter(f, -std::numeric_limits<float>::infinity()) : f;
  }
  static float up(double x) {
    const float f = static_cast<float>(x);
    return f < x ? std::nextafter(f, std::numeric_limits<float>::infinity()) : f;
  }
  double squared_distance(const Eigen::Vector3d& p) const {
    return (lo.cast<double>() - p).cwiseMax(p - hi.cast<double>()).cwiseMax(0.0).squaredNorm();
  }
  bool overlaps(const Eigen::Vector3d& a, const Eigen::Vector3d& b) const {
    return (lo.cast<double>().array() <= b.array()).all() &&
           (a.array() <= hi.cast<double>().array()).all();
  }
  bool clip(const Eigen::Vector3d& o, const Eigen::Vector3d& inv_d, double& t0, double& t1) const {
    return detail::clip_line_to_box(lo.cast<double>(), hi.cast<double>(), o, inv_d, t0, t1);
  }
};

}  // namespace detail

/// A binary bounding-volume hierarchy over the primitives' boxes (binned surface-area splits,
/// the median on the longest axis below depth 48; up to 4 primitives per leaf).
struct TargetShape::Bvh {
  using Box = detail::Box;
  using StoredBox = detail::StoredBox;
  static constexpr double kInf = detail::kInf;

  struct Node {
    StoredBox box;
    int first = 0, count = 0;  // leaf: primitives order[first .. first + count)
    int right = -1;            // inner node: left child is the next node, right child here
  };
  std::vector<Node> nodes;
  std::vector<int> order;
  std::vector<StoredBox> boxes;  // the primitives' boxes, in `order`: a leaf's are contiguous
  std::vector<Box> boxes_by_id;  // during the build only: the primitives' boxes by id

  /// Over the primitives `ids` (their boxes indexed by id). The tree is built from the double
  /// boxes; the nodes and primitives keep them as StoredBox.
  void build(std::vector<Box> primitive_boxes, std::vector<int> ids) {
    boxes_by_id = std::move(primitive_boxes);
    order = std::move(ids);
    // A tree over m primitives has at most 2 m - 1 nodes. Reserved, not touched: only the
    // pages the nodes fill become resident, and no growth copies the array (at a million
    // atoms a copy was the peak of G's construction).
    nodes.reserve(2 * order.size());
    if (!order.empty()) build(nodes, 0, static_cast<int>(order.size()), 0);
    boxes.resize(order.size());
    tbb::parallel_for(std::size_t(0), order.size(), [&](std::size_t i) {
      boxes[i] = StoredBox(boxes_by_id[static_cast<std::size_t>(order[i])]);
    });
    std::vector<Box>().swap(boxes_by_id);
  }

  static double half_area(const Box& b) {
    const Eigen::Vector3d e = (b.hi - b.lo).cwiseMax(0.0);
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
    // The three axes' bins in one pass over the boxes.
    std::array<std::array<Box, kBins>, 3> bins_box;
    std::array<std::array<int, kBins>, 3> bins_count{};
    std::array<bool, 3> spread;
    for (int axis = 0; axis < 3; ++axis) spread[axis] = centres.hi[axis] - centres.lo[axis] > 0;
    for (int i = first; heuristic && i < last; ++i) {
      const Box& b = boxes_by_id[order[i]];
      for (int axis = 0; axis < 3; ++axis) {
        if (!spread[axis]) continue;
        const int k = bin_of(b, axis, centres.lo[axis], centres.hi[axis] - centres.lo[axis], kBins);
        bins_box[axis][k].grow(b);
        ++bins_count[axis][k];
      }
    }
    for (int axis = 0; heuristic && axis < 3; ++axis) {
      const double lo = centres.lo[axis], extent = centres.hi[axis] - lo;
      if (!(extent > 0)) continue;
      const std::array<Box, kBins>& bin_box = bins_box[axis];
      const std::array<int, kBins>& bin_count = bins_count[axis];
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
      const auto mid =
          std::stable_partition(order.begin() + first, order.begin() + last, [&](int id) {
            return bin_of(boxes_by_id[id], best_axis, lo, extent, kBins) <= best_bin;
          });
      return static_cast<int>(mid - order.begin());
    }
    Eigen::Index axis;
    (centres.hi - centres.lo).maxCoeff(&axis);
    const int mid = (first + last) / 2;
    std::nth_element(order.begin() + first, order.begin() + mid, order.begin() + last,
                     [&](int a, int b) {
                       const double ca = boxes_by_id[a].lo[axis] + boxes_by_id[a].hi[axis];
                       const double cb = boxes_by_id[b].lo[axis] + boxes_by_id[b].hi[axis];
                       return ca < cb || (ca == cb && a < b);
                     });
    return mid;
  }

  static int bin_of(const Box& b, int axis, double lo, double extent, int bins) {
    const double c = (b.lo[axis] + b.hi[axis]) / 2;
    const int k = static_cast<int>(bins * ((c - lo) / extent));
    return std::clamp(k, 0, bins - 1);
  }

  /// Subtrees over more primitives than this are built in parallel.
  static constexpr int kParallelBuild = 1 << 14;

  /// Appends the subtree over order[first, last) to `out` in depth-first order (the left child
  /// next, the right child at `right`), returns its root. Depth stays under 48 + 31 (median
  /// splits below 48): the traversal stacks hold 128. Large subtrees build their two halves in
  /// parallel into their own arrays, spliced in the same order: the same tree as one pass.
  int build(std::vector<Node>& out, int first, int last, int depth) {
    const int id = static_cast<int>(out.size());
    out.emplace_back();
    Box box, centres;
    for (int i = first; i < last; ++i) {
      box.grow(boxes_by_id[order[i]]);
      const Eigen::Vector3d c = (boxes_by_id[order[i]].lo + boxes_by_id[order[i]].hi) / 2;
      centres.grow({c, c});
    }
    out[id].box = StoredBox(box);
    if (last - first <= 4) {
      out[id].first = first;
      out[id].count = last - first;
      return id;
    }
    const int mid = split(first, last, centres, depth < 48);
    if (last - first < kParallelBuild) {
      build(out, first, mid, depth + 1);
      const int right = build(out, mid, last, depth + 1);
      out[id].right = right;
      return id;
    }
    // The left half goes straight after this node in `out`; the right one, built meanwhile in
    // its own array, is appended after it.
    std::vector<Node> right;
    right.reserve(2 * static_cast<std::size_t>(last - mid));
    tbb::parallel_invoke([&] { build(out, first, mid, depth + 1); },
                         [&] { build(right, mid, last, depth + 1); });
    const int offset = static_cast<int>(out.size());
    out[id].right = offset;
    for (Node n : right) {
      if (n.right >= 0) n.right += offset;
      out.push_back(n);
    }
    return id;
  }

  /// Visits the primitives whose boxes the segment origin + t dir, t in [0, t_max], crosses, in
  /// increasing order of the parameter where the segment enters their leaf node's box, until
  /// `more(t_entry)` says no node entered at t_entry or later can matter.
  template <class More, class Visit>
  void visit_along_ray(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, double t_max,
                       More&& more, Visit&& visit_primitive) const {
    if (nodes.empty()) return;
    const Eigen::Vector3d inv = dir.cwiseInverse();
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
  void visit_segment(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, Limit&& limit,
                     Visit&& visit_primitive) const {
    if (nodes.empty()) return;
    const Eigen::Vector3d inv = dir.cwiseInverse();
    // Slabs by the direction's signs (the same products as Box::clip, without its swaps);
    // Box::clip itself when a component of dir is 0 (its NaN guard).
    const bool generic = dir[0] != 0 && dir[1] != 0 && dir[2] != 0;
    int near_side[3];
    for (int k = 0; k < 3; ++k) near_side[k] = inv[k] < 0;
    auto clip = [&](const StoredBox& b, double& t0, double& t1) {
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

}  // namespace mg::garbing
