#pragma once
/// \file detail/line_box.h
/// Internal: where a line runs through an axis-aligned box, shared by G's hierarchy
/// (TargetShape) and M2's walk along a vertex's line through the octree's leaves.

#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <utility>

namespace mg::garbing::detail {

/// Clips [t0, t1] to the parameters t where o + t d lies in the closed box [lo, hi]; inv_d
/// is 1 / d per component (infinite where d is 0: that slab keeps the line when o lies in
/// it). False when nothing is left.
inline bool clip_line_to_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi,
                             const Eigen::Vector3d& o, const Eigen::Vector3d& inv_d, double& t0,
                             double& t1) {
  for (int k = 0; k < 3; ++k) {
    double a = (lo[k] - o[k]) * inv_d[k], b = (hi[k] - o[k]) * inv_d[k];
    if (std::isnan(a) || std::isnan(b)) {  // d[k] == 0 and o on a slab plane
      if (o[k] < lo[k] || o[k] > hi[k]) return false;
      continue;
    }
    if (a > b) std::swap(a, b);
    t0 = std::max(t0, a);
    t1 = std::min(t1, b);
    if (t0 > t1) return false;
  }
  return true;
}

}  // namespace mg::garbing::detail
