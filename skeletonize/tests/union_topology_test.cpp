// The topology of a union of balls: analytic cases, hidden balls, and random sets against an
// independent voxel count.
#include "skeletonize/union_topology.h"
#include "core/errors.h"
#include "core/random.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <numeric>

namespace {

using Eigen::Vector3d;
namespace sk = mg::skeletonize;
constexpr double kPi = 3.14159265358979323846;

mg::MedialSurface balls(std::initializer_list<mg::MedialAtom> list) {
  mg::MedialSurface s;
  s.atoms = list;
  return s;
}

/// n balls of radius r on the circle of radius R around `axis` (a unit vector) through `centre`;
/// `wave` moves them off the circle's plane (0: coplanar centres).
mg::MedialSurface ring(int n, double R, double r, const Vector3d& centre = Vector3d::Zero(),
                       const Vector3d& axis = Vector3d::UnitZ(), double wave = 0) {
  const Vector3d u = axis.unitOrthogonal(), v = axis.cross(u);
  mg::MedialSurface s;
  for (int k = 0; k < n; ++k) {
    const double t = 2 * kPi * k / n;
    s.atoms.push_back(
        {centre + R * (std::cos(t) * u + std::sin(t) * v) + wave * std::sin(3 * t) * axis, r});
  }
  return s;
}

void append(mg::MedialSurface& to, const mg::MedialSurface& from) {
  to.atoms.insert(to.atoms.end(), from.atoms.begin(), from.atoms.end());
}

/// Inside every ball: a concentric smaller one (hidden in the regular triangulation) and an
/// off-centre one in the plane of `normal` (its power cell is a far-away half-space: it is in
/// the triangulation but not in the dual complex).
void add_inner_balls(mg::MedialSurface& s, const Vector3d& normal) {
  const std::size_t n = s.atoms.size();
  const Vector3d side = normal.unitOrthogonal();
  for (std::size_t i = 0; i < n; ++i) {
    const mg::MedialAtom a = s.atoms[i];
    s.atoms.push_back({a.centre, 0.5 * a.radius});
    s.atoms.push_back({a.centre + 0.4 * a.radius * side, 0.3 * a.radius});
  }
}

TEST(UnionTopology, OneBallTwoDisjointBallsAndARingOfSixty) {
  const auto one = sk::union_topology(balls({{Vector3d(1, 2, 3), 0.5}}));
  EXPECT_EQ(one.components, 1u);
  EXPECT_EQ(one.euler, 2);
  EXPECT_EQ(one.solid_euler, 1);
  const auto two = sk::union_topology(balls({{Vector3d(0, 0, 0), 1}, {Vector3d(3, 0, 0), 1}}));
  EXPECT_EQ(two.components, 2u);
  EXPECT_EQ(two.euler, 4);
  // 60 overlapping balls around a circle: a solid torus (coplanar centres: the planar complex).
  const auto flat = sk::union_topology(ring(60, 1.0, 0.3));
  EXPECT_EQ(flat.components, 1u);
  EXPECT_EQ(flat.euler, 0);
  // The same ring, waved out of its plane: the 3D complex.
  const auto wavy =
      sk::union_topology(ring(60, 1.0, 0.3, Vector3d::Zero(), Vector3d::UnitZ(), 0.05));
  EXPECT_EQ(wavy.components, 1u);
  EXPECT_EQ(wavy.euler, 0);
  // Too few balls to close the ring: a chain with a gap is a topological ball.
  auto open = ring(60, 1.0, 0.3);
  open.atoms.resize(50);
  EXPECT_EQ(sk::union_topology(open).euler, 2);
}

TEST(UnionTopology, HiddenAndRedundantBallsChangeNothing) {
  for (double wave : {0.0, 0.05}) {  // planar and 3D paths
    auto s = ring(60, 1.0, 0.3, Vector3d::Zero(), Vector3d::UnitZ(), wave);
    add_inner_balls(s, Vector3d::UnitZ());
    s.atoms.push_back(s.atoms[7]);  // an exact duplicate
    const auto t = sk::union_topology(s);
    EXPECT_EQ(t.components, 1u) << "wave " << wave;
    EXPECT_EQ(t.euler, 0) << "wave " << wave;
    EXPECT_GE(t.hidden_atoms, 61u) << "wave " << wave;  // the concentric ones and the duplicate
  }
  // One big ball full of smaller balls, off-centre and concentric, plus a far small one.
  const auto nested = sk::union_topology(balls({{Vector3d(0, 0, 0), 1},
                                                {Vector3d(0.2, 0, 0), 0.3},
                                                {Vector3d(0, 0.1, 0.1), 0.2},
                                                {Vector3d(-0.5, 0.3, 0), 0.4},
                                                {Vector3d(0, 0, 0), 0.5},
                                                {Vector3d(2, 2, 2), 0.1}}));
  EXPECT_EQ(nested.components, 2u);
  EXPECT_EQ(nested.euler, 4);
}

TEST(UnionTopology, LinkedRingsShellsAndChains) {
  // Two linked solid tori: 2 components, boundary Euler characteristic 0 + 0.
  auto linked = ring(48, 1.0, 0.2);
  append(linked, ring(48, 1.0, 0.2, Vector3d(1, 0, 0), Vector3d::UnitY()));
  const auto l = sk::union_topology(linked);
  EXPECT_EQ(l.components, 2u);
  EXPECT_EQ(l.euler, 0);
  // Two rings touching at one point: a genus-2 solid (boundary -2).
  auto eight = ring(48, 1.0, 0.25);
  append(eight, ring(48, 1.0, 0.25, Vector3d(2.0, 0, 0.01)));
  const auto e = sk::union_topology(eight);
  EXPECT_EQ(e.components, 1u);
  EXPECT_EQ(e.euler, -2);
  // A shell of balls around a void: the boundary is two spheres, 4.
  mg::MedialSurface shell;
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 24; ++j) {
      const double th = kPi * (i + 0.5) / 12, ph = 2 * kPi * j / 24;
      shell.atoms.push_back(
          {Vector3d(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)), 0.25});
    }
  const auto hollow = sk::union_topology(shell);
  EXPECT_EQ(hollow.components, 1u);
  EXPECT_EQ(hollow.euler, 4);
  // Collinear centres: runs of overlapping balls.
  mg::MedialSurface line;
  for (int k = 0; k < 10; ++k)
    line.atoms.push_back({Vector3d(0.5 * k, 0.5 * k, 0), k == 5 ? 0.1 : 0.4});
  const auto c = sk::union_topology(line);
  EXPECT_EQ(c.components, 3u);  // the small ball at k = 5 is alone between two gaps
  EXPECT_EQ(c.euler, 6);
}

