#include "garbing/target_shape.h"
#include "core/errors.h"
#include "garbing/detail/regular_edges.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

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

TEST(TargetShape, BoxQueriesFindEveryPrimitiveAmongSlabsWithoutPrisms) {
  // Envelope slabs, every other one too steep for a prism: those have no box in the hierarchy,
  // the others' boxes are reordered around the gaps. Each ball is found at its centre, each
  // prism at its centres' centroid; a slab without prism never; balls exactly on random boxes.
  mg::MedialSurface s;
  std::vector<std::array<int, 3>> triples;
  for (int k = 0; k < 60; ++k) {
    const int first = static_cast<int>(s.atoms.size());
    const Vector3d o(3.0 * (k % 8), 3.0 * (k / 8), 0.5 * (k % 3));
    const bool steep = k % 2 == 1;
    s.atoms.push_back({o, steep ? 3.0 : 0.3});
    s.atoms.push_back({o + Vector3d(1, 0, 0), steep ? 0.1 : 0.35});
    s.atoms.push_back({o + Vector3d(0, 1, 0.2), steep ? 0.1 : 0.25});
    triples.push_back({first, first + 1, first + 2});
  }
  const gb::TargetShape g(s, {}, triples, gb::Frame{});
  ASSERT_EQ(g.slab_count(), 60u);
  std::vector<gb::PrimitiveId> found;
  auto query = [&](const Vector3d& lo, const Vector3d& hi) {
    found.clear();
    g.primitives_meeting_box(lo, hi, found);
    return found;
  };
  const Vector3d eps = Vector3d::Constant(1e-6);
  for (std::size_t i = 0; i < g.sphere_count(); ++i) {
    const auto hit = query(s.atoms[i].centre - eps, s.atoms[i].centre + eps);
    EXPECT_NE(std::find(hit.begin(), hit.end(), static_cast<int>(i)), hit.end()) << i;
  }
  for (int k = 0; k < 60; ++k) {
    const gb::PrimitiveId id = g.slab_id(k);
    EXPECT_EQ(g.slab(id).has_tangent_triangles, k % 2 == 0);
    const auto hit = query(Vector3d::Constant(-100), Vector3d::Constant(100));
    EXPECT_EQ(std::find(hit.begin(), hit.end(), id) != hit.end(), k % 2 == 0) << k;
    if (k % 2 == 1) continue;
    const Vector3d centroid = (s.atoms[triples[k][0]].centre + s.atoms[triples[k][1]].centre +
                               s.atoms[triples[k][2]].centre) /
                              3;
    const auto near = query(centroid - eps, centroid + eps);
    EXPECT_NE(std::find(near.begin(), near.end(), id), near.end()) << k;
  }
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> x(-3, 24), y(-3, 24), z(-3, 4), side(0.05, 2);
  for (int q = 0; q < 300; ++q) {
    const Vector3d lo(x(gen), y(gen), z(gen));
    const Vector3d hi = lo + Vector3d(side(gen), side(gen), side(gen));
    std::vector<gb::PrimitiveId> balls;
    for (gb::PrimitiveId id : query(lo, hi))
      if (g.is_sphere(id)) balls.push_back(id);
    std::vector<gb::PrimitiveId> expected;
    for (std::size_t i = 0; i < s.atoms.size(); ++i) {
      const Vector3d c = s.atoms[i].centre;
      if ((c.cwiseMax(lo).cwiseMin(hi) - c).squaredNorm() <= s.atoms[i].radius * s.atoms[i].radius)
        expected.push_back(static_cast<int>(i));
    }
    EXPECT_EQ(balls, expected) << q;
  }
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

TEST(ConePairs, RegularTriangulationAtAnyThreadCountAndWithRepeatedAtoms) {
  // A lattice of equal balls (every cell of it cospherical: the triangulation rests on CGAL's
  // symbolic perturbation) and jittered balls of random radii, then copies of some of them
  // appended: the same pairs at one thread and at several (the triangulation is built in
  // parallel), and the copies (higher indices) carry no pair.
  mg::MedialSurface s;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j)
      for (int k = 0; k < 10; ++k) s.atoms.push_back({Vector3d(i, j, k), 0.8});
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> u(0, 9), radius(0.4, 1.2);
  for (int k = 0; k < 2000; ++k) s.atoms.push_back({Vector3d(u(gen), u(gen), u(gen)), radius(gen)});
  const std::size_t distinct = s.atoms.size();
  for (std::size_t k = 0; k < distinct; k += 7) s.atoms.push_back(s.atoms[k]);
  gb::ConeOptions opt;
  opt.min_circle_ratio = 0;
  opt.max_collar = 0;
  std::vector<std::array<int, 2>> one, several;
  {
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
    one = gb::cone_pairs(s, opt);
  }
  {
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 4);
    several = gb::cone_pairs(s, opt);
  }
  ASSERT_GT(one.size(), distinct);
  EXPECT_EQ(one, several);
  for (const auto& p : one) EXPECT_LT(p[1], static_cast<int>(distinct));
  mg::MedialSurface without = s;
  without.atoms.resize(distinct);
  EXPECT_EQ(gb::cone_pairs(without, opt), one);
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

