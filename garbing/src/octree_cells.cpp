// The octree's cells: their cubes and the neighbour queries every stage after step 1 uses.
#include "garbing/octree.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace mg::garbing {

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
  // The cell's ancestors by level, read once: each neighbour's common ancestor is one of them.
  std::array<int, 64> ancestor;
  ancestor[n] = c;
  for (int l = n; l > 0; --l) ancestor[l - 1] = tree.cells[ancestor[l]].parent;
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
          if (nb[a] < 0 || nb[a] >= size)
            inside = false;
          else {
            const std::uint64_t diff = static_cast<std::uint64_t>(nb[a]) ^ cell.ijk[a];
            if (diff != 0) climb = std::max(climb, 64 - __builtin_clzll(diff));
          }
        }
        if (!inside) continue;
        // Descend from the common ancestor toward (n, nb).
        int d = ancestor[n - climb];
        while (!tree.cells[d].is_leaf() && tree.cells[d].level < n) {
          const int shift = n - tree.cells[d].level - 1;
          int k = 0;
          for (int a = 0; a < 3; ++a) k |= static_cast<int>((nb[a] >> shift) & 1) << a;
          d = tree.cells[d].first_child + k;
        }
        if (tree.cells[d].is_leaf())
          out.push_back(d);
        else
          leaves_facing(tree, d, offset, out);
      }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
}

}  // namespace mg::garbing