double uniform(std::uint64_t& state) {  // splitmix64: the same stream on every platform
  state += mg::kSplitmixIncrement;
  return mg::unit_interval(mg::mix64(state));
}

TEST(UnionTopology, RandomLatticeUnionsMatchTheirGraphs) {
  // Balls of radius 0.62 on a random subset of a jittered unit lattice (jitter <= 0.03 per
  // axis): axis neighbours overlap (distance <= 1.06 < 1.24), diagonal ones do not (>= 1.33),
  // and the middle of every lattice square stays uncovered (>= 0.66 from each centre). No three
  // balls meet, so the union is homotopy equivalent to the graph of overlapping pairs (nerve
  // theorem): components and Euler characteristic V - E are known exactly. Isolated small balls
  // and balls hidden inside others are added. Dozens of tunnels, several components.
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    std::uint64_t state = seed;
    constexpr int n = 6;
    std::vector<int> site(n * n * n, -1);  // atom index of a big ball at the site
    mg::MedialSurface s;
    long edges = 0;
    long smalls = 0;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        for (int k = 0; k < n; ++k) {
          const double roll = uniform(state);
          Vector3d c(i, j, k);
          for (int a = 0; a < 3; ++a) c[a] += 0.06 * uniform(state) - 0.03;
          if (roll < 0.6) {
            site[(i * n + j) * n + k] = static_cast<int>(s.atoms.size());
            s.atoms.push_back({c, 0.62});
          } else if (roll < 0.7) {  // a small ball alone (0.3 + 0.62 < 0.94)
            s.atoms.push_back({c, 0.3});
            ++smalls;
          }
        }
    std::vector<int> parent(s.atoms.size());
    std::iota(parent.begin(), parent.end(), 0);
    std::function<int(int)> find = [&](int x) {
      return parent[x] == x ? x : parent[x] = find(parent[x]);
    };
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        for (int k = 0; k < n; ++k) {
          const int a = site[(i * n + j) * n + k];
          if (a < 0) continue;
          const int next[3] = {i + 1 < n ? site[((i + 1) * n + j) * n + k] : -1,
                               j + 1 < n ? site[(i * n + j + 1) * n + k] : -1,
                               k + 1 < n ? site[(i * n + j) * n + k + 1] : -1};
          for (int b : next)
            if (b >= 0) {
              ++edges;
              parent[find(a)] = find(b);
            }
        }
    std::size_t components = 0;
    for (std::size_t a = 0; a < parent.size(); ++a)
      components += find(static_cast<int>(a)) == static_cast<int>(a);
    const long euler = static_cast<long>(s.atoms.size()) - edges;
    for (std::size_t a = 0, count = s.atoms.size(); a < count; a += 3)  // hidden and inner balls
      s.atoms.push_back({s.atoms[a].centre + Vector3d(0.1, -0.05, 0), 0.5 * s.atoms[a].radius});
    const auto t = sk::union_topology(s);
    EXPECT_EQ(t.components, components) << "seed " << seed;
    EXPECT_EQ(t.solid_euler, euler) << "seed " << seed;
    EXPECT_EQ(t.euler, 2 * euler) << "seed " << seed;
    EXPECT_LT(euler, static_cast<long>(components) - 20)
        << "seed " << seed << ": want many tunnels";
    EXPECT_GT(smalls, 0);
  }
}

