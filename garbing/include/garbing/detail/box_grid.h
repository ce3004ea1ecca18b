#pragma once
/// \file detail/box_grid.h
/// Internal: which boxes lie near a few probe boxes, for checks after a local change (the fold
/// check of a few moved triangles, the gap splits of M2). A grid of cells as large as the
/// largest probe; each probe marks the cells it overlaps; a box is near when it overlaps a
/// marked cell. Conservative: a box that overlaps a probe is always near.

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace mg::detail {

class BoxGrid {
 public:
  explicit BoxGrid(const std::vector<Eigen::AlignedBox3d>& probes) {
    for (const auto& b : probes) h_ = std::max(h_, (b.max() - b.min()).maxCoeff());
    if (!(h_ > 0)) return;  // no probe, or only points: near() keeps everything
    for (const auto& b : probes) visit(b, [&](std::uint64_t key) { marked_.push_back(key); return false; });
    std::sort(marked_.begin(), marked_.end());
    marked_.erase(std::unique(marked_.begin(), marked_.end()), marked_.end());
  }

  /// Whether `b` overlaps a marked cell (always true for a box spanning more than 64 cells).
  bool near(const Eigen::AlignedBox3d& b) const {
    if (!(h_ > 0)) return true;
    return visit(b, [&](std::uint64_t key) { return std::binary_search(marked_.begin(), marked_.end(), key); });
  }

 private:
  std::int64_t cell(double x) const { return static_cast<std::int64_t>(std::floor(x / h_)); }

  /// Calls f(key) for each cell b overlaps until f says true (returned); a box over more than
  /// 64 cells returns true unvisited. Keys wrap at 2^21 cells per axis: aliasing only adds.
  template <class F>
  bool visit(const Eigen::AlignedBox3d& b, F&& f) const {
    std::int64_t lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      lo[a] = cell(b.min()[a]);
      hi[a] = cell(b.max()[a]);
    }
    if ((hi[0] - lo[0] + 1) * (hi[1] - lo[1] + 1) * (hi[2] - lo[2] + 1) > 64) return true;
    for (std::int64_t i = lo[0]; i <= hi[0]; ++i)
      for (std::int64_t j = lo[1]; j <= hi[1]; ++j)
        for (std::int64_t k = lo[2]; k <= hi[2]; ++k) {
          const std::uint64_t key = (static_cast<std::uint64_t>(i & 0x1FFFFF) << 42) |
                                    (static_cast<std::uint64_t>(j & 0x1FFFFF) << 21) |
                                    static_cast<std::uint64_t>(k & 0x1FFFFF);
          if (f(key)) return true;
        }
    return false;
  }

  double h_ = 0;
  std::vector<std::uint64_t> marked_;
};

}  // namespace mg::detail
