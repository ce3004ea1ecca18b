#include "garbing/target_shape.h"
#include "core/errors.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "atom_sets.h"

namespace {

namespace gb = mg::garbing;
using Eigen::Vector3d;
using mg_test::atoms;

// The cone of the example: r1 = 1 at the origin, r2 = 0.5 at (2, 0, 0), L = 2.
const mg::MedialAtom kA{Vector3d(0, 0, 0), 1.0};
const mg::MedialAtom kB{Vector3d(2, 0, 0), 0.5};

TEST(TargetShape, WithinIsTheDistanceToTheUnionAgainstATolerance) {
  const auto s = atoms({kA, kB});
  const gb::TargetShape shape(s, {{0, 1}});
  const double cos_phi = std::sqrt(1 - 0.0625);
  const double over_cone = (2 - 0.75 / cos_phi) * cos_phi;  // (1, 2, 0) to the lateral surface
  EXPECT_TRUE(shape.within(Vector3d(1, 2, 0), over_cone * (1 + 1e-9)));
  EXPECT_FALSE(shape.within(Vector3d(1, 2, 0), over_cone * (1 - 1e-9)));
  EXPECT_TRUE(shape.within(Vector3d(0, -1.5, 0), 0.5 + 1e-12));  // 0.5 from the first ball
  EXPECT_FALSE(shape.within(Vector3d(0, -1.5, 0), 0.5 - 1e-9));
  EXPECT_TRUE(shape.within(Vector3d(0.2, 0.1, 0), 0));  // inside
  // Between the balls (1.22 from both centres), under the lateral surface (R(1) = 0.775).
  EXPECT_FALSE(gb::TargetShape(s, {}).within(Vector3d(1, 0.7, 0), 0.01));
  EXPECT_TRUE(shape.within(Vector3d(1, 0.7, 0), 0));
}

/// line_to_boundary against the definition, from every primitive's interval: from outside,
/// the smallest entry in (0, t_max]; from inside, where the merged run holding t = 0 ends
/// toward negative t. Random lines through a blob of balls and their cones, some axis-parallel.
TEST(TargetShape, LineToBoundaryMatchesAllIntervals) {
  const auto s = mg_test::blob(40, 0.1, 0.35, 5);
  gb::ConeOptions every;
  every.min_circle_ratio = 0;
  every.max_collar = 0;
  const gb::TargetShape shape(s, gb::cone_pairs(s, every));
  ASSERT_GT(shape.cone_count(), 20u);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> box(-1.3, 1.3), unit(-1, 1);
  int inside_count = 0, hits = 0;
  for (int n = 0; n < 2000; ++n) {
    const Vector3d v(box(rng), box(rng), box(rng));
    Vector3d dir(unit(rng), unit(rng), unit(rng));
    if (n % 10 == 0) dir = Vector3d::Unit(n / 10 % 3);  // components equal to 0
    const double t_max = 0.6;
    std::vector<std::pair<double, double>> runs;
    const int total = static_cast<int>(shape.sphere_count() + shape.cone_count());
    for (int i = 0; i < total; ++i) {
      double a, z;
      if (shape.ray_interval(i, v, dir, a, z)) runs.emplace_back(a, z);
    }
    bool inside = false;
    for (const auto& [a, z] : runs) inside = inside || (a <= 0 && z >= 0);
    double expected = 0;
    bool found;
    if (!inside) {
      double first = INFINITY;
      for (const auto& [a, z] : runs)
        if (a > 0 && a <= t_max) first = std::min(first, a);
      found = first <= t_max;
      expected = first;
    } else {
      std::sort(runs.begin(), runs.end(),
                [](const auto& x, const auto& y) { return x.second > y.second; });
      double end = 0;
      for (const auto& [a, z] : runs) {
        if (z < end - 1e-12 * (1 + t_max)) break;
        end = std::min(end, a);
      }
      found = end >= -t_max;
      expected = end;
    }
    double t = 0;
    bool got_inside = false;
    const bool got = shape.line_to_boundary(v, dir, t_max, t, got_inside);
    ASSERT_EQ(got_inside, inside) << n;
    ASSERT_EQ(got, found) << n;
    if (found) {
      EXPECT_EQ(t, expected) << n;
    }
    inside_count += inside;
    hits += found;
  }
  EXPECT_GT(inside_count, 100);
  EXPECT_GT(hits, 500);
}

TEST(TargetShape, RaysThroughTheConeSolid) {
  const gb::TargetShape cone_only(atoms({kA, kB}), {{0, 1}});
  // Remove the spheres' contribution by starting between them on a ray across the waist:
  // at x = 1 the cone's radius is (1 - 0.25) / cos(phi) = 0.7745966692414834.
  double t;
  ASSERT_TRUE(cone_only.first_entry(Vector3d(1, -5, 0), Vector3d(0, 1, 0), 10, t));
  EXPECT_NEAR(t, 5 - 0.7745966692414834, 1e-12);
  ASSERT_TRUE(cone_only.run_end(Vector3d(1, 0, 0), Vector3d(0, 1, 0), 10, t));
  EXPECT_NEAR(t, 0.7745966692414834, 1e-12);
  // Along the axis from the first centre: sphere [-1, 1], cone [0.25, 2.125], sphere [1.5, 2.5].
  ASSERT_TRUE(cone_only.run_end(Vector3d(0, 0, 0), Vector3d(1, 0, 0), 10, t));
  EXPECT_NEAR(t, 2.5, 1e-12);
  // The run goes beyond the searched segment: not reported.
  EXPECT_FALSE(cone_only.run_end(Vector3d(0, 0, 0), Vector3d(1, 0, 0), 2.0, t));
  // A ray that misses everything.
  EXPECT_FALSE(cone_only.first_entry(Vector3d(0, 5, 0), Vector3d(1, 0, 0), 100, t));
}

TEST(TargetShape, ContainsAndClosestPoint) {
  const gb::TargetShape shape(atoms({kA, kB}), {{0, 1}});
  EXPECT_TRUE(shape.contains(Vector3d(1, 0.7, 0)));  // in the cone, outside both balls
  EXPECT_FALSE(shape.contains(Vector3d(1, 0.8, 0)));
  const gb::TargetShape balls(atoms({kA, kB}), {});
  EXPECT_FALSE(balls.contains(Vector3d(1, 0.7, 0)));  // the waist without the cone
  // Outside: exact nearest point.
  EXPECT_TRUE(shape.closest_point(Vector3d(-3, 0, 0)).isApprox(Vector3d(-1, 0, 0), 1e-15));
  // Above the waist the nearest point is on the cone: distance (rho - R(x)) cos(phi).
  const double cos_phi = std::sqrt(15.0) / 4;
  EXPECT_NEAR(shape.distance(Vector3d(1, 2, 0)), (2 - 0.75 / cos_phi) * cos_phi, 1e-12);
  // Inside a ball far from the other: the radial projection.
  EXPECT_NEAR(shape.distance(Vector3d(-0.5, 0, 0)), 0.5, 1e-12);
}

TEST(ConePairs, SourcesAndFilter) {
  // A chain of 4 balls plus one inside another (no cone with it) and one far away.
  mg::MedialSurface s = atoms({{Vector3d(0, 0, 0), 1},
                               {Vector3d(1.5, 0, 0), 1},
                               {Vector3d(3, 0, 0), 1},
                               {Vector3d(4.9, 0, 0), 1},
                               {Vector3d(0.1, 0, 0), 0.2},
                               {Vector3d(10, 0, 0), 1}});
  s.edges = {{1, 0}, {2, 3}, {0, 4}};
  gb::ConeOptions opt;
  opt.min_circle_ratio = 0;
  opt.max_collar = 0;  // no collar limit here (see CollarLimitMatchesTheConeGeometry)
  opt.source = gb::ConeSource::all_pairs;
  const auto all = gb::cone_pairs(s, opt);
  // 0-1, 1-2, 2-3 and 0-2 (distance 3 > 2: no), 1-4 (contains? no: 1.4 < 1.2? no) ...
  for (const auto& p : all) {
    const auto& a = s.atoms[p[0]];
    const auto& b = s.atoms[p[1]];
    const double L = (a.centre - b.centre).norm();
    EXPECT_LT(L, a.radius + b.radius);
    EXPECT_GT(L, std::abs(a.radius - b.radius));
  }
  EXPECT_NE(std::find(all.begin(), all.end(), std::array<int, 2>{2, 3}), all.end());
  opt.source = gb::ConeSource::ma_edges;
  EXPECT_EQ(gb::cone_pairs(s, opt), (std::vector<std::array<int, 2>>{{0, 1}, {2, 3}}));
  opt.source = gb::ConeSource::regular_triangulation;
  const auto rt = gb::cone_pairs(s, opt);
  for (const auto& p : rt) EXPECT_NE(std::find(all.begin(), all.end(), p), all.end());
  // Balls 2 and 3 barely intersect (circle radius 0.31 r), balls 0 and 1 well (0.66 r): a 0.5
  // filter drops the first cone only.
  opt.source = gb::ConeSource::all_pairs;
  opt.min_circle_ratio = 0.5;
  const auto kept = gb::cone_pairs(s, opt);
  EXPECT_EQ(std::find(kept.begin(), kept.end(), std::array<int, 2>{2, 3}), kept.end());
  EXPECT_NE(std::find(kept.begin(), kept.end(), std::array<int, 2>{0, 1}), kept.end());
  EXPECT_THROW(gb::parse_cone_source("some"), mg::InvalidInput);
}

TEST(ConePairs, RegularTriangulationEdgesOfATallBipyramid) {
  // Equal balls on a unit triangle (z = 0) and two apexes at z = +-2: every pair of balls
  // intersects, but the regular triangulation is two tetrahedra on the triangle, so the two
  // apexes share no edge. The other 9 pairs are edges, each listed once.
  const double c = std::sqrt(3.0) / 2;
  const mg::MedialSurface s = atoms({{Vector3d(1, 0, 0), 2.5},
                                     {Vector3d(-0.5, c, 0), 2.5},
                                     {Vector3d(-0.5, -c, 0), 2.5},
                                     {Vector3d(0, 0, 2), 2.5},
                                     {Vector3d(0, 0, -2), 2.5}});
  gb::ConeOptions opt;
  opt.min_circle_ratio = 0;
  opt.max_collar = 0;
  opt.source = gb::ConeSource::all_pairs;
  EXPECT_EQ(gb::cone_pairs(s, opt).size(), 10u);
  opt.source = gb::ConeSource::regular_triangulation;
  EXPECT_EQ(gb::cone_pairs(s, opt),
            (std::vector<std::array<int, 2>>{
                {0, 1}, {0, 2}, {0, 3}, {0, 4}, {1, 2}, {1, 3}, {1, 4}, {2, 3}, {2, 4}}));
  // Flattened (apexes at z = +-0.3), the apexes' edge crosses the triangle: all 10 pairs.
  mg::MedialSurface flat = s;
  flat.atoms[3].centre.z() = 0.3;
  flat.atoms[4].centre.z() = -0.3;
  EXPECT_EQ(gb::cone_pairs(flat, opt).size(), 10u);
}

TEST(ConePairs, CollarLimitMatchesTheConeGeometry) {
  // Two balls r1 = 1, r2 = 0.6 at L = 0.9 (circle radius 0.59: ratio 0.98, kept by the 0.9
  // filter). The collar, measured on the cone itself: the distance from a point of the circle
  // where the spheres meet to the lateral surface, (R(x) - h) cos(phi).
  const mg::MedialAtom a{Vector3d(0, 0, 0), 1.0}, b{Vector3d(0.9, 0, 0), 0.6};
  const gb::Cone cone = gb::make_cone(a, b, 0, 1);
  const double L = 0.9, x = (L * L + 1 - 0.36) / (2 * L), h = std::sqrt(1 - x * x);
  const double collar = ((cone.r1 - x * cone.sin_phi) / cone.cos_phi - h) * cone.cos_phi;
  ASSERT_GT(collar, 0.01);
  // The collar must lie on the lateral surface's inner side: the crease point is inside the cone.
  const mg::MedialSurface s = atoms({a, b});
  gb::TargetShape shape(s, {{0, 1}});
  EXPECT_TRUE(shape.primitive_contains(1 + 1, Vector3d(x, h, 0), 0.5 * collar));  // cone id 2
  EXPECT_FALSE(shape.primitive_contains(1 + 1, Vector3d(x, h, 0), 1.5 * collar));
  const double unit = (1.0 + 0.6) / 2 / 8;  // rc / 8
  gb::ConeOptions opt;
  opt.source = gb::ConeSource::all_pairs;
  opt.max_collar = collar / unit * (1 + 1e-9);
  EXPECT_EQ(gb::cone_pairs(s, opt).size(), 1u);
  opt.max_collar = collar / unit * (1 - 1e-9);
  EXPECT_TRUE(gb::cone_pairs(s, opt).empty());
  opt.max_collar = 0;  // no limit
  EXPECT_EQ(gb::cone_pairs(s, opt).size(), 1u);
  opt.max_collar = -1;
  EXPECT_THROW(gb::cone_pairs(s, opt), mg::InvalidInput);
  EXPECT_EQ(gb::ConeOptions{}.max_collar, 1.0);  // the default the cone study chose
}

}  // namespace
