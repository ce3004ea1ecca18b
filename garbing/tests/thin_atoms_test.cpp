// Thinning of dense atoms (thin_atoms.h) and the garbing with a tolerance (garb.h).
#include "garbing/thin_atoms.h"
#include "core/errors.h"
#include "core/mesh_topology.h"
#include "core/triangle_defects.h"
#include "garbing/garb.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "atom_sets.h"

namespace {

using Eigen::Vector3d;

/// Pole-like dense atoms of a torus tube (core circle of radius 1, tube 0.3): centres scattered
/// within 0.05 of the core circle, each ball shrunk by its offset so that it stays in the tube.
/// Most balls lie inside a neighbour's up to a small slack, as poles of a finely meshed object do.
mg::MedialSurface dense_tube(int n, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> unit(0, 1);
  mg::MedialSurface s;
  for (int k = 0; k < n; ++k) {
    const double t = 2 * M_PI * unit(gen), phi = 2 * M_PI * unit(gen);
    const double rho = 0.05 * std::sqrt(unit(gen));
    const Vector3d radial(std::cos(t), std::sin(t), 0);
    const Vector3d offset = rho * (std::cos(phi) * radial + std::sin(phi) * Vector3d::UnitZ());
    s.atoms.push_back({radial + offset, 0.3 - 0.9 * rho});
  }
  return s;
}

/// Atoms of a medial sheet, as a finely sampled plate's poles: centres spread over the unit disk
/// (within 1e-4 of the plane z = 0), radii 0.2 shrinking slowly outwards.
mg::MedialSurface dense_sheet(int n, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> unit(0, 1);
  mg::MedialSurface s;
  for (int k = 0; k < n; ++k) {
    const double t = 2 * M_PI * unit(gen), rho = std::sqrt(unit(gen));
    const Vector3d c(rho * std::cos(t), rho * std::sin(t), 1e-4 * (unit(gen) - 0.5));
    s.atoms.push_back({c, 0.2 - 0.02 * rho * rho});
  }
  return s;
}

bool contains(const mg::MedialAtom& big, const mg::MedialAtom& small, double slack) {
  return (small.centre - big.centre).norm() + small.radius <= big.radius + slack;
}

TEST(ThinAtoms, EveryDroppedBallHasAKeptContainer) {
  const mg::MedialSurface s = dense_tube(6000, 7);
  const double slack = 0.01;
  mg::garbing::ThinStats stats;
  std::vector<int> kept;
  const mg::MedialSurface out = mg::garbing::thin_atoms(s, slack, &stats, &kept);
  ASSERT_EQ(out.atoms.size(), kept.size());
  EXPECT_EQ(stats.kept, kept.size());
  EXPECT_EQ(stats.kept + stats.dropped, s.atoms.size());
  EXPECT_EQ(stats.slack, slack);
  // Dense: most balls go.
  EXPECT_LT(4 * kept.size(), s.atoms.size());
  // The kept atoms, in their order.
  for (std::size_t k = 0; k < kept.size(); ++k) {
    if (k > 0) {
      EXPECT_LT(kept[k - 1], kept[k]);
    }
    EXPECT_EQ(out.atoms[k].centre, s.atoms[kept[k]].centre);
    EXPECT_EQ(out.atoms[k].radius, s.atoms[kept[k]].radius);
  }
  // Every dropped ball lies in a kept ball grown by the slack: the unions are within the slack.
  std::vector<char> is_kept(s.atoms.size(), 0);
  for (int i : kept) is_kept[i] = 1;
  for (std::size_t i = 0; i < s.atoms.size(); ++i) {
    if (is_kept[i]) continue;
    EXPECT_TRUE(
        std::any_of(out.atoms.begin(), out.atoms.end(),
                    [&](const mg::MedialAtom& b) { return contains(b, s.atoms[i], slack); }))
        << "atom " << i;
  }
}

TEST(ThinAtoms, NearbyContainedBallsGoAndDuplicatesKeepTheFirst) {
  const double slack = 0.01;
  // b lies in a up to the slack (centres 0.015 apart); c is a duplicate of a; d is apart.
  const mg::MedialSurface s = mg_test::atoms({{Vector3d(0.015, 0, 0), 0.5},
                                              {Vector3d(0, 0, 0), 0.51},
                                              {Vector3d(0, 0, 0), 0.51},
                                              {Vector3d(3, 0, 0), 0.1}});
  std::vector<int> kept;
  mg::garbing::thin_atoms(s, slack, nullptr, &kept);
  EXPECT_EQ(kept, (std::vector<int>{1, 3}));
  // Slack 0 keeps every atom, even a duplicate.
  mg::garbing::thin_atoms(s, 0, nullptr, &kept);
  EXPECT_EQ(kept, (std::vector<int>{0, 1, 2, 3}));
}

TEST(ThinAtoms, EachPairWithinTheSlackKeepsOneWhereverTheGridCellsFall) {
  // Far-apart pairs of equal balls, centres 0 < |d| <= slack apart in random directions, at
  // random places relative to the grid (side 8 slack): one of each pair goes, whichever cells
  // they fall in (a search of the wrong neighbour cells misses the pairs split by a cell face).
  const double slack = 0.01;
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> unit(0, 1);
  mg::MedialSurface s;
  for (int k = 0; k < 300; ++k) {
    const Vector3d at(10.0 * k + unit(gen), unit(gen), unit(gen));
    Vector3d d(unit(gen) - 0.5, unit(gen) - 0.5, unit(gen) - 0.5);
    d *= slack * (0.1 + 0.89 * unit(gen)) / d.norm();
    s.atoms.push_back({at, 0.05});
    s.atoms.push_back({at + d, 0.05});
  }
  std::vector<int> kept;
  mg::garbing::thin_atoms(s, slack, nullptr, &kept);
  ASSERT_EQ(kept.size(), 300u);
  for (int i : kept)
    EXPECT_TRUE(std::count_if(kept.begin(), kept.end(), [&](int j) { return j / 2 == i / 2; }) == 1)
        << "pair " << i / 2;
}

/// The kept indices of `thin` on the atoms at 1 and at 4 threads.
template <class Thin>
std::pair<std::vector<int>, std::vector<int>> kept_at_1_and_4_threads(const mg::MedialSurface& s,
                                                                      Thin thin) {
  std::vector<int> one, four;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    thin(s, 0.004, nullptr, &one);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 4);
    thin(s, 0.004, nullptr, &four);
  }
  return {one, four};
}

