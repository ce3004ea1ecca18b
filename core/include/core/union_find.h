#pragma once
/// \file union_find.h
/// Disjoint sets over 0 .. n - 1 with path halving; each set's representative is its smallest
/// element, so the classes do not depend on the order of the unions.

#include <algorithm>
#include <cstddef>
#include <numeric>
#include <vector>

namespace mg {

class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(n) { std::iota(parent_.begin(), parent_.end(), 0); }

  /// The representative (smallest element) of i's set.  @pre i < n
  std::size_t find(std::size_t i) {
    while (parent_[i] != i) i = parent_[i] = parent_[parent_[i]];
    return i;
  }

  /// Joins the sets of a and b.  @pre a, b < n
  void unite(std::size_t a, std::size_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<std::size_t> parent_;
};

}  // namespace mg
