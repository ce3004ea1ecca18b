// The primitives of G (primitives.h) on shapes solvable by hand, and their box tests against
// brute force.
#include "garbing/primitives.h"
#include "garbing/target_shape.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "atom_sets.h"

namespace {

namespace gb = mg::garbing;
using Eigen::Vector3d;

// The cone of the example: r1 = 1 at the origin, r2 = 0.5 at (2, 0, 0), L = 2.
const mg::MedialAtom kA{Vector3d(0, 0, 0), 1.0};
const mg::MedialAtom kB{Vector3d(2, 0, 0), 0.5};

TEST(Crease, IsTheCircleWhereTheTwoSpheresMeet) {
  // |x|^2 = 1 and |x - (1.5, 0, 0)|^2 = 0.64: x = (2.25 + 1 - 0.64) / 3 = 0.87.
  const mg::MedialAtom a{Vector3d(0, 0, 0), 1.0}, b{Vector3d(1.5, 0, 0), 0.8};
  const gb::Crease c = gb::crease(1.5, 1, 0.8);
  EXPECT_NEAR(c.along, 0.87, 1e-15);
  EXPECT_NEAR(c.radius, std::sqrt(1 - 0.87 * 0.87), 1e-15);
  const Vector3d on(c.along, 0, c.radius);
  EXPECT_NEAR(on.norm(), 1.0, 1e-15);
  EXPECT_NEAR((on - b.centre).norm(), 0.8, 1e-15);
  const gb::Cone cone = gb::make_cone(a, b, 0, 1);
  EXPECT_EQ(cone.crease.along, c.along);
  EXPECT_EQ(cone.crease.radius, c.radius);
  // The crease lies inside the cone's solid, on the corner of its fill triangle.
  EXPECT_LT(gb::hull_distance(cone, on), 0);
  EXPECT_TRUE(gb::contains_deeper_than(cone, on, 0));
  EXPECT_LE(cone.fill_lo[0], c.along);
  EXPECT_GE(cone.fill_hi[0], c.along);
  EXPECT_GE(cone.fill_hi[1], c.radius);
}

TEST(MigrationVector, SphereIsRadiusOverDistanceAwayFromTheCentre) {
  const mg::MedialAtom s{Vector3d(0, 0, 0), 2.0};
  EXPECT_TRUE(gb::migration_vector(s, Vector3d(1, 0, 0)).isApprox(Vector3d(2, 0, 0), 1e-15));
  EXPECT_TRUE(gb::migration_vector(s, Vector3d(0, 0, 4)).isApprox(Vector3d(0, 0, 0.5), 1e-15));
  EXPECT_EQ(gb::migration_vector(s, Vector3d(0, 0, 0)), Vector3d::Zero());  // on the centre
}

TEST(MigrationVector, ConeMatchesHandComputedValues) {
  const gb::Cone cone = gb::make_cone(kA, kB, 0, 1);
  EXPECT_NEAR(cone.sin_phi, 0.25, 1e-15);
  // v = (1, 1, 0): foot t* = 1 - tan(phi) = 0.7418011102528389, r(t*) = 1 - t* / 4.
  EXPECT_TRUE(gb::migration_vector(cone, Vector3d(1, 1, 0))
                  .isApprox(Vector3d(0.19717109, 0.76364036, 0), 1e-7));
  EXPECT_TRUE(gb::migration_vector(cone, Vector3d(0.5, 0, -0.8))
                  .isApprox(Vector3d(0.28037972, 0, -1.08590599), 1e-7));
  // Feet outside [0, L], and a point on the axis: zero.
  EXPECT_EQ(gb::migration_vector(cone, Vector3d(-1, 0.5, 0)), Vector3d::Zero());
  EXPECT_EQ(gb::migration_vector(cone, Vector3d(3, 0.1, 0)), Vector3d::Zero());
  EXPECT_EQ(gb::migration_vector(cone, Vector3d(1, 0, 0)), Vector3d::Zero());
}

TEST(MigrationVector, ConeVectorPointsAtTheTangentBall) {
  // |m_g| = r / |v - p|: the point p + r (v - p) / |v - p| lies on the cone's lateral surface.
  const gb::Cone cone = gb::make_cone(kA, kB, 0, 1);
  const gb::TargetShape shape(mg_test::atoms({kA, kB}), {{0, 1}});
  for (const Vector3d& v : {Vector3d(1, 1, 0), Vector3d(0.7, -0.3, 2), Vector3d(1.5, 0.2, 0.1)}) {
    const Vector3d m = gb::migration_vector(cone, v);
    ASSERT_GT(m.norm(), 0);
    const double x = v.dot(cone.u), rho = (v - x * cone.u).norm();
    const Vector3d p = (x - rho * cone.sin_phi / cone.cos_phi) * cone.u;
    const Vector3d on = p + (m / m.norm()) * (m.norm() * (v - p).norm());
    EXPECT_LT(shape.distance(on), 1e-12);
  }
}

TEST(HullDistance, MatchesHandComputedValues) {
  const gb::Cone cone = gb::make_cone(kA, kB, 0, 1);
  // Beside the first centre, 2 from the axis: the nearest point is on the first ball's cap.
  EXPECT_NEAR(gb::hull_distance(cone, Vector3d(0, 2, 0)), 1.0, 1e-15);
  // (1, 2): over the lateral surface, (y - R(x)) cos(phi) with R(x) = (1 - x / 4) / cos(phi).
  const double cos_phi = std::sqrt(1 - 0.0625);
  EXPECT_NEAR(gb::hull_distance(cone, Vector3d(1, 0, 2)), (2 - 0.75 / cos_phi) * cos_phi, 1e-14);
  // Beyond the second centre on the axis: the second ball.
  EXPECT_NEAR(gb::hull_distance(cone, Vector3d(3, 0, 0)), 0.5, 1e-15);
  // Inside: minus the depth in the deepest ball B(c(t), r(t)); on the axis at x = 0.5 it is
  // the one centred there, t = 0.25, r = 1 - 0.25 / 2.
  EXPECT_NEAR(gb::hull_distance(cone, Vector3d(0.5, 0, 0)), -0.875, 1e-15);
}

TEST(LineInterval, MatchesTheBallAndConeByHand) {
  double t0, t1;
  ASSERT_TRUE(gb::line_interval(kA, Vector3d(-3, 0, 0), Vector3d(2, 0, 0), t0, t1));
  EXPECT_NEAR(t0, 1.0, 1e-15);  // enters at x = -1, in units of |d| = 2
  EXPECT_NEAR(t1, 2.0, 1e-15);
  EXPECT_FALSE(gb::line_interval(kA, Vector3d(0, 1.5, -3), Vector3d(0, 0, 1), t0, t1));
  // Across the cone at x = 1 along z: the lateral radius there is (1 - 1 / 4) / cos(phi).
  const gb::Cone cone = gb::make_cone(kA, kB, 0, 1);
  const double R = 0.75 / cone.cos_phi;
  ASSERT_TRUE(gb::line_interval(cone, Vector3d(1, 0, -5), Vector3d(0, 0, 1), t0, t1));
  EXPECT_NEAR(t0, 5 - R, 1e-12);
  EXPECT_NEAR(t1, 5 + R, 1e-12);
  // Along the axis: the frustum's slab only.
  ASSERT_TRUE(gb::line_interval(cone, Vector3d(-5, 0, 0), Vector3d(1, 0, 0), t0, t1));
  EXPECT_NEAR(t0, 5 + cone.t_lo, 1e-12);
  EXPECT_NEAR(t1, 5 + cone.t_hi, 1e-12);
}

TEST(ClosestPoints, AreOnTheFrustumAndNearestAmongItsSamples) {
  const gb::Cone cone = gb::make_cone(kA, kB, 0, 1);
  // Points of the frustum and of its lateral surface, in the profile (x, radius) then turned.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0, 1);
  auto frame = [&](double x, double rho, double angle) {
    const Vector3d e1 = cone.u.unitOrthogonal(), e2 = cone.u.cross(e1);
    return Vector3d(cone.c1 + x * cone.u + rho * (std::cos(angle) * e1 + std::sin(angle) * e2));
  };
  std::vector<Vector3d> solid, lateral;
  for (int i = 0; i < 20000; ++i) {
    const double s = unit(rng), angle = 2 * M_PI * unit(rng);
    const double x = cone.t_lo + s * (cone.t_hi - cone.t_lo);
    const double R = cone.rho_lo + s * (cone.rho_hi - cone.rho_lo);
    lateral.push_back(frame(x, R, angle));
    solid.push_back(frame(x, R * std::sqrt(unit(rng)), angle));
  }
  std::uniform_real_distribution<double> u(-2, 4);
  for (int i = 0; i < 100; ++i) {
    const Vector3d p(u(rng), u(rng) - 1, u(rng) - 1);
    const Vector3d q = gb::closest_solid_point(cone, p), l = gb::closest_lateral_point(cone, p);
    if (gb::contains_deeper_than(cone, p, 1e-12)) {
      EXPECT_EQ(q, p);
    }
    EXPECT_TRUE(gb::contains_deeper_than(cone, q, -1e-9)) << p.transpose();
    const double x = (l - cone.c1).dot(cone.u), rho = ((l - cone.c1) - x * cone.u).norm();
    EXPECT_NEAR(rho, (cone.r1 - x * cone.sin_phi) / cone.cos_phi, 1e-12);  // on the lateral surface
    for (std::size_t k = 0; k < solid.size(); k += 7) {
      EXPECT_LE((q - p).norm(), (solid[k] - p).norm() + 1e-12);
      EXPECT_LE((l - p).norm(), (lateral[k] - p).norm() + 1e-12);
    }
  }
}

/// Whether the cone's solid meets the box, by sampling its interpolated balls finely.
bool meets_box_by_sampling(const gb::Cone& k, const Vector3d& lo, const Vector3d& hi) {
  for (int s = 0; s <= 4000; ++s) {
    const double t = s / 4000.0;
    if (gb::box_distance(lo, hi, k.centre(t)) <= k.radius(t)) return true;
  }
  return false;
}

TEST(BoxTests, AgreeWithSamplingTheInterpolatedBalls) {
  const gb::Cone cone = gb::make_cone(kA, kB, 0, 1);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.6, 3.1), side(0.01, 0.4);
  int met = 0, fills = 0;
  for (int i = 0; i < 3000; ++i) {
    const Vector3d lo(u(rng), u(rng) - 0.7, u(rng) - 0.7);
    const double s = side(rng);
    const Vector3d hi = lo + Vector3d::Constant(s);
    const bool sampled = meets_box_by_sampling(cone, lo, hi);
    const bool exact = gb::hull_meets_box(cone, lo, hi);
    // The search errs only toward "meets", by at most 1e-9 of the parameter range; sampling at
    // 1/4000 can miss a tangency, so only disagreements with a clear margin count.
    if (exact != sampled) {
      const double margin = [&] {
        double best = INFINITY;
        for (int k = 0; k <= 4000; ++k) {
          const double t = k / 4000.0;
          best = std::min(best, gb::box_distance(lo, hi, cone.centre(t)) - cone.radius(t));
        }
        return best;
      }();
      EXPECT_LT(std::abs(margin), 1e-3) << lo.transpose() << " side " << s;
    }
    met += exact;
    const bool in_ball = gb::meets_box(kA, lo, hi) || gb::meets_box(kB, lo, hi);
    if (!in_ball) {
      EXPECT_EQ(gb::fill_meets_cube(cone, lo, s), exact) << lo.transpose() << " side " << s;
      if (exact) {
        ++fills;
        EXPECT_TRUE(gb::near_crease_fill(cone, lo, s));
      }
    }
  }
  EXPECT_GT(met, 200);
  EXPECT_GT(fills, 5);  // some boxes meet the crease fill alone
}