TEST(ThinAtoms, SameAtAnyThreadCount) {
  const mg::MedialSurface s = dense_tube(20000, 11);
  const auto [one, four] = kept_at_1_and_4_threads(s, mg::garbing::thin_atoms);
  EXPECT_EQ(one, four);
  EXPECT_LT(one.size(), s.atoms.size());
}

TEST(ThinAtoms, RefusesAnEnvelopeAndABadSlack) {
  mg::MedialSurface capsule = mg_test::atoms({{Vector3d(0, 0, 0), 1.0}, {Vector3d(2, 0, 0), 0.5}});
  EXPECT_THROW(mg::garbing::thin_atoms(capsule, -1), mg::InvalidInput);
  EXPECT_THROW(mg::garbing::thin_atoms(capsule, NAN), mg::InvalidInput);
  capsule.edges.push_back({0, 1});
  EXPECT_THROW(mg::garbing::thin_atoms(capsule, 0.1), mg::InvalidInput);
  mg::garbing::GarbOptions opt;
  opt.tolerance = 0.1;
  EXPECT_THROW(mg::garbing::garb(capsule, opt), mg::InvalidInput);  // auto: the envelope
  opt.tolerance = -0.1;
  capsule.edges.clear();
  EXPECT_THROW(mg::garbing::garb(capsule, opt), mg::InvalidInput);
}

// --- The cover pass (thin_atoms_by_cover) ---

/// Points of the ball: its centre, and points on spheres of radius r, r / 2 (Fibonacci spirals).
std::vector<Vector3d> ball_samples(const mg::MedialAtom& b, int per_sphere) {
  std::vector<Vector3d> out{b.centre};
  for (double scale : {1.0, 0.5})
    for (int k = 0; k < per_sphere; ++k) {
      const double z = 1 - (2.0 * k + 1) / per_sphere, rho = std::sqrt(1 - z * z);
      const double phi = k * M_PI * (3 - std::sqrt(5.0));
      out.push_back(b.centre +
                    scale * b.radius * Vector3d(rho * std::cos(phi), rho * std::sin(phi), z));
    }
  return out;
}

