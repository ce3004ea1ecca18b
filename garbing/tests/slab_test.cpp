// The medial slab against hand-computed values and a brute-force oracle over its triangle.
#include "garbing/slab.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace {

using Eigen::Vector3d;
namespace gb = mg::garbing;

gb::Slab slab_of(const mg::MedialAtom& a, const mg::MedialAtom& b, const mg::MedialAtom& c) {
  return gb::make_slab(a, b, c, 0, 1, 2);
}

/// min over a barycentric grid (n steps per side) of f(centre, radius).
template <class F>
double grid_minimum(const gb::Slab& s, int n, const F& f) {
  double best = INFINITY;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; i + j <= n; ++j) {
      const double u = double(i) / n, v = double(j) / n;
      best = std::min(best, f(s.centre(u, v), s.radius(u, v)));
    }
  return best;
}

double oracle_distance(const gb::Slab& s, const Vector3d& p) {
  return grid_minimum(s, 400, [&](const Vector3d& c, double r) { return (p - c).norm() - r; });
}

/// min over the triangle of |p - c(l)| - r(l) by brute force, to ~1e-10: a 60-step grid, then
/// grids of 13 x 13 around the best node, each a quarter as wide, clamped to the triangle, and
/// the same along the three edges (where the minimum sits when it leaves the interior).
double fine_oracle_distance(const gb::Slab& s, const Vector3d& p) {
  auto f = [&](double u, double v) { return (p - s.centre(u, v)).norm() - s.radius(u, v); };
  auto clamp_to_triangle = [](double& u, double& v) {
    u = std::max(u, 0.0);
    v = std::max(v, 0.0);
    if (u + v > 1) {
      const double excess = (u + v - 1) / 2;
      u -= excess;
      v -= excess;
      u = std::clamp(u, 0.0, 1.0);
      v = 1 - u;
    }
  };
  double best = INFINITY, bu = 0, bv = 0;
  const int n = 60;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; i + j <= n; ++j)
      if (const double x = f(double(i) / n, double(j) / n); x < best) {
        best = x;
        bu = double(i) / n;
        bv = double(j) / n;
      }
  for (double h = 1.0 / n; h > 1e-12; h /= 4)
    for (int i = -6; i <= 6; ++i)
      for (int j = -6; j <= 6; ++j) {
        double u = bu + i * h / 2, v = bv + j * h / 2;
        clamp_to_triangle(u, v);
        if (const double x = f(u, v); x < best) {
          best = x;
          bu = u;
          bv = v;
        }
      }
  // The edges, parametrised (u, v) = a + t (b - a).
  const double ends[3][4] = {{0, 0, 1, 0}, {1, 0, 0, 1}, {0, 1, 0, 0}};
  for (const auto& e : ends) {
    auto g = [&](double t) { return f(e[0] + t * (e[2] - e[0]), e[1] + t * (e[3] - e[1])); };
    double bt = 0, edge_best = INFINITY;
    for (int i = 0; i <= 1000; ++i)
      if (const double x = g(i / 1000.0); x < edge_best) {
        edge_best = x;
        bt = i / 1000.0;
      }
    for (double h = 1e-3; h > 1e-13; h /= 4)
      for (int i = -6; i <= 6; ++i) {
        const double t = std::clamp(bt + i * h / 2, 0.0, 1.0);
        if (const double x = g(t); x < edge_best) {
          edge_best = x;
          bt = t;
        }
      }
    best = std::min(best, edge_best);
  }
  return best;
}

/// Three unit balls at the corners of a triangle in z = 0: a rounded plate of half-thickness 1.
gb::Slab plate() {
  return slab_of({Vector3d(0, 0, 0), 1}, {Vector3d(4, 0, 0), 1}, {Vector3d(0, 4, 0), 1});
}

