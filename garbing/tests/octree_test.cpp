#include "garbing/octree.h"
#include "core/errors.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "atom_sets.h"

namespace {

using mg_test::atoms;

/// Dimension of the contact of two closed cells (0 corner, 1 edge, 2 face), -1 if apart.
int contact(const mg::garbing::OctreeCell& a, const mg::garbing::OctreeCell& b) {
  const int level = std::max(a.level, b.level);
  int dim = 0;
  for (int k = 0; k < 3; ++k) {
    const long alo = long(a.ijk[k]) << (level - a.level), ahi = long(a.ijk[k] + 1)
                                                                << (level - a.level);
    const long blo = long(b.ijk[k]) << (level - b.level), bhi = long(b.ijk[k] + 1)
                                                                << (level - b.level);
    const long overlap = std::min(ahi, bhi) - std::max(alo, blo);
    if (overlap < 0) return -1;
    if (overlap > 0) ++dim;
  }
  return dim;
}

std::vector<int> active_leaves(const mg::garbing::Octree& t) {
  std::vector<int> out;
  for (int c : t.leaves)
    if (t.cells[c].is_active()) out.push_back(c);
  return out;
}

TEST(Octree, OneSphereGetsDepthFourInATightRoot) {
  const auto t = mg_test::octree_of(atoms({{Eigen::Vector3d(1, 2, 3), 1.0}}));
  EXPECT_EQ(t.min_depth, 4);
  EXPECT_DOUBLE_EQ(t.root_side, 2.0);
  EXPECT_DOUBLE_EQ(t.rc, 1.0);
  EXPECT_TRUE(t.frame.axes.isIdentity());
  EXPECT_TRUE(t.to_local(Eigen::Vector3d(1, 2, 3)).isApprox(Eigen::Vector3d(1, 1, 1)));
  EXPECT_FALSE(t.hit_max_depth);
}

TEST(Octree, PrincipalFrameIsRightHandedWithFixedSigns) {
  // An elongated, tilted blob: distinct eigenvalues.
  mg::MedialSurface s;
  mg_test::add_chain(s, Eigen::Vector3d(-2, -1, 0.5), Eigen::Vector3d(2, 1, -0.5), 9, 0.3);
  s.atoms.push_back({Eigen::Vector3d(0, 0.4, 0.3), 0.3});
  const auto t = mg_test::octree_of(s);
  EXPECT_NEAR(t.frame.axes.determinant(), 1.0, 1e-12);
  EXPECT_TRUE((t.frame.axes.transpose() * t.frame.axes).isIdentity(1e-12));
  Eigen::Index big;
  t.frame.axes.col(0).cwiseAbs().maxCoeff(&big);
  EXPECT_GT(t.frame.axes(big, 0), 0);
  EXPECT_NEAR(std::abs(t.frame.axes.col(0).dot(Eigen::Vector3d(4, 2, -1).normalized())), 1.0, 1e-3);
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
  EXPECT_TRUE(mg_test::octree_of(mg_test::ring(60, 1.0, 0.3)).frame.axes.isIdentity());
  EXPECT_TRUE(
      mg_test::octree_of(atoms({{Eigen::Vector3d(0, 0, 0), 1}, {Eigen::Vector3d(1, 1, 1), 1}}))
          .frame.axes.isIdentity());
}

TEST(Octree, MinDepthOverrideAndMaxDepthStop) {
  mg::garbing::OctreeOptions opt;
  opt.min_depth = 6;
  const auto t = mg_test::octree_of(atoms({{Eigen::Vector3d::Zero(), 1.0}}), opt);
  EXPECT_EQ(t.min_depth, 6);
  for (int c : active_leaves(t))
    if (!t.cells[c].inside_one_ball) {
      EXPECT_GE(t.cells[c].level, 6);
    }

  // Two balls 0.01 apart need level 11 to separate: a stop at 8 is reported.
  opt = {};
  opt.max_depth = 8;
  const auto gap = atoms({{Eigen::Vector3d(-1.005, 0, 0), 1}, {Eigen::Vector3d(1.005, 0, 0), 1}});
  const auto stopped = mg_test::octree_of(gap, opt);
  EXPECT_TRUE(stopped.hit_max_depth);
  EXPECT_LE(stopped.depth, 8);
  EXPECT_FALSE(mg_test::octree_of(gap).hit_max_depth);
}

/// Brute-force geometry of a cone's solid, the union of the balls B(c(t), r(t)), c and r
/// linear from one atom to the other: minima by sampling t, each sample within
/// slope * step / 2 of the true minimum; `tolerance` returns that bound.
struct SampledHull {
  Eigen::Vector3d c1, d;
  double r1, dr;
  static constexpr int steps = 2000;
  SampledHull(const mg::MedialSurface& s, const std::array<int, 2>& pair)
      : c1(s.atoms[pair[0]].centre),
        d(s.atoms[pair[1]].centre - c1),
        r1(s.atoms[pair[0]].radius),
        dr(s.atoms[pair[1]].radius - r1) {}
  Eigen::Vector3d centre(double t) const { return c1 + t * d; }
  double radius(double t) const { return r1 + t * dr; }
  double tolerance() const { return (d.norm() + std::abs(dr)) / steps; }
  template <class F>
  static double min_over_t(const F& f) {
    double best = INFINITY;
    for (int k = 0; k <= steps; ++k) best = std::min(best, f(double(k) / steps));
    return best;
  }
};

/// Criteria 1, 3 and 4 hold at the fixed point, checked by brute force over the leaves
/// touching each active leaf (touching_leaves is checked against all pairs separately).
/// Primitives: sphere i is i, cone k of `pairs` (G's) is n + k; a pair counts as meeting
/// when the sampled minimum is within the sampling tolerance (so the check never blames the
/// octree for a meeting it may have seen).
void expect_criteria_hold(const mg::MedialSurface& s, const mg::garbing::Octree& t,
                          const std::vector<std::array<int, 2>>& pairs) {
  const auto active = active_leaves(t);
  const int n = static_cast<int>(s.atoms.size());
  std::vector<SampledHull> hulls;
  for (const auto& pair : pairs) hulls.emplace_back(s, pair);
  auto meet = [&](int i, int j) {
    if (i == j) return true;
    if (i > j) std::swap(i, j);
    if (j < n) {
      const auto& a = s.atoms[i];
      const auto& b = s.atoms[j];
      return (a.centre - b.centre).norm() <= a.radius + b.radius;
    }
    const auto& pj = pairs[j - n];
    const SampledHull& hj = hulls[j - n];
    if (i < n) {
      if (i == pj[0] || i == pj[1]) return true;
      const auto& a = s.atoms[i];
      return SampledHull::min_over_t([&](double u) {
               return (a.centre - hj.centre(u)).norm() - hj.radius(u);
             }) <= a.radius + hj.tolerance();
    }
    const auto& pi = pairs[i - n];
    if (pi[0] == pj[0] || pi[0] == pj[1] || pi[1] == pj[0] || pi[1] == pj[1]) return true;
    const SampledHull& hi = hulls[i - n];
    double best = INFINITY;
    for (int x = 0; x <= 200; ++x)
      for (int y = 0; y <= 200; ++y)
        best = std::min(best, (hi.centre(x / 200.0) - hj.centre(y / 200.0)).norm() -
                                  hi.radius(x / 200.0) - hj.radius(y / 200.0));
    return best <= 10 * (hi.tolerance() + hj.tolerance());
  };
  auto primitives = [&](const mg::garbing::OctreeCell& c) {
    std::vector<int> out(c.spheres.begin(), c.spheres.end());
    for (int k : c.cones) out.push_back(n + k);
    return out;
  };
  std::vector<int> touching;
  for (std::size_t x = 0; x < active.size(); ++x) {
    const auto& a = t.cells[active[x]];
    const auto pa = primitives(a);
    mg::garbing::touching_leaves(t, active[x], touching);
    for (int y : touching) {
      const auto& b = t.cells[y];
      if (!b.is_active()) continue;
      const int dim = contact(a, b);
      if (dim >= 1) {
        EXPECT_LE(std::abs(a.level - b.level), 1) << "grading";
      }
      if (dim >= 0 && a.level >= t.min_depth && b.level >= t.min_depth) {
        bool linked = false;
        for (int i : pa)
          for (int j : primitives(b)) linked = linked || meet(i, j);
        EXPECT_TRUE(linked) << "criterion 3 between leaves " << active[x] << " and " << y;
      }
    }
    if (a.level >= t.min_depth) {  // criterion 1: one connected component per leaf
      std::vector<int> reached = {pa.front()}, todo = reached;
      while (!todo.empty()) {
        const int i = todo.back();
        todo.pop_back();
        for (int j : pa)
          if (std::find(reached.begin(), reached.end(), j) == reached.end() && meet(i, j)) {
            reached.push_back(j);
            todo.push_back(j);
          }
      }
      EXPECT_EQ(reached.size(), pa.size()) << "criterion 1 at leaf " << active[x];
    }
  }
}

TEST(Octree, CriteriaHoldAtTheFixedPointOnARandomBlob) {
  const auto s = mg_test::blob(40, 0.08, 0.3, 7);
  const auto t = mg_test::octree_of(s);
  EXPECT_FALSE(t.hit_max_depth);
  expect_criteria_hold(s, t, mg::garbing::cone_pairs(s, {}));
}

TEST(Octree, CriteriaHoldWithEveryConeOfARandomBlob) {
  // No cone filter: many cones whose crease fill reaches leaves that no ball meets.
  const auto s = mg_test::blob(40, 0.08, 0.3, 7);
  mg::garbing::ConeOptions cones;
  cones.min_circle_ratio = 0;
  cones.max_collar = 0;
  const auto t = mg_test::octree_of(s, {}, cones);
  EXPECT_FALSE(t.hit_max_depth);
  long crease_leaves = 0;
  for (int c : active_leaves(t)) crease_leaves += t.cells[c].spheres.empty();
  EXPECT_GT(crease_leaves, 0);
  expect_criteria_hold(s, t, mg::garbing::cone_pairs(s, cones));
}

TEST(Octree, CriteriaHoldOnTwoChainsPassingClose) {
  mg::MedialSurface s;
  mg_test::add_chain(s, Eigen::Vector3d(-1, 0, 0), Eigen::Vector3d(1, 0, 0), 21, 0.1);
  mg_test::add_chain(s, Eigen::Vector3d(0, -1, 0.21), Eigen::Vector3d(0, 1, 0.21), 21, 0.1);
  const auto t = mg_test::octree_of(s);
  expect_criteria_hold(s, t, mg::garbing::cone_pairs(s, {}));
}

/// Cones(c) is exactly the cones whose solid meets the cube while neither ball does, checked
/// on every leaf by sampling: a clear meeting must be listed, a clear miss must not.
class CreaseCones : public ::testing::TestWithParam<std::array<double, 5>> {};

TEST_P(CreaseCones, AreTheConesMeetingTheCubeOutsideTheirBalls) {
  // Two balls (the first at the origin, radius 1; the second at (x, y, z), radius r): the
  // crease where they meet is filled by their cone.
  const auto [x, y, z, r, depth] = GetParam();
  const auto s = atoms({{Eigen::Vector3d(0, 0, 0), 1.0}, {Eigen::Vector3d(x, y, z), r}});
  mg::garbing::OctreeOptions opt;
  opt.min_depth = static_cast<int>(depth);
  mg::garbing::ConeOptions cones;
  cones.min_circle_ratio = 0;
  cones.max_collar = 0;
  const auto t = mg_test::octree_of(s, opt, cones);
  const auto pairs = mg::garbing::cone_pairs(s, cones);
  ASSERT_EQ(pairs.size(), 1u);
  const SampledHull hull(s, pairs[0]);
  long listed = 0, checked = 0;
  for (int c : t.leaves) {
    const auto& cell = t.cells[c];
    const double side = t.side(cell.level);
    const Eigen::Vector3d lo(cell.ijk[0] * side, cell.ijk[1] * side, cell.ijk[2] * side);
    auto cube_distance = [&](const Eigen::Vector3d& world) {
      const Eigen::Vector3d p = t.to_local(world);
      return (p - p.cwiseMax(lo).cwiseMin(lo + Eigen::Vector3d::Constant(side))).norm();
    };
    // Cubes that touch a ball within rounding (the tree works in its own frame) are skipped.
    bool ball_meets = false, ball_touches = false;
    for (const auto& a : s.atoms) {
      const double gap = cube_distance(a.centre) - a.radius;
      ball_meets = ball_meets || gap <= 0;
      ball_touches = ball_touches || std::abs(gap) <= 1e-12;
    }
    if (ball_touches) continue;
    const double gap = SampledHull::min_over_t(
        [&](double u) { return cube_distance(hull.centre(u)) - hull.radius(u); });
    const bool is_listed = !cell.cones.empty();
    listed += is_listed;
    if (ball_meets) {
      EXPECT_FALSE(is_listed) << "leaf " << c << " meets a ball: its ball stands for the cone";
    } else if (gap < -hull.tolerance()) {
      EXPECT_TRUE(is_listed) << "leaf " << c << " meets the crease fill by " << -gap;
      ++checked;
    } else if (gap > hull.tolerance()) {
      EXPECT_FALSE(is_listed) << "leaf " << c << " misses the cone by " << gap;
    }
    EXPECT_EQ(cell.is_active(), ball_meets || is_listed);
  }
  EXPECT_GT(checked, 10);  // the crease is deep enough to hold leaves
  EXPECT_GT(listed, 10);
}

INSTANTIATE_TEST_SUITE_P(
    Octree, CreaseCones,
    ::testing::Values(std::array<double, 5>{1.6, 0.1, -0.2, 0.8, 5},   // shallow angle
                      std::array<double, 5>{0.9, 0.5, 0.3, 0.4, 6},    // small ball
                      std::array<double, 5>{1.2, -0.7, 0.4, 1.0, 5},   // equal radii
                      std::array<double, 5>{0.3, 0.2, 1.7, 0.9, 5}));  // off-axis

TEST(Octree, TouchingLeavesMatchesBruteForce) {
  mg::garbing::OctreeOptions opt;
  opt.min_depth = 3;  // a small tree: the brute force is quadratic
  const auto t = mg_test::octree_of(mg_test::blob(15, 0.1, 0.4, 3), opt);
  ASSERT_GT(t.depth, 4);  // several levels meet
  std::vector<int> fast;
  for (std::size_t x = 0; x < t.leaves.size(); x += 5) {
    const int c = t.leaves[x];
    mg::garbing::touching_leaves(t, c, fast);
    std::vector<int> slow;
    for (int d : t.leaves)
      if (d != c && contact(t.cells[c], t.cells[d]) >= 0) slow.push_back(d);
    std::sort(slow.begin(), slow.end());
    EXPECT_EQ(fast, slow) << "leaf " << c;
  }
}

TEST(Octree, CubesTileWithoutGapsOrOverlaps) {
  // Neighbouring cubes share their face plane exactly, and every corner is the same double
  // as the lattice point (corner x side at the finest level): no point falls between leaves.
  const auto t = mg_test::octree_of(mg_test::blob(15, 0.1, 0.4, 3));
  const double unit = t.side(t.depth);
  std::size_t shared = 0;
  for (int c : t.leaves) {
    const mg::garbing::OctreeCell& cell = t.cells[c];
    const Eigen::AlignedBox3d cube = t.cube(cell);
    const std::int64_t scale = std::int64_t(1) << (t.depth - cell.level);
    for (int a = 0; a < 3; ++a) {
      ASSERT_EQ(cube.min()[a], static_cast<double>(cell.ijk[a] * scale) * unit);
      ASSERT_EQ(cube.max()[a], static_cast<double>((cell.ijk[a] + 1) * scale) * unit);
      // The neighbour across the upper face, at the same level or coarser.
      std::array<std::int64_t, 3> ijk = {cell.ijk[0], cell.ijk[1], cell.ijk[2]};
      ++ijk[a];
      const int n = mg::garbing::find_cell(t, cell.level, ijk);
      if (n < 0) continue;
      const mg::garbing::OctreeCell& other = t.cells[n];
      if (other.level > cell.level) continue;
      EXPECT_EQ(t.cube(other).min()[a], cube.max()[a]) << "leaf " << c << " axis " << a;
      ++shared;
    }
  }
  EXPECT_GT(shared, t.leaves.size());
}

/// A dense sheet of balls: a grid of n x n centres with spacing h in the z = 0 plane, radii
/// r (1 + 0.1 sin): every point near the sheet lies in dozens of balls, as on pole skeletons.
mg::MedialSurface dense_sheet(int n, double h, double r) {
  mg::MedialSurface s;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      s.atoms.push_back({Eigen::Vector3d(i * h, j * h, 0.02 * std::sin(i + 2.0 * j)),
                         r * (1 + 0.1 * std::sin(0.7 * i - 0.3 * j))});
  return s;
}

/// The pruned lists (the default) hold G within every leaf: each point of G in an active leaf's
/// cube lies in a listed ball, a cone of one, or a listed cone (what the criteria and the
/// migration read as P(c)); the listed balls all meet the cube; and the lists are a fraction of
/// the paper's full ones. Checked by sampling each leaf, with the regular triangulation's cones
/// as filtered by default and unfiltered (wide crease fills).
void expect_pruned_lists_hold_g(const mg::MedialSurface& s, const mg::garbing::ConeOptions& cones,
                                double most_kept) {
  const auto g = mg_test::shape_of(s, cones);
  const auto t = mg::garbing::build_octree(g);
  mg::garbing::OctreeOptions paper;
  paper.prune_lists = false;
  const auto full = mg::garbing::build_octree(g, paper);
  const int n = static_cast<int>(g.sphere_count());
  std::mt19937 gen(3);
  std::uniform_real_distribution<double> unit(0, 1);
  long points_in_g = 0;
  std::size_t kept = 0, all = 0;
  for (int c : active_leaves(t)) {
    const auto& cell = t.cells[c];
    const auto cube = t.cube(cell);
    std::vector<int> prims;
    for (int i : cell.spheres) {
      EXPECT_LE(cube.exteriorDistance(g.sphere(i).centre), g.sphere(i).radius) << "ball " << i;
      prims.push_back(i);
      const auto [first, last] = g.cones_of_atom(i);
      prims.insert(prims.end(), first, last);
    }
    for (int k : cell.cones) prims.push_back(n + k);
    for (int k = 0; k < 24; ++k) {
      const Eigen::Vector3d p =
          cube.min() + cube.sizes().cwiseProduct(Eigen::Vector3d(unit(gen), unit(gen), unit(gen)));
      if (!g.contains(p)) continue;
      ++points_in_g;
      const bool listed = std::any_of(prims.begin(), prims.end(), [&](int q) {
        return g.primitive_contains(q, p, -1e-9 * cube.sizes()[0]);
      });
      EXPECT_TRUE(listed) << "leaf " << c << ": a point of G in no listed primitive";
      if (!listed) return;
    }
    kept += cell.spheres.size();
  }
  for (int c : active_leaves(full)) all += full.cells[c].spheres.size();
  EXPECT_GT(points_in_g, 1000);
  // Points of every cone's solid, crease fills included: just inside an interpolated ball,
  // each checked against the leaf holding it.
  const double lattice = t.side(t.depth);
  std::uniform_real_distribution<double> normal(-1, 1);
  long in_cones = 0;
  for (std::size_t k = 0; k < g.cone_count(); ++k) {
    const mg::garbing::Cone cone = g.cone(n + static_cast<int>(k));
    for (int sample = 0; sample < 40; ++sample) {
      Eigen::Vector3d dir(normal(gen), normal(gen), normal(gen));
      if (!(dir.norm() > 1e-3)) continue;
      const double u = unit(gen);
      const Eigen::Vector3d p = cone.centre(u) + (1 - 1e-9) * cone.radius(u) * dir.normalized();
      std::array<std::int64_t, 3> ijk;
      for (int a = 0; a < 3; ++a) ijk[a] = static_cast<std::int64_t>(std::floor(p[a] / lattice));
      const int leaf = mg::garbing::find_cell(t, t.depth, ijk);
      if (leaf < 0 || !t.cells[leaf].is_active()) {
        ADD_FAILURE() << "a point of cone " << k << " in no active leaf";
        return;
      }
      const auto& cell = t.cells[leaf];
      std::vector<int> prims(cell.spheres.begin(), cell.spheres.end());
      for (int i : cell.spheres) {
        const auto [first, last] = g.cones_of_atom(i);
        prims.insert(prims.end(), first, last);
      }
      for (int c : cell.cones) prims.push_back(n + c);
      ++in_cones;
      const bool listed = std::any_of(prims.begin(), prims.end(), [&](int q) {
        return g.primitive_contains(q, p, -1e-9 * lattice);
      });
      EXPECT_TRUE(listed) << "leaf " << leaf << ": a point of cone " << k
                          << " in no listed primitive";
      if (!listed) return;
    }
  }
  EXPECT_GT(in_cones, 1000);
  EXPECT_LT(double(kept), most_kept * double(all)) << kept << " of " << all;
}

TEST(Octree, PrunedListsHoldGInsideEveryLeafOfADenseSheet) {
  expect_pruned_lists_hold_g(dense_sheet(24, 0.04, 0.3), {}, 0.25);  // measured 0.152
}

TEST(Octree, PrunedListsHoldGWithEveryConeOfADenseSheet) {
  mg::garbing::ConeOptions cones;
  cones.min_circle_ratio = 0;
  cones.max_collar = 0;
  expect_pruned_lists_hold_g(dense_sheet(24, 0.04, 0.3), cones, 0.25);  // measured 0.163
}

TEST(Octree, PrunedListsHoldGInsideEveryLeafOfARandomBlob) {
  expect_pruned_lists_hold_g(mg_test::blob(300, 0.2, 0.45, 11), {}, 0.8);  // measured 0.672
}

/// --full-lists is the paper's: a leaf lists exactly the balls meeting its cube.
TEST(Octree, FullListsListEveryBallMeetingTheCube) {
  const auto s = dense_sheet(12, 0.08, 0.3);
  const auto g = mg_test::shape_of(s);
  mg::garbing::OctreeOptions paper;
  paper.prune_lists = false;
  const auto t = mg::garbing::build_octree(g, paper);
  for (int c : t.leaves) {
    const auto cube = t.cube(t.cells[c]);
    std::vector<int> meeting;
    for (int i = 0; i < static_cast<int>(g.sphere_count()); ++i)
      if (cube.exteriorDistance(g.sphere(i).centre) <= g.sphere(i).radius) meeting.push_back(i);
    EXPECT_EQ(t.cells[c].spheres, meeting) << "leaf " << c;
  }
}

TEST(Octree, RefusesBadInput) {
  EXPECT_THROW(mg_test::octree_of(mg::MedialSurface{}), mg::InvalidInput);
  EXPECT_THROW(mg_test::octree_of(
                   atoms({{Eigen::Vector3d::Zero(), std::numeric_limits<double>::quiet_NaN()}})),
               mg::InvalidInput);
  // A ball of radius 0 is a valid atom, but the balls alone (rt) have nothing to garb there.
  try {
    mg_test::octree_of(atoms({{Eigen::Vector3d::Zero(), 1.0}, {Eigen::Vector3d(3, 0, 0), 0.0}}));
    ADD_FAILURE() << "a zero radius accepted by G of the atoms alone";
  } catch (const mg::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("atom 1 has radius 0"), std::string::npos) << e.what();
  }
  EXPECT_THROW(mg_test::octree_of(atoms({{Eigen::Vector3d::Zero(), -1.0}})), mg::InvalidInput);
  mg::garbing::OctreeOptions opt;
  opt.min_depth = 9;
  opt.max_depth = 8;
  EXPECT_THROW(mg_test::octree_of(atoms({{Eigen::Vector3d::Zero(), 1.0}}), opt), mg::InvalidInput);
  // Automatic d above the stop: a tiny ball beside a huge one.
  opt = {};
  opt.max_depth = 5;
  EXPECT_THROW(
      mg_test::octree_of(
          atoms({{Eigen::Vector3d::Zero(), 1.0}, {Eigen::Vector3d(1000, 0, 0), 0.001}}), opt),
      mg::InvalidInput);
  // G outside a bounding cube frame (world coordinates) has no root cube.
  const auto one = atoms({{Eigen::Vector3d::Zero(), 1.0}});
  EXPECT_THROW(mg::garbing::build_octree(mg::garbing::make_target_shape(one)), mg::InvalidInput);
}

}  // namespace