/// Whether p lies in one of the balls grown by the slack (up to 1e-12).
bool in_grown(const Vector3d& p, const std::vector<mg::MedialAtom>& balls, double slack) {
  return std::any_of(balls.begin(), balls.end(), [&](const mg::MedialAtom& b) {
    return (p - b.centre).norm() <= b.radius + slack + 1e-12;
  });
}

TEST(UnionCoversBall, NeighboursOnEverySideWithinTheReachCoverTheSphere) {
  // Equal balls (r = 1) around the ball in a plane, at distance d: each grown one (slack s)
  // covers the poles of the middle sphere when d^2 < 2 r s + s^2, and the ring covers it all
  // when no gap between neighbours' directions reaches 180 degrees.
  const double r = 1, s = 0.02, reach = std::sqrt(2 * r * s + s * s);
  const mg::MedialAtom ball{Vector3d(0, 0, 0), r};
  auto ring = [&](double d, std::vector<int> angles_deg) {
    std::vector<mg::MedialAtom> out;
    for (int a : angles_deg) {
      const double t = a * M_PI / 180;
      out.push_back({Vector3d(d * std::cos(t), d * std::sin(t), 0), r});
    }
    return out;
  };
  const std::vector<int> six = {0, 60, 120, 180, 240, 300};
  EXPECT_TRUE(mg::garbing::union_covers_ball(ball, ring(0.95 * reach, six), s));
  EXPECT_FALSE(mg::garbing::union_covers_ball(ball, ring(1.05 * reach, six), s));
  EXPECT_TRUE(mg::garbing::union_covers_ball(ball, ring(0.95 * reach, {0, 120, 240}), s));
  // A gap of more than 180 degrees (each cap passes the hemisphere by 0.6 degrees here) leaves
  // the side it faces: not covered.
  EXPECT_FALSE(mg::garbing::union_covers_ball(ball, ring(0.95 * reach, {0, 90, 170}), s));
  EXPECT_FALSE(mg::garbing::union_covers_ball(ball, ring(0.95 * reach, {0, 60, 120}), s));
  // On a line (a tube's medial curve), two neighbours suffice; one does not.
  EXPECT_TRUE(mg::garbing::union_covers_ball(ball, ring(0.95 * reach, {0, 180}), s));
  EXPECT_FALSE(mg::garbing::union_covers_ball(ball, ring(1.05 * reach, {0, 180}), s));
  EXPECT_FALSE(mg::garbing::union_covers_ball(ball, ring(0.5 * reach, {0}), s));
  EXPECT_FALSE(mg::garbing::union_covers_ball(ball, {}, s));
  // One ball that contains it up to the slack; a concentric smaller one does not.
  EXPECT_TRUE(mg::garbing::union_covers_ball(ball, {{Vector3d(0.01, 0, 0), 0.995}}, s));
  EXPECT_FALSE(mg::garbing::union_covers_ball(ball, {{Vector3d(0, 0, 0), 0.97}}, s));
}

TEST(UnionCoversBall, RepeatedCapsProveNothing) {
  // Two caps of 120 degrees, axes 90 degrees apart, each given twice (or nearly): a lens around
  // -(a + b) stays uncovered, whatever the orientation. An equal cap's circle lies on the
  // other's boundary, not inside it, so it must not count as covering it.
  std::mt19937 gen(3);
  std::normal_distribution<double> normal;
  for (int trial = 0; trial < 300; ++trial) {
    const Eigen::Quaterniond q =
        Eigen::Quaterniond(normal(gen), normal(gen), normal(gen), normal(gen)).normalized();
    const Vector3d a = q * Vector3d::UnitX(), b = q * Vector3d::UnitY();
    // |c_j| = 0.5 and r_j^2 = 1.75: cos theta = (1 + 0.25 - 1.75) / 1 = -0.5.
    const double rj = std::sqrt(1.75), tiny = trial % 2 ? 0.0 : 1e-13;
    const std::vector<mg::MedialAtom> others = {{0.5 * a, rj},
                                                {0.5 * a + Vector3d(tiny, 0, 0), rj},
                                                {0.5 * b, rj},
                                                {0.5 * b + Vector3d(0, tiny, 0), rj}};
    const mg::MedialAtom ball{Vector3d(0, 0, 0), 1};
    ASSERT_FALSE(in_grown(-(a + b).normalized(), others, 0));
    EXPECT_FALSE(mg::garbing::union_covers_ball(ball, others, 0)) << "trial " << trial;
  }
}