TEST(Slab, PlateByHand) {
  const gb::Slab s = plate();
  ASSERT_TRUE(s.has_tangent_triangles);
  EXPECT_NEAR(s.gradient.norm(), 0, 1e-15);
  const Vector3d c(4.0 / 3, 4.0 / 3, 0);  // the centroid
  EXPECT_NEAR(gb::slab_distance(s, c + Vector3d(0, 0, 3)), 2, 1e-12);
  EXPECT_NEAR(gb::slab_distance(s, c), -1, 1e-12);
  EXPECT_TRUE((gb::closest_solid_point(s, c + Vector3d(0, 0, 3)) - (c + Vector3d(0, 0, 1))).norm() <
              1e-12);
  // From inside, the nearest boundary point is on a tangent plane.
  EXPECT_TRUE(
      (gb::closest_boundary_point(s, c + Vector3d(0, 0, 0.25)) - (c + Vector3d(0, 0, 1))).norm() <
      1e-12);
  // On an edge's axis and at a centre, every way out is 1 long.
  for (const Vector3d& p : {Vector3d(2, 0, 0), Vector3d(0, 0, 0), Vector3d(0, 4, 0)}) {
    const Vector3d q = gb::closest_boundary_point(s, p);
    EXPECT_NEAR((q - p).norm(), 1, 1e-12) << p.transpose();
    EXPECT_NEAR(gb::slab_distance(s, q), 0, 1e-12) << p.transpose();
  }
  // The tangent triangles are the medial triangle at z = +-1.
  for (int side = 0; side < 2; ++side)
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(std::abs(s.tangent[side][i].z()), 1, 1e-12);
  EXPECT_NEAR(gb::tangent_area(s), 2 * 8, 1e-12);
  // m_g(v) = r (v - p) / |v - p|^2 with p the foot (the centroid), r = 1: (0, 0, 1/2) at z = 2.
  EXPECT_TRUE((gb::migration_vector(s, c + Vector3d(0, 0, 2)) - Vector3d(0, 0, 0.5)).norm() <
              1e-12);
  // Zero when the foot leaves the triangle, and on the medial plane.
  EXPECT_EQ(gb::migration_vector(s, Vector3d(-3, -3, 2)), Vector3d::Zero());
  EXPECT_EQ(gb::migration_vector(s, Vector3d(1, 1, 0)), Vector3d::Zero());
  double t0, t1;
  ASSERT_TRUE(gb::line_interval(s, c + Vector3d(0, 0, 5), Vector3d(0, 0, -1), t0, t1));
  EXPECT_NEAR(t0, 4, 1e-12);
  EXPECT_NEAR(t1, 6, 1e-12);
  EXPECT_FALSE(gb::line_interval(s, Vector3d(0, 0, 3), Vector3d(1, 0, 0), t0, t1));
  EXPECT_TRUE(gb::contains_deeper_than(s, c, 0.99));
  EXPECT_FALSE(gb::contains_deeper_than(s, c, 1.01));
  EXPECT_TRUE(gb::contains_deeper_than(s, c + Vector3d(0, 0, 1.5), -0.6));
  EXPECT_FALSE(gb::contains_deeper_than(s, c + Vector3d(0, 0, 1.5), -0.4));
}