TEST(TargetShape, ConesAreMakeConeOfTheirAtomsInItsFrame) {
  // G keeps its cones slim and restores them on demand: each is make_cone of its two balls (in
  // G's frame) bit for bit, and cone_atoms names the same atoms.
  const mg::MedialSurface s = mg_test::blob(400, 0.2, 0.6, 3);
  const gb::TargetShape g(s, gb::cone_pairs(s, {}), gb::bounding_cube_frame(s));
  ASSERT_GT(g.cone_count(), 400u);
  const int n = static_cast<int>(g.sphere_count());
  for (int id = n; id < n + static_cast<int>(g.cone_count()); ++id) {
    const gb::Cone k = g.cone(id);
    ASSERT_TRUE(mg_test::same_cone(k, gb::make_cone(g.sphere(k.a), g.sphere(k.b), k.a, k.b)));
    EXPECT_EQ(g.cone_atoms(id), (std::array<int, 2>{k.a, k.b}));
  }
}

TEST(TargetShape, BoxQueriesFindBallsThatOnlyTouchTheBox) {
  // The hierarchy keeps its boxes as floats rounded outward: a box that touches a ball at one
  // point (its lower x at centre.x + r, exactly) still finds it, for centres and radii that
  // floats do not hold.
  std::mt19937 gen(9);
  std::uniform_real_distribution<double> u(-3, 3), radius(0.01, 0.7);
  mg::MedialSurface s;
  for (int k = 0; k < 3000; ++k) s.atoms.push_back({Vector3d(u(gen), u(gen), u(gen)), radius(gen)});
  const gb::TargetShape g(s, {});
  std::vector<gb::PrimitiveId> found;
  int checked = 0;
  for (int i = 0; i < static_cast<int>(s.atoms.size()); ++i) {
    const mg::MedialAtom& a = s.atoms[i];
    for (int side : {-1, 1}) {
      // The face x = c.x + side r of a thin box meets the ball at its pole only.
      const double x = a.centre.x() + side * a.radius;
      Vector3d lo = a.centre - Vector3d::Constant(0.25), hi = a.centre + Vector3d::Constant(0.25);
      if (side > 0) {
        lo.x() = x;
        hi.x() = x + 1;
      } else {
        lo.x() = x - 1;
        hi.x() = x;
      }
      if (!gb::meets_box(a, lo, hi)) continue;  // rounding put the pole outside: nothing owed
      found.clear();
      g.primitives_meeting_box(lo, hi, found);
      ASSERT_TRUE(std::binary_search(found.begin(), found.end(), i)) << "ball " << i;
      ++checked;
    }
  }
  EXPECT_GT(checked, 1500);
}