TEST(UnionCoversBall, NeverClaimsABallWithAnUncoveredPoint) {
  // Random neighbourhoods, near the edge of covering: whenever a ball is reported covered,
  // every sampled point of it lies in a grown neighbour; and the reports are not all "no".
  std::mt19937 gen(17);
  std::uniform_real_distribution<double> unit(0, 1);
  int covered = 0, uncovered_found = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const mg::MedialAtom ball{Vector3d(unit(gen), unit(gen), unit(gen)), 0.5 + unit(gen)};
    const double slack = 0.05 * unit(gen) * ball.radius;
    std::vector<mg::MedialAtom> others;
    const int count = 2 + static_cast<int>(10 * unit(gen));
    for (int k = 0; k < count; ++k) {
      Vector3d dir(unit(gen) - 0.5, unit(gen) - 0.5, unit(gen) - 0.5);
      dir.normalize();
      if (trial % 2 == 0) dir.z() *= 0.1;  // half the trials: a sheet, as medial atoms
      dir.normalize();
      const double d = std::sqrt(2 * ball.radius * slack) * (0.3 + unit(gen));
      others.push_back({ball.centre + d * dir, ball.radius * (0.97 + 0.06 * unit(gen))});
    }
    const bool claimed = mg::garbing::union_covers_ball(ball, others, slack);
    bool all_in = true;
    for (const Vector3d& p : ball_samples(ball, 20000))
      all_in = all_in && in_grown(p, others, slack);
    if (claimed) {
      ++covered;
      EXPECT_TRUE(all_in) << "trial " << trial;
    } else if (!all_in) {
      ++uncovered_found;
    }
  }
  EXPECT_GT(covered, 40);
  EXPECT_GT(uncovered_found, 40);
}

TEST(ThinAtomsByCover, EveryDroppedBallLiesWithinTheSlackOfTheKeptBalls) {
  const mg::MedialSurface s = dense_sheet(6000, 7);
  const double slack = 0.01;
  mg::garbing::ThinStats stats, contain_stats;
  std::vector<int> kept;
  const mg::MedialSurface out = mg::garbing::thin_atoms_by_cover(s, slack, &stats, &kept);
  mg::garbing::thin_atoms(s, slack, &contain_stats);
  ASSERT_EQ(out.atoms.size(), kept.size());
  EXPECT_EQ(stats.kept, kept.size());
  EXPECT_EQ(stats.kept + stats.dropped, s.atoms.size());
  EXPECT_GT(stats.covered, 0u);
  EXPECT_LE(stats.covered, stats.dropped);
  EXPECT_EQ(stats.slack, slack);
  // The union of neighbours covers far more than one container: a fraction of thin_atoms' count.
  EXPECT_LT(3 * stats.kept, contain_stats.kept);
  for (std::size_t k = 0; k < kept.size(); ++k) {
    if (k > 0) {
      EXPECT_LT(kept[k - 1], kept[k]);
    }
    EXPECT_EQ(out.atoms[k].centre, s.atoms[kept[k]].centre);
    EXPECT_EQ(out.atoms[k].radius, s.atoms[kept[k]].radius);
  }
  // Each dropped ball's points (2,000 per sphere, about 0.013 apart on a radius of 0.2) lie in
  // a kept ball grown by the slack (checked against the kept balls that can reach it).
  std::vector<char> is_kept(s.atoms.size(), 0);
  for (int i : kept) is_kept[i] = 1;
  int checked = 0;
  for (std::size_t i = 0; i < s.atoms.size(); i += 3) {
    if (is_kept[i]) continue;
    std::vector<mg::MedialAtom> near;
    for (const mg::MedialAtom& b : out.atoms)
      if ((b.centre - s.atoms[i].centre).norm() <= b.radius + s.atoms[i].radius + slack)
        near.push_back(b);
    for (const Vector3d& p : ball_samples(s.atoms[i], 2000))
      ASSERT_TRUE(in_grown(p, near, slack)) << "atom " << i;
    ++checked;
  }
  EXPECT_GT(checked, 1000);
}