// The prism of the plate: the triangle (0, 0), (4, 0), (0, 4) times z in [-1, 1].
TEST(Slab, PrismOfThePlateByHand) {
  const gb::Slab s = plate();
  const Vector3d c(4.0 / 3, 4.0 / 3, 0);
  // Depth: the least gap to the five faces (z = +-1: 1; x = 0, y = 0: 4/3; x + y = 4: the
  // centroid is (4 - 8/3) / sqrt 2 from it).
  EXPECT_NEAR(gb::prism_depth(s, c), (4 - 8.0 / 3) / std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(gb::prism_depth(s, c + Vector3d(0, 0, 0.25)), 0.75, 1e-12);
  EXPECT_NEAR(gb::prism_depth(s, c + Vector3d(0, 0, 1.5)), -0.5, 1e-12);
  EXPECT_TRUE(
      (gb::prism_boundary_point(s, c + Vector3d(0, 0, 0.25)) - (c + Vector3d(0, 0, 1))).norm() <
      1e-12);
  EXPECT_TRUE((gb::prism_boundary_point(s, Vector3d(0.25, 1, 0.1)) - Vector3d(0, 1, 0.1)).norm() <
              1e-12);
  double t0, t1;
  ASSERT_TRUE(gb::prism_interval(s, c + Vector3d(0, 0, 5), Vector3d(0, 0, -1), t0, t1));
  EXPECT_NEAR(t0, 4, 1e-12);
  EXPECT_NEAR(t1, 6, 1e-12);
  // Along x at y = 1: in from x = 0, out at x + y = 4 (the slab itself reaches x = -1 and beyond
  // the hypotenuse through its balls and edge cones).
  ASSERT_TRUE(gb::prism_interval(s, Vector3d(-5, 1, 0), Vector3d(2, 0, 0), t0, t1));
  EXPECT_NEAR(t0, 2.5, 1e-12);
  EXPECT_NEAR(t1, 4, 1e-12);
  EXPECT_FALSE(gb::prism_interval(s, Vector3d(0, 0, 1.5), Vector3d(1, 1, 0), t0, t1));
  EXPECT_TRUE(gb::prism_meets_box(s, Vector3d(1, 1, 0.9), Vector3d(2, 2, 1.5)));
  EXPECT_FALSE(gb::prism_meets_box(s, Vector3d(1, 1, 1.1), Vector3d(2, 2, 1.5)));
  EXPECT_TRUE(gb::prism_meets_box(s, Vector3d(1.9, 1.9, -0.1), Vector3d(2.1, 2.1, 0.1)));
  EXPECT_FALSE(gb::prism_meets_box(s, Vector3d(2.05, 2.05, -0.1), Vector3d(2.2, 2.2, 0.1)));
  // A box around the whole prism, and one inside it.
  EXPECT_TRUE(gb::prism_meets_box(s, Vector3d(-9, -9, -9), Vector3d(9, 9, 9)));
  EXPECT_TRUE(gb::prism_meets_box(s, Vector3d(1, 1, -0.1), Vector3d(1.2, 1.2, 0.1)));
}

// A slab too steep for a plane to touch all three balls has no prism: nothing meets it.
TEST(Slab, NoPrismWithoutTangentTriangles) {
  const gb::Slab s =
      slab_of({Vector3d(0, 0, 0), 3}, {Vector3d(1, 0, 0), 0.1}, {Vector3d(0, 1, 0), 0.1});
  ASSERT_FALSE(s.has_tangent_triangles);
  double t0, t1;
  EXPECT_FALSE(gb::prism_interval(s, Vector3d(-5, 0.1, 0), Vector3d(1, 0, 0), t0, t1));
  EXPECT_EQ(gb::prism_depth(s, Vector3d(0.1, 0.1, 0)), -INFINITY);
  EXPECT_FALSE(gb::prism_meets_box(s, Vector3d(-9, -9, -9), Vector3d(9, 9, 9)));
}

TEST(Slab, UnequalRadiiAgainstTheOracle) {
  const gb::Slab s =
      slab_of({Vector3d(0, 0, 0), 1}, {Vector3d(5, 0.5, 0.3), 0.5}, {Vector3d(1, 4, -0.5), 0.25});
  ASSERT_TRUE(s.has_tangent_triangles);
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> x(-2, 7), y(-2, 6), z(-2.5, 2.5);
  int outside = 0, inside = 0;
  for (int k = 0; k < 300; ++k) {
    const Vector3d p(x(gen), y(gen), z(gen));
    const double d = gb::slab_distance(s, p), oracle = fine_oracle_distance(s, p);
    ASSERT_TRUE(std::isfinite(d));
    EXPECT_NEAR(d, oracle, 1e-6 * std::max(1.0, std::abs(oracle))) << p.transpose();
    if (d > 0) {
      ++outside;
      const Vector3d q = gb::closest_solid_point(s, p);
      EXPECT_NEAR((q - p).norm(), d, 1e-9);
      EXPECT_NEAR(gb::slab_distance(s, q), 0, 1e-9);
      EXPECT_EQ(gb::closest_boundary_point(s, p), q);
      EXPECT_TRUE(gb::contains_deeper_than(s, p, -1.01 * d));
      EXPECT_FALSE(gb::contains_deeper_than(s, p, -0.99 * d));
      EXPECT_FALSE(gb::contains_deeper_than(s, p, 0));
    } else {
      ++inside;
      // The nearest boundary point: on the boundary, no nearer than the deepest ball's surface,
      // and no farther than the boundary along any of 200 directions.
      const Vector3d q = gb::closest_boundary_point(s, p);
      const double depth = (q - p).norm();
      EXPECT_NEAR(gb::slab_distance(s, q), 0, 1e-9) << p.transpose();
      EXPECT_GE(depth, -d - 1e-9);
      EXPECT_EQ(gb::closest_solid_point(s, p), p);
      if (depth > 1e-6) {
        EXPECT_TRUE(gb::contains_deeper_than(s, p, 0.99 * depth));
        EXPECT_FALSE(gb::contains_deeper_than(s, p, 1.01 * depth));
      }
      double t0, t1;
      std::uniform_real_distribution<double> u(-1, 1);
      for (int j = 0; j < 200; ++j) {
        const Vector3d dir = Vector3d(u(gen), u(gen), u(gen)).normalized();
        ASSERT_TRUE(gb::line_interval(s, p, dir, t0, t1));
        EXPECT_LE((q - p).norm(), t1 + 1e-9);
      }
    }
    // Lines through p: the ends of the interval lie on the boundary.
    double t0, t1;
    const Vector3d dir = Vector3d(1, 2, 3).normalized();
    if (gb::line_interval(s, p, dir, t0, t1)) {
      EXPECT_NEAR(gb::slab_distance(s, p + t0 * dir), 0, 1e-9);
      EXPECT_NEAR(gb::slab_distance(s, p + t1 * dir), 0, 1e-9);
    } else {
      EXPECT_GT(gb::slab_distance(s, p + ((s.c[0] - p).dot(dir)) * dir), -1e-12);
    }
  }
  EXPECT_GT(outside, 50);
  EXPECT_GT(inside, 10);
}

TEST(Slab, DegenerateCasesGiveNumbers) {
  // A pointed slab: one atom of radius 0.
  const gb::Slab pointed =
      slab_of({Vector3d(0, 0, 0), 1}, {Vector3d(3, 0, 0), 0}, {Vector3d(0, 3, 0), 0.5});
  EXPECT_TRUE(pointed.has_tangent_triangles);
  EXPECT_NEAR(gb::slab_distance(pointed, Vector3d(3, 0, 0)), 0, 1e-12);
  EXPECT_NEAR(gb::slab_distance(pointed, Vector3d(4, 0, 0)), 1, 1e-12);
  // One ball holds another: that edge is the larger ball.
  const gb::Slab held =
      slab_of({Vector3d(0, 0, 0), 2}, {Vector3d(0.5, 0, 0), 0.5}, {Vector3d(0, 5, 0), 0.5});
  EXPECT_TRUE(held.edge_is_ball[0]);
  EXPECT_EQ(held.edge_ball[0], 0);
  // Radii too steep for a plane touching all three: no tangent triangles, the edges only.
  const gb::Slab steep =
      slab_of({Vector3d(0, 0, 0), 2}, {Vector3d(2.1, 0, 0), 0.1}, {Vector3d(0, 2.1, 0), 0.1});
  EXPECT_FALSE(steep.has_tangent_triangles);
  EXPECT_EQ(gb::tangent_area(steep), 0);
  EXPECT_EQ(gb::migration_vector(steep, Vector3d(0.5, 0.5, 3)), Vector3d::Zero());
  for (const gb::Slab* s : {&pointed, &held, &steep})
    for (const Vector3d& p :
         {Vector3d(0, 0, 0), Vector3d(1, 1, 0), Vector3d(0.5, 0.5, 4), s->c[1], s->c[2]}) {
      const double d = gb::slab_distance(*s, p);
      EXPECT_TRUE(std::isfinite(d));
      const double oracle = fine_oracle_distance(*s, p);
      EXPECT_NEAR(d, oracle, 1e-6 * std::max(1.0, std::abs(oracle))) << p.transpose();
      EXPECT_TRUE(gb::migration_vector(*s, p).allFinite());
      double t0 = 0, t1 = 0;
      if (gb::line_interval(*s, p, Vector3d(0, 0, 1), t0, t1)) {
        EXPECT_TRUE(std::isfinite(t0) && std::isfinite(t1));
        EXPECT_NEAR(gb::slab_distance(*s, p + Vector3d(0, 0, t1)), 0, 1e-9);
      }
      EXPECT_TRUE(gb::closest_boundary_point(*s, p).allFinite());
      EXPECT_TRUE(gb::closest_solid_point(*s, p).allFinite());
    }
  EXPECT_TRUE(gb::collinear_centres({Vector3d(0, 0, 0), 1}, {Vector3d(1, 1, 1), 1},
                                    {Vector3d(3, 3, 3), 1}));
  EXPECT_FALSE(gb::collinear_centres({Vector3d(0, 0, 0), 1}, {Vector3d(1, 0, 0), 1},
                                     {Vector3d(0, 1, 0), 1}));
}

TEST(Slab, MeetingTestsNeverMissAMeeting) {
  const gb::Slab s =
      slab_of({Vector3d(0, 0, 0), 0.5}, {Vector3d(5, 0.5, 0.3), 0.25}, {Vector3d(1, 4, -0.5), 0.1});
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> x(-1.5, 6), y(-1.5, 5), z(-1.5, 1.5), side(0.05, 1);
  int met = 0, missed = 0;
  for (int k = 0; k < 400; ++k) {
    const Vector3d lo(x(gen), y(gen), z(gen));
    const Vector3d hi = lo + Vector3d::Constant(side(gen));
    const double oracle = grid_minimum(
        s, 200, [&](const Vector3d& c, double r) { return gb::box_distance(lo, hi, c) - r; });
    const bool meets = gb::slab_meets_box(s, lo, hi);
    if (oracle <= 0) {
      EXPECT_TRUE(meets) << lo.transpose();
    }
    // A "meets" is never wrong by more than the grid's error.
    if (meets) {
      EXPECT_LE(oracle, 0.05) << lo.transpose();
    }
    (meets ? met : missed) += 1;
  }
  EXPECT_GT(met, 30);
  EXPECT_GT(missed, 30);
  // Balls, cones and slabs: met exactly when the oracle says so (beyond its error).
  for (int k = 0; k < 200; ++k) {
    const mg::MedialAtom b{Vector3d(x(gen), y(gen), z(gen)), side(gen)};
    const double oracle = oracle_distance(s, b.centre) - b.radius;
    if (std::abs(oracle) > 0.02) {
      EXPECT_EQ(gb::slab_meets_ball(s, b), oracle < 0);
    }
    const mg::MedialAtom e{Vector3d(x(gen), y(gen), z(gen)), 0.5 * side(gen)};
    if ((e.centre - b.centre).norm() <= std::abs(e.radius - b.radius)) continue;
    const gb::Cone cone = gb::make_cone(b, e, 3, 4);
    const double cone_oracle = grid_minimum(
        s, 120, [&](const Vector3d& c, double r) { return gb::hull_distance(cone, c) - r; });
    if (std::abs(cone_oracle) > 0.05) {
      EXPECT_EQ(gb::slab_meets_cone(s, cone), cone_oracle < 0);
    }
    const gb::Slab other = slab_of(b, e, {Vector3d(x(gen), y(gen), z(gen)), 0.2});
    const double slab_oracle = grid_minimum(
        other, 120, [&](const Vector3d& c, double r) { return gb::slab_distance(s, c) - r; });
    if (std::abs(slab_oracle) > 0.05) {
      EXPECT_EQ(gb::slabs_meet(other, s), slab_oracle < 0);
    }
  }
}

/// Whether p lies in the prism between the tangent triangles (its five planes, up to tol).
bool in_prism(const gb::Slab& s, const Eigen::Vector3d& p, double tol) {
  if (!s.has_tangent_triangles) return false;
  for (int side = 0; side < 2; ++side)
    if (s.tangent_normal[side].dot(p - s.tangent[side][0]) > tol) return false;
  for (int e = 0; e < 3; ++e) {
    const Eigen::Vector3d a = s.tangent[0][e], b = s.tangent[0][(e + 1) % 3],
                          c = s.tangent[0][(e + 2) % 3];
    Eigen::Vector3d m = (b - a).cross(s.normal).normalized();
    if (m.dot(c - a) > 0) m = -m;
    if (m.dot(p - a) > tol) return false;
  }
  return true;
}

// The slab is the union of its balls, edge hulls and prism (by its mirror symmetry in the medial
// plane, each chord normal to it lies in the piece holding its ends), which line_interval relies
// on: points of interpolated balls c(l) + rho n, rho <= r(l), of random slabs, steep ones
// included, each lie in one of the pieces.
TEST(Slab, PiecesCoverTheSolid) {
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> x(-3, 3), rad(0, 2), unit(0, 1);
  std::normal_distribution<double> normal;
  int tangent = 0;
  for (int k = 0; k < 200; ++k) {
    const gb::Slab s = slab_of({Vector3d(x(gen), x(gen), x(gen)), rad(gen)},
                               {Vector3d(x(gen), x(gen), x(gen)), rad(gen)},
                               {Vector3d(x(gen), x(gen), x(gen)), rad(gen)});
    tangent += s.has_tangent_triangles;
    for (int j = 0; j < 200; ++j) {
      double u = unit(gen), v = unit(gen);
      if (u + v > 1) {
        u = 1 - u;
        v = 1 - v;
      }
      const Vector3d n = Vector3d(normal(gen), normal(gen), normal(gen)).normalized();
      const Vector3d p = s.centre(u, v) + (s.radius(u, v) * std::cbrt(unit(gen))) * n;
      bool covered = in_prism(s, p, 1e-9);
      for (int i = 0; i < 3 && !covered; ++i) covered = (p - s.c[i]).norm() <= s.r[i] + 1e-9;
      for (int e = 0; e < 3 && !covered; ++e)
        covered = !s.edge_is_ball[e] && gb::hull_distance(s.edge[e], p) <= 1e-9;
      EXPECT_TRUE(covered) << "slab " << k << ", p = " << p.transpose();
    }
  }
  EXPECT_GT(tangent, 40);
}

// The prism's queries agree with its five planes on random slabs: the depth's sign with the
// planes, a line's interval ends on the boundary with its middle inside, a box holding a point
// of the prism always meets it, and one whose distance from the prism exceeds its half-diagonal
// never does.
TEST(Slab, PrismQueriesAgreeWithItsPlanes) {
  std::mt19937 gen(17);
  std::uniform_real_distribution<double> x(-3, 3), rad(0.05, 1.5), unit(0, 1), side(0.01, 1.5);
  std::normal_distribution<double> normal;
  int prisms = 0, lines = 0, boxes_met = 0, boxes_missed = 0;
  for (int k = 0; k < 100; ++k) {
    const gb::Slab s = slab_of({Vector3d(x(gen), x(gen), x(gen)), rad(gen)},
                               {Vector3d(x(gen), x(gen), x(gen)), rad(gen)},
                               {Vector3d(x(gen), x(gen), x(gen)), rad(gen)});
    if (!s.has_tangent_triangles) continue;
    ++prisms;
    for (int j = 0; j < 50; ++j) {
      const Vector3d p(x(gen), x(gen), x(gen));
      const double depth = gb::prism_depth(s, p);
      if (std::abs(depth) > 1e-9) {
        EXPECT_EQ(depth > 0, in_prism(s, p, 0)) << p.transpose();
      }
      if (depth > 0) {
        const Vector3d q = gb::prism_boundary_point(s, p);
        EXPECT_NEAR((q - p).norm(), depth, 1e-12);
        EXPECT_NEAR(gb::prism_depth(s, q), 0, 1e-12);
      }
      const Vector3d d = Vector3d(normal(gen), normal(gen), normal(gen));
      double t0, t1;
      if (gb::prism_interval(s, p, d, t0, t1)) {
        ++lines;
        EXPECT_LE(t0, t1);
        EXPECT_NEAR(gb::prism_depth(s, p + t0 * d), 0, 1e-9);
        EXPECT_NEAR(gb::prism_depth(s, p + t1 * d), 0, 1e-9);
        EXPECT_GE(gb::prism_depth(s, p + 0.5 * (t0 + t1) * d), -1e-9);
      }
      const Vector3d half = Vector3d::Constant(side(gen) / 2);
      const bool meets = gb::prism_meets_box(s, p - half, p + half);
      if (depth >= 0) {
        EXPECT_TRUE(meets) << p.transpose();
      }
      if (-depth > half.norm()) {  // the box lies beyond one face plane
        EXPECT_FALSE(meets) << p.transpose();
      }
      // The tangent triangles' corners and centroids, and the prism's centre: if one lies in
      // the box, the box meets the prism.
      std::vector<Vector3d> points = {(s.tangent[0][0] + s.tangent[1][1] + s.tangent[0][2]) / 3};
      for (const auto& t : s.tangent) {
        points.insert(points.end(), t.begin(), t.end());
        points.push_back((t[0] + t[1] + t[2]) / 3);
      }
      for (const Vector3d& q : points)
        if (((q - p).cwiseAbs() - half).maxCoeff() <= 0) {
          EXPECT_TRUE(meets) << p.transpose();
        }
      (meets ? boxes_met : boxes_missed) += 1;
    }
  }
  EXPECT_GT(prisms, 30);
  EXPECT_GT(lines, 100);
  EXPECT_GT(boxes_met, 100);
  EXPECT_GT(boxes_missed, 100);
}

}  // namespace