TEST(ConePairs, RegularEdgesAreThoseOfTheTetrahedraWithAnEmptyOrthogonalSphere) {
  // The definition, by brute force: four weighted points span a cell of the regular
  // triangulation when the sphere orthogonal to all four has every other point outside it
  // (power product > 0). In general position, with hidden points (small balls inside others)
  // and a repeated atom (the lower index takes part).
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> u(0, 1), radius(0.05, 0.4);
  mg::MedialSurface s;
  for (int k = 0; k < 28; ++k) {
    const double x = u(gen), y = u(gen), z = u(gen);
    s.atoms.push_back({Vector3d(x, y, z), radius(gen)});
  }
  s.atoms.push_back({s.atoms[3].centre, 0.01});  // hidden in ball 3
  s.atoms.push_back(s.atoms[7]);                 // a repeat of atom 7
  const int n = static_cast<int>(s.atoms.size());
  auto weight = [&](int i) { return s.atoms[i].radius * s.atoms[i].radius; };
  std::vector<std::array<int, 2>> expected;
  int cells = 0;
  for (int a = 0; a < n - 1; ++a)  // the repeat (last) never spans a cell of its own
    for (int b = a + 1; b < n - 1; ++b)
      for (int c = b + 1; c < n - 1; ++c)
        for (int d = c + 1; d < n - 1; ++d) {
          const int v[4] = {a, b, c, d};
          // The orthogonal sphere's centre z: |z - c_i|^2 - w_i equal for the four.
          Eigen::Matrix3d m;
          Vector3d rhs;
          const Vector3d& c0 = s.atoms[a].centre;
          for (int k = 1; k < 4; ++k) {
            const Vector3d& ck = s.atoms[v[k]].centre;
            m.row(k - 1) = 2 * (ck - c0).transpose();
            rhs[k - 1] = ck.squaredNorm() - c0.squaredNorm() - weight(v[k]) + weight(a);
          }
          if (!(std::abs(m.determinant()) > 1e-12)) continue;  // e.g. atoms 3 and 28, one centre
          const Vector3d z = m.partialPivLu().solve(rhs);
          const double wz = (z - c0).squaredNorm() - weight(a);
          bool empty = true;
          for (int q = 0; q < n - 1 && empty; ++q)
            if (q != a && q != b && q != c && q != d)
              empty = (z - s.atoms[q].centre).squaredNorm() - weight(q) - wz > 1e-9;
          if (!empty) continue;
          ++cells;
          for (int i = 0; i < 4; ++i)
            for (int j = i + 1; j < 4; ++j) expected.push_back({v[i], v[j]});
        }
  std::sort(expected.begin(), expected.end());
  expected.erase(std::unique(expected.begin(), expected.end()), expected.end());
  ASSERT_GT(cells, 40);
  const auto edges = gb::detail::regular_edges(s);
  EXPECT_EQ(edges, expected);
  for (const auto& e : edges) {
    EXPECT_TRUE(e[0] != 28 && e[1] != 28) << "the hidden atom has an edge";
    EXPECT_NE(e[1], 29) << "the repeat has an edge";
  }
}

TEST(ConePairs, RegularEdgesTheSameAtAnyThreadCount) {
  // Thousands of atoms (the gathering runs in parallel chunks), a large first ball with a
  // hundred neighbours above it (its bucket sorted whole), hidden balls and repeats: the same
  // sorted, distinct edges at one thread and at several.
  mg::MedialSurface s;
  s.atoms.push_back({Vector3d(0, 0, 0), 0.8});
  const mg::MedialSurface cloud = mg_test::blob(6000, 0.05, 0.3, 8);
  for (const mg::MedialAtom& a : cloud.atoms) s.atoms.push_back(a);
  for (std::size_t k = 1; k < 6000; k += 13) s.atoms.push_back({s.atoms[k].centre, 0.01});
  for (std::size_t k = 1; k < 6000; k += 17) s.atoms.push_back(s.atoms[k]);
  std::vector<std::array<int, 2>> one, several;
  {
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
    one = gb::detail::regular_edges(s);
  }
  {
    tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 4);
    several = gb::detail::regular_edges(s);
  }
  ASSERT_GT(one.size(), 10000u);
  EXPECT_EQ(one, several);
  EXPECT_TRUE(std::is_sorted(one.begin(), one.end()));
  EXPECT_EQ(std::adjacent_find(one.begin(), one.end()), one.end());
  for (const auto& e : one) ASSERT_LT(e[0], e[1]);
  const auto of_first =
      std::count_if(one.begin(), one.end(), [](const auto& e) { return e[0] == 0; });
  EXPECT_GT(of_first, 100);
  for (const auto& e : one) ASSERT_LT(e[1], 6001) << "a hidden ball or a repeat has an edge";
}

}  // namespace