TEST(ThinAtomsByCover, TheKeptCountFollowsTheSlackNotTheDensity) {
  // Ten times the atoms of the same sheet: thin_atoms keeps about five times as many, the
  // cover pass about 1.4 times (it nears the count the slack sets, about the sheet's area /
  // (0.87 * 2 r slack / 2): 3,600 here). Measured: 2,759 -> 3,973 against 8,884 -> 45,605.
  const double slack = 0.005;
  mg::garbing::ThinStats sparse, dense, sparse_contain, dense_contain;
  mg::garbing::thin_atoms_by_cover(dense_sheet(10000, 1), slack, &sparse);
  mg::garbing::thin_atoms_by_cover(dense_sheet(100000, 2), slack, &dense);
  mg::garbing::thin_atoms(dense_sheet(10000, 1), slack, &sparse_contain);
  mg::garbing::thin_atoms(dense_sheet(100000, 2), slack, &dense_contain);
  EXPECT_LT(static_cast<double>(dense.kept), 1.6 * static_cast<double>(sparse.kept));
  EXPECT_LT(static_cast<double>(dense.kept), 5000.0);
  EXPECT_GT(static_cast<double>(dense_contain.kept),
            4.0 * static_cast<double>(sparse_contain.kept));
}

TEST(ThinAtomsByCover, SameAtAnyThreadCountAndRefusals) {
  const mg::MedialSurface s = dense_tube(20000, 11);
  const auto [one, four] = kept_at_1_and_4_threads(s, mg::garbing::thin_atoms_by_cover);
  EXPECT_EQ(one, four);
  EXPECT_LT(one.size(), s.atoms.size());
  std::vector<int> all;
  mg::garbing::thin_atoms_by_cover(s, 0, nullptr, &all);
  EXPECT_EQ(all.size(), s.atoms.size());
  mg::MedialSurface capsule = mg_test::atoms({{Vector3d(0, 0, 0), 1.0}, {Vector3d(2, 0, 0), 0.5}});
  EXPECT_THROW(mg::garbing::thin_atoms_by_cover(capsule, -1), mg::InvalidInput);
  EXPECT_THROW(mg::garbing::thin_atoms_by_cover(capsule, INFINITY), mg::InvalidInput);
  capsule.edges.push_back({0, 1});
  EXPECT_THROW(mg::garbing::thin_atoms_by_cover(capsule, 0.1), mg::InvalidInput);
}

TEST(Garb, ToleranceKeepsTheGivenAtomsDepth) {
  // A ball of radius 1 holding 20 of radius 0.05 near its centre: rc = 0.525 gives d = 5 (root
  // side 2); thinned, the big ball alone would give rc = 1 and d = 4. The given atoms' d stays.
  mg::MedialSurface s = mg_test::atoms({{Vector3d(0, 0, 0), 1.0}});
  for (int k = 0; k < 20; ++k)
    s.atoms.push_back({Vector3d(0.01 * k - 0.1, 0.005 * k, -0.004 * k), 0.05});
  mg::garbing::GarbOptions opt;
  const mg::garbing::Garbing exact = mg::garbing::garb(s, opt);
  ASSERT_EQ(exact.tree.min_depth, 5);
  opt.tolerance = 1;
  const mg::garbing::Garbing thin = mg::garbing::garb(s, opt);
  EXPECT_EQ(thin.thinning.kept, 1u);
  EXPECT_EQ(thin.tree.min_depth, 5);
  EXPECT_EQ(mg::garbing::automatic_min_depth(thin.tree.root_side, thin.tree.rc, 14), 4);
  // Options are checked before the thinning, with build_octree's messages.
  opt.octree.min_depth = 12;
  opt.octree.max_depth = 10;
  try {
    mg::garbing::garb(s, opt);
    ADD_FAILURE() << "min depth above max depth accepted";
  } catch (const mg::InvalidInput& e) {
    EXPECT_STREQ(e.what(), "min depth 12 must be in [0, max depth 10]");
  }
}