TEST(BoxTests, TheBoundingBoxesHoldTheirPrimitives) {
  const gb::Cone cone = gb::make_cone(kA, kB, 0, 1);
  const Eigen::AlignedBox3d frustum = gb::bounding_box(cone), ball = gb::bounding_box(kA);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.5, 3);
  for (int i = 0; i < 20000; ++i) {
    const Vector3d p(u(rng), u(rng) - 0.75, u(rng) - 0.75);
    if (gb::contains_deeper_than(cone, p, 0)) {
      EXPECT_TRUE(frustum.contains(p)) << p.transpose();
    }
    if (gb::contains_deeper_than(kA, p, 0)) {
      EXPECT_TRUE(ball.contains(p)) << p.transpose();
    }
  }
  EXPECT_NEAR(gb::lateral_area(cone),
              M_PI * (cone.rho_lo + cone.rho_hi) *
                  std::hypot(cone.t_hi - cone.t_lo, cone.rho_hi - cone.rho_lo),
              1e-15);
}

TEST(HullsMeet, AgreesWithTheDistanceBetweenSampledBalls) {
  const gb::Cone a = gb::make_cone(kA, kB, 0, 1);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-3, 5), r(0.1, 0.6);
  for (int i = 0; i < 400; ++i) {
    const mg::MedialAtom p{Vector3d(u(rng), u(rng) - 1, u(rng) - 1), r(rng)};
    const mg::MedialAtom q{p.centre + Vector3d(0.5 * r(rng), 0.3, -0.2), r(rng)};
    const gb::Cone b = gb::make_cone(p, q, 2, 3);
    double gap = INFINITY;
    for (int s = 0; s <= 400; ++s)
      gap = std::min(gap, gb::hull_distance(a, b.centre(s / 400.0)) - b.radius(s / 400.0));
    if (std::abs(gap) > 1e-3) {
      EXPECT_EQ(gb::hulls_meet(a, b), gap <= 0) << i;
    }
  }
}

