#include "garbing/errors.h"
#include "garbing/octree.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "atom_sets.h"

namespace {

using mg_test::atoms;

/// Dimension of the contact of two closed cells (0 corner, 1 edge, 2 face), -1 if apart.
int contact(const mg::OctreeCell& a, const mg::OctreeCell& b) {
  const int level = std::max(a.level, b.level);
  int dim = 0;
  for (int k = 0; k < 3; ++k) {
    const long alo = long(a.ijk[k]) << (level - a.level), ahi = long(a.ijk[k] + 1) << (level - a.level);
    const long blo = long(b.ijk[k]) << (level - b.level), bhi = long(b.ijk[k] + 1) << (level - b.level);
    const long overlap = std::min(ahi, bhi) - std::max(alo, blo);
    if (overlap < 0) return -1;
    if (overlap > 0) ++dim;
  }
  return dim;
}

std::vector<int> active_leaves(const mg::Octree& t) {
  std::vector<int> out;
  for (int c : t.leaves)
    if (t.cells[c].is_active()) out.push_back(c);
  return out;
}

TEST(Octree, OneSphereGetsDepthFourInATightRoot) {
  const auto t = mg::build_octree(atoms({{Eigen::Vector3d(1, 2, 3), 1.0}}));
  EXPECT_EQ(t.min_depth, 4);
  EXPECT_DOUBLE_EQ(t.root_side, 2.0);
  EXPECT_DOUBLE_EQ(t.rc, 1.0);
  EXPECT_TRUE(t.axes.isIdentity());
  EXPECT_TRUE(t.to_local(Eigen::Vector3d(1, 2, 3)).isApprox(Eigen::Vector3d(1, 1, 1)));
  EXPECT_FALSE(t.hit_max_depth);
}

TEST(Octree, PrincipalFrameIsRightHandedWithFixedSigns) {
  // An elongated, tilted blob: distinct eigenvalues.
  mg::MedialSurface s;
  mg_test::add_chain(s, Eigen::Vector3d(-2, -1, 0.5), Eigen::Vector3d(2, 1, -0.5), 9, 0.3);
  s.atoms.push_back({Eigen::Vector3d(0, 0.4, 0.3), 0.3});
  const auto t = mg::build_octree(s);
  EXPECT_NEAR(t.axes.determinant(), 1.0, 1e-12);
  EXPECT_TRUE((t.axes.transpose() * t.axes).isIdentity(1e-12));
  Eigen::Index big;
  t.axes.col(0).cwiseAbs().maxCoeff(&big);
  EXPECT_GT(t.axes(big, 0), 0);
  EXPECT_NEAR(std::abs(t.axes.col(0).dot(Eigen::Vector3d(4, 2, -1).normalized())), 1.0, 1e-3);
  // The root is the tightest cube around the balls in that frame: some ball touches each of
  // the two faces of the longest side.
  double lo = 1e9, hi = -1e9;
  for (const auto& a : s.atoms) {
    const Eigen::Vector3d p = t.to_local(a.centre);
    lo = std::min(lo, p[0] - a.radius);
    hi = std::max(hi, p[0] + a.radius);
  }
  EXPECT_NEAR(lo, 0.0, 1e-12);
  EXPECT_NEAR(hi, t.root_side, 1e-12);
}

TEST(Octree, RepeatedEigenvaluesGiveTheIdentityFrame) {
  EXPECT_TRUE(mg::build_octree(mg_test::ring(60, 1.0, 0.3)).axes.isIdentity());
  EXPECT_TRUE(mg::build_octree(atoms({{Eigen::Vector3d(0, 0, 0), 1}, {Eigen::Vector3d(1, 1, 1), 1}}))
                  .axes.isIdentity());
}

TEST(Octree, MinDepthOverrideAndMaxDepthStop) {
  mg::OctreeOptions opt;
  opt.min_depth = 6;
  const auto t = mg::build_octree(atoms({{Eigen::Vector3d::Zero(), 1.0}}), opt);
  EXPECT_EQ(t.min_depth, 6);
  for (int c : active_leaves(t))
    if (!t.cells[c].inside_one_ball) {
      EXPECT_GE(t.cells[c].level, 6);
    }

  // Two balls 0.01 apart need level 11 to separate: a stop at 8 is reported.
  opt = {};
  opt.max_depth = 8;
  const auto gap = atoms({{Eigen::Vector3d(-1.005, 0, 0), 1}, {Eigen::Vector3d(1.005, 0, 0), 1}});
  const auto stopped = mg::build_octree(gap, opt);
  EXPECT_TRUE(stopped.hit_max_depth);
  EXPECT_LE(stopped.depth, 8);
  EXPECT_FALSE(mg::build_octree(gap).hit_max_depth);
}

/// Criteria 1, 3 and 4 hold at the fixed point, checked by brute force over the leaves
/// touching each active leaf (touching_leaves is checked against all pairs separately).
void expect_criteria_hold(const mg::MedialSurface& s, const mg::Octree& t) {
  const auto active = active_leaves(t);
  auto intersect = [&](int i, int j) {
    const auto& a = s.atoms[i];
    const auto& b = s.atoms[j];
    return (a.centre - b.centre).norm() <= a.radius + b.radius;
  };
  std::vector<int> touching;
  for (std::size_t x = 0; x < active.size(); ++x) {
    const auto& a = t.cells[active[x]];
    mg::touching_leaves(t, active[x], touching);
    for (int y : touching) {
      const auto& b = t.cells[y];
      if (!b.is_active()) continue;
      const int dim = contact(a, b);
      if (dim >= 1) {
        EXPECT_LE(std::abs(a.level - b.level), 1) << "grading";
      }
      if (dim >= 0 && a.level >= t.min_depth && b.level >= t.min_depth) {
        bool linked = false;
        for (int i : a.spheres)
          for (int j : b.spheres) linked = linked || i == j || intersect(i, j);
        EXPECT_TRUE(linked) << "criterion 3 between leaves " << active[x] << " and " << y;
      }
    }
    if (a.level >= t.min_depth) {  // criterion 1: one connected component per leaf
      std::vector<int> reached = {a.spheres.front()}, todo = reached;
      while (!todo.empty()) {
        const int i = todo.back();
        todo.pop_back();
        for (int j : a.spheres)
          if (std::find(reached.begin(), reached.end(), j) == reached.end() && intersect(i, j)) {
            reached.push_back(j);
            todo.push_back(j);
          }
      }
      EXPECT_EQ(reached.size(), a.spheres.size()) << "criterion 1 at leaf " << active[x];
    }
  }
}

TEST(Octree, CriteriaHoldAtTheFixedPointOnARandomBlob) {
  const auto s = mg_test::blob(40, 0.08, 0.3, 7);
  const auto t = mg::build_octree(s);
  EXPECT_FALSE(t.hit_max_depth);
  expect_criteria_hold(s, t);
}

TEST(Octree, CriteriaHoldOnTwoChainsPassingClose) {
  mg::MedialSurface s;
  mg_test::add_chain(s, Eigen::Vector3d(-1, 0, 0), Eigen::Vector3d(1, 0, 0), 21, 0.1);
  mg_test::add_chain(s, Eigen::Vector3d(0, -1, 0.21), Eigen::Vector3d(0, 1, 0.21), 21, 0.1);
  const auto t = mg::build_octree(s);
  expect_criteria_hold(s, t);
}

TEST(Octree, TouchingLeavesMatchesBruteForce) {
  mg::OctreeOptions opt;
  opt.min_depth = 3;  // a small tree: the brute force is quadratic
  const auto t = mg::build_octree(mg_test::blob(15, 0.1, 0.4, 3), opt);
  ASSERT_GT(t.depth, 4);  // several levels meet
  std::vector<int> fast;
  for (std::size_t x = 0; x < t.leaves.size(); x += 5) {
    const int c = t.leaves[x];
    mg::touching_leaves(t, c, fast);
    std::vector<int> slow;
    for (int d : t.leaves)
      if (d != c && contact(t.cells[c], t.cells[d]) >= 0) slow.push_back(d);
    std::sort(slow.begin(), slow.end());
    EXPECT_EQ(fast, slow) << "leaf " << c;
  }
}

TEST(Octree, RefusesBadInput) {
  EXPECT_THROW(mg::build_octree(mg::MedialSurface{}), mg::InvalidInput);
  EXPECT_THROW(mg::build_octree(atoms({{Eigen::Vector3d::Zero(), std::numeric_limits<double>::quiet_NaN()}})),
               mg::InvalidInput);
  EXPECT_THROW(mg::build_octree(atoms({{Eigen::Vector3d::Zero(), 0.0}})), mg::InvalidInput);
  EXPECT_THROW(mg::build_octree(atoms({{Eigen::Vector3d::Zero(), -1.0}})), mg::InvalidInput);
  mg::OctreeOptions opt;
  opt.min_depth = 9;
  opt.max_depth = 8;
  EXPECT_THROW(mg::build_octree(atoms({{Eigen::Vector3d::Zero(), 1.0}}), opt), mg::InvalidInput);
  // Automatic d above the stop: a tiny ball beside a huge one.
  opt = {};
  opt.max_depth = 5;
  EXPECT_THROW(mg::build_octree(atoms({{Eigen::Vector3d::Zero(), 1.0}, {Eigen::Vector3d(1000, 0, 0), 0.001}}), opt),
               mg::InvalidInput);
}

}  // namespace