TEST(UnionTopology, RefusesInvalidAtoms) {
  EXPECT_THROW(sk::union_topology(mg::MedialSurface{}), mg::InvalidInput);
  EXPECT_THROW(sk::union_topology(balls({{Vector3d(0, 0, 0), -1}})), mg::InvalidInput);
  EXPECT_THROW(sk::union_topology(balls({{Vector3d(0, NAN, 0), 1}})), mg::InvalidInput);
  EXPECT_THROW(sk::regular_simplices(mg::MedialSurface{}), mg::InvalidInput);
}

TEST(RegularSimplices, RingLinksNeighboursAndHidesConcentricBalls) {
  auto s = ring(24, 1.0, 0.3, Vector3d::Zero(), Vector3d::UnitZ(), 0.05);
  s.atoms.push_back({s.atoms[0].centre, 0.1});  // concentric, smaller: hidden
  const auto rs = sk::regular_simplices(s);
  EXPECT_EQ(rs.hidden_atoms, 1u);
  for (int k = 0; k < 24; ++k) {
    const std::array<int, 2> e = {std::min(k, (k + 1) % 24), std::max(k, (k + 1) % 24)};
    EXPECT_TRUE(std::binary_search(rs.edges.begin(), rs.edges.end(), e)) << k;
  }
  for (const auto& e : rs.edges) EXPECT_NE(e[1], 24);
  EXPECT_TRUE(std::is_sorted(rs.edges.begin(), rs.edges.end()));
  EXPECT_TRUE(std::is_sorted(rs.triangles.begin(), rs.triangles.end()));
}

}  // namespace
