#pragma once
/// \file detail/box_grid.h
/// Internal: boxes on a grid of cubic cells, for broad phases. `BoxGrid` says which boxes lie
/// near a few probe boxes, for checks after a local change (the fold check of a few moved
/// triangles, the gap splits of M2): cells as large as the largest probe; each probe marks the
/// cells it overlaps; a box is near when it overlaps a marked cell. Conservative: a box that
/// overlaps a probe is always near.

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace mg::detail {

/// The cells [lo, hi] (per axis) that the closed box b overlaps on a grid of side h. False,
/// and nothing to rely on, when b spans more than `max_cells` cells or a coordinate is not
/// finite or too far out for 64-bit cell numbers: callers treat such a box as near everything.
inline bool cell_range(const Eigen::AlignedBox3d& b, double h, std::int64_t lo[3],
                       std::int64_t hi[3], double max_cells = 64) {
  double cells = 1;
  for (int a = 0; a < 3; ++a) {
    const double l = std::floor(b.min()[a] / h), u = std::floor(b.max()[a] / h);
    if (!(std::abs(l) < 0x1p52 && std::abs(u) < 0x1p52) || u < l) return false;  // also NaN
    cells *= u - l + 1;
    lo[a] = static_cast<std::int64_t>(l);
    hi[a] = static_cast<std::int64_t>(u);
  }
  return cells <= max_cells;
}

/// A cell's key; numbers wrap at 2^21 per axis, so far-apart cells may share a key (aliasing
/// only adds candidates).
inline std::uint64_t cell_key(std::int64_t i, std::int64_t j, std::int64_t k) {
  return (static_cast<std::uint64_t>(i & 0x1FFFFF) << 42) |
         (static_cast<std::uint64_t>(j & 0x1FFFFF) << 21) |
         static_cast<std::uint64_t>(k & 0x1FFFFF);
}

class BoxGrid {
 public:
  explicit BoxGrid(const std::vector<Eigen::AlignedBox3d>& probes) {
    for (const auto& b : probes) h_ = std::max(h_, (b.max() - b.min()).maxCoeff());
    if (!(h_ > 0 && std::isfinite(h_))) {  // no probe, only points, or not finite: all near
      h_ = 0;
      return;
    }
    for (const auto& b : probes) {
      std::int64_t lo[3], hi[3];
      if (!cell_range(b, h_, lo, hi)) {  // not expected (a probe spans at most 3 cells per axis)
        h_ = 0;
        marked_.clear();
        return;
      }
      for (std::int64_t i = lo[0]; i <= hi[0]; ++i)
        for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
          for (std::int64_t k = lo[2]; k <= hi[2]; ++k) marked_.push_back(cell_key(i, j, k));
    }
    std::sort(marked_.begin(), marked_.end());
    marked_.erase(std::unique(marked_.begin(), marked_.end()), marked_.end());
  }

  /// Whether `b` overlaps a marked cell (always true for a box over more than 64 cells).
  bool near(const Eigen::AlignedBox3d& b) const {
    if (h_ == 0) return true;
    std::int64_t lo[3], hi[3];
    if (!cell_range(b, h_, lo, hi)) return true;
    for (std::int64_t i = lo[0]; i <= hi[0]; ++i)
      for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
        for (std::int64_t k = lo[2]; k <= hi[2]; ++k)
          if (std::binary_search(marked_.begin(), marked_.end(), cell_key(i, j, k))) return true;
    return false;
  }

 private:
  double h_ = 0;
  std::vector<std::uint64_t> marked_;
};

}  // namespace mg::detail