/// Largest distance from M2's vertices to G.
double farthest_vertex(const mg::Mesh& m, const mg::garbing::TargetShape& g) {
  double most = 0;
  for (const auto& v : m.vertices()) {
    const auto& p = m.point(v);
    most = std::max(most, g.distance(Vector3d(p[0], p[1], p[2])));
  }
  return most;
}

TEST(Garb, ToleranceThinsDenseAtomsKeepsTheResolutionAndLandsOnTheThinnedG) {
  const mg::MedialSurface s = dense_tube(4000, 3);
  using mg::garbing::ThinMethod;
  for (bool spheres_only : {false, true}) {
    mg::garbing::GarbOptions opt;
    opt.octree.min_depth = 6;  // a leaf side of 0.04, the tube's radius 0.3
    if (spheres_only) opt.cones.source = mg::garbing::ConeSource::none;
    const mg::garbing::Garbing exact = mg::garbing::garb(s, opt);
    for (ThinMethod method : {ThinMethod::contain, ThinMethod::cover}) {
      opt.thinning = method;
      opt.tolerance = 0.25;
      const mg::garbing::Garbing thin = mg::garbing::garb(s, opt);
      EXPECT_EQ(thin.tree.min_depth, 6);
      EXPECT_DOUBLE_EQ(thin.thinning.slack, 0.25 * exact.tree.side(6));
      EXPECT_LT(2 * thin.thinning.kept, s.atoms.size());
      EXPECT_EQ(thin.g.sphere_count(), thin.thinning.kept);
      for (const mg::garbing::Garbing* r : {&exact, &thin}) {
        const auto soup = mg::soup_from_mesh(r->m2.mesh);
        const auto t = mg::mesh_topology(soup);
        EXPECT_TRUE(t.closed && t.manifold && t.oriented) << t.first_problem;
        EXPECT_EQ(t.genus, 1);
        const auto d = mg::find_triangle_defects(soup);
        EXPECT_TRUE(d.intersecting_pairs.empty());
        EXPECT_TRUE(d.degenerate_faces.empty());
      }
      // M2's vertices land on the thinned G (in world coordinates, as the meshes).
      mg::garbing::ConeOptions cones = opt.cones;
      const mg::MedialSurface sorted = mg::spatially_sorted(s);
      const double slack = thin.thinning.slack;
      const mg::garbing::TargetShape exact_g = mg::garbing::make_target_shape(s, cones);
      const mg::garbing::TargetShape thin_g = mg::garbing::make_target_shape(
          method == ThinMethod::cover ? mg::garbing::thin_atoms_by_cover(sorted, slack)
                                      : mg::garbing::thin_atoms(sorted, slack),
          cones);
      EXPECT_LT(farthest_vertex(exact.m2.mesh, exact_g), 1e-9);
      EXPECT_LT(farthest_vertex(thin.m2.mesh, thin_g), 1e-9);
      // The union of the balls moves by at most the slack, G's boundary may move more (a
      // crease bottom, a cone pair of the thinned atoms' own). Measured on this set, the
      // vertices' farthest from the exact G (cones, balls alone): contain 0.82, 0.74 slack;
      // cover 0.81, 0.71. Bound 1 slack.
      EXPECT_LE(farthest_vertex(thin.m2.mesh, exact_g), slack)
          << spheres_only << " " << (method == ThinMethod::cover);
    }
  }
  mg::garbing::GarbOptions opt;
  opt.octree.min_depth = 6;
  opt.tolerance = 0.25;
  // The same mesh for the atoms in another order.
  mg::MedialSurface shuffled = s;
  std::reverse(shuffled.atoms.begin(), shuffled.atoms.end());
  const mg::garbing::Garbing again = mg::garbing::garb(shuffled, opt);
  const mg::garbing::Garbing thin = mg::garbing::garb(s, opt);
  EXPECT_EQ(mg::soup_from_mesh(again.m2.mesh).points, mg::soup_from_mesh(thin.m2.mesh).points);
  EXPECT_EQ(mg::soup_from_mesh(again.m2.mesh).faces, mg::soup_from_mesh(thin.m2.mesh).faces);
}

}  // namespace