TEST(StoredCone, RestoresTheConeBitForBit) {
  // What G keeps of a cone gives back make_cone's Cone exactly, for intersecting and disjoint
  // balls, and the shortcuts read from it (bounding ball, m_g) equal the restored cone's.
  std::mt19937 gen(5);
  std::uniform_real_distribution<double> u(-2, 2), radius(0.05, 1.5);
  int disjoint = 0;
  for (int k = 0; k < 2000; ++k) {
    const mg::MedialAtom a{Vector3d(u(gen), u(gen), u(gen)), radius(gen)};
    const mg::MedialAtom b{Vector3d(u(gen), u(gen), u(gen)), radius(gen)};
    if (!((b.centre - a.centre).norm() > std::abs(a.radius - b.radius))) continue;
    const gb::Cone cone = gb::make_cone(a, b, 3, 8);
    disjoint += cone.disjoint;
    const gb::StoredCone kept = gb::stored(cone);
    ASSERT_TRUE(mg_test::same_cone(gb::restored(kept), cone)) << "case " << k;
    Vector3d centre;
    double radius2;
    gb::bounding_ball(kept, centre, radius2);
    EXPECT_EQ(centre, cone.bound_centre);
    EXPECT_EQ(radius2, cone.bound_radius2);
    const Vector3d v(u(gen), u(gen), u(gen));
    EXPECT_EQ(gb::migration_vector(kept, v), gb::migration_vector(cone, v));
  }
  EXPECT_GT(disjoint, 100);  // both kinds were met
}

}  // namespace
