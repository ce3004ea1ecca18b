// Thinning of dense atoms: balls contained in a nearby kept ball up to a slack are left
// out, greedily, in an order that visits space block by block.
#include "garbing/thin_atoms.h"

#include "core/errors.h"
#include "core/medial_surface.h"
#include "core/timer.h"
#include "garbing/target_shape.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <string>

namespace mg::garbing {
namespace {

using Cell = std::array<std::int64_t, 3>;

/// Open addressing from a grid cell to the last kept ball in it (the others follow through
/// `next`); a cell is identified by the cell of its first ball.
class KeptGrid {
 public:
  KeptGrid(std::size_t balls, const std::vector<Cell>& cell_of)
      : cell_of_(cell_of), next_(balls, -1) {
    std::size_t size = 16;
    while (size < 2 * balls) size *= 2;
    slot_.assign(size, -1);
    mask_ = size - 1;
  }
  /// The last kept ball of the cell, -1 if none.
  int head(const Cell& c) const { return slot_[find(c)]; }
  int next(int i) const { return next_[static_cast<std::size_t>(i)]; }
  void insert(int i) {
    const std::size_t s = find(cell_of_[static_cast<std::size_t>(i)]);
    next_[static_cast<std::size_t>(i)] = slot_[s];
    slot_[s] = i;
  }

 private:
  std::size_t find(const Cell& c) const {
    std::uint64_t h = static_cast<std::uint64_t>(c[0]) * 0x9e3779b97f4a7c15ULL ^
                      static_cast<std::uint64_t>(c[1]) * 0xc2b2ae3d27d4eb4fULL ^
                      static_cast<std::uint64_t>(c[2]) * 0x165667b19e3779f9ULL;
    std::size_t s = static_cast<std::size_t>(h ^ h >> 29) & mask_;
    while (slot_[s] >= 0 && cell_of_[static_cast<std::size_t>(slot_[s])] != c) s = (s + 1) & mask_;
    return s;
  }
  const std::vector<Cell>& cell_of_;
  std::vector<int> next_;
  std::vector<int> slot_;
  std::size_t mask_ = 0;
};

}  // namespace

MedialSurface thin_atoms(const MedialSurface& atoms, double slack, ThinStats* stats,
                         std::vector<int>* kept_index) {
  const Stopwatch clock;
  if (!(slack >= 0) || !std::isfinite(slack))
    throw InvalidInput("thin_atoms: the slack must be finite and >= 0, got " +
                       std::to_string(slack));
  if (!atoms.edges.empty() || !atoms.faces.empty())
    throw InvalidInput(
        "thin_atoms: a medial mesh's envelope (edges or faces) is not a union of balls");
  validate(atoms);
  require_positive_radii(atoms);
  const std::vector<MedialAtom>& a = atoms.atoms;
  const std::size_t n = a.size();
  std::vector<char> kept(n, 1);
  if (slack > 0 && n > 1) {
    // Grid of side h = 8 slack: the centres within 4 slack of a point lie in the 2 x 2 x 2
    // cells nearest to it (up to the rounding of their cell coordinates). Coarser where the
    // atoms span more than 2^24 cells, so that the blocks' Morton codes (21 bits of cell / 8)
    // do not wrap: the search then only reaches farther, and the containment test decides.
    Eigen::AlignedBox3d box;
    for (const MedialAtom& b : a) box.extend(b.centre);
    const double h = std::max(8 * slack, box.sizes().maxCoeff() * 0x1p-24);
    std::vector<Cell> cell_of(n);
    std::vector<std::uint64_t> block_key(n);
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
      const Eigen::Vector3d q = (a[i].centre - box.min()) / h;
      for (int k = 0; k < 3; ++k) cell_of[i][k] = static_cast<std::int64_t>(std::floor(q[k]));
      // Blocks of 8 x 8 x 8 cells in Morton order: the greedy pass reads one region at a time.
      block_key[i] = morton_code(static_cast<std::uint64_t>(cell_of[i][0] >> 3),
                                 static_cast<std::uint64_t>(cell_of[i][1] >> 3),
                                 static_cast<std::uint64_t>(cell_of[i][2] >> 3));
    });
    // The order: block, then decreasing radius, then index (a strict total order).
    std::vector<int> order(n);
    std::iota(order.begin(), order.end(), 0);
    tbb::parallel_sort(order.begin(), order.end(), [&](int i, int j) {
      if (block_key[i] != block_key[j]) return block_key[i] < block_key[j];
      if (a[i].radius != a[j].radius) return a[i].radius > a[j].radius;
      return i < j;
    });
    std::vector<std::uint64_t>().swap(block_key);
    KeptGrid grid(n, cell_of);
    for (int i : order) {
      const Eigen::Vector3d& c = a[i].centre;
      const double r = a[i].radius;
      const Eigen::Vector3d q = (c - box.min()) / h;
      Cell base = cell_of[i];
      std::array<int, 3> step;
      for (int k = 0; k < 3; ++k) step[k] = q[k] - static_cast<double>(base[k]) < 0.5 ? -1 : 1;
      bool contained = false;
      for (int k = 0; k < 8 && !contained; ++k) {
        const Cell cell = {base[0] + (k & 1) * step[0], base[1] + (k >> 1 & 1) * step[1],
                           base[2] + (k >> 2 & 1) * step[2]};
        for (int j = grid.head(cell); j >= 0; j = grid.next(j))
          if ((a[j].centre - c).norm() + r <= a[j].radius + slack) {
            contained = true;
            break;
          }
      }
      if (contained)
        kept[i] = 0;
      else
        grid.insert(i);
    }
  }
  MedialSurface out;
  if (kept_index) kept_index->clear();
  for (std::size_t i = 0; i < n; ++i)
    if (kept[i]) {
      out.atoms.push_back(a[i]);
      if (kept_index) kept_index->push_back(static_cast<int>(i));
    }
  if (stats) {
    stats->slack = slack;
    stats->kept = out.atoms.size();
    stats->dropped = n - out.atoms.size();
    stats->seconds = clock.seconds();
  }
  return out;
}

}  // namespace mg::garbing
