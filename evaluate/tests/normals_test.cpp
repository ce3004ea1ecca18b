// Normal deviation (normals.h).
#include "evaluate/normals.h"
#include "core/errors.h"
#include "core/shapes.h"
#include "evaluate/baselines.h"

#include <gtest/gtest.h>

#include <cmath>

namespace ev = mg::evaluate;

namespace {

ev::NormalOptions with_samples(std::size_t n, bool smooth = true) {
  ev::NormalOptions opt;
  opt.samples = n;
  opt.smooth_reference = smooth;
  return opt;
}

}  // namespace

TEST(Normals, AFineSphereAgainstItselfDeviatesUnderOneDegree) {
  const mg::PolygonSoup sphere = mg::make_geodesic_sphere(40);
  const ev::NormalDeviation smooth = ev::normal_deviation(sphere, sphere, with_samples(200000));
  EXPECT_LT(smooth.mean_deg, 1.0);
  EXPECT_LT(smooth.p95_deg, 1.0);
  EXPECT_GT(smooth.mean_deg, 0.0);  // facets against the smooth normal: not zero
  EXPECT_LE(smooth.mean_deg, smooth.p95_deg);
  EXPECT_LE(smooth.p95_deg, smooth.max_deg);
  EXPECT_EQ(smooth.samples, 200000u);
  EXPECT_EQ(smooth.skipped, 0u);

  const ev::NormalDeviation flat =
      ev::normal_deviation(sphere, sphere, with_samples(20000, /*smooth=*/false));
  EXPECT_LT(flat.p95_deg, 1e-6);
}

TEST(Normals, AUnionOfBallsIsBumpierThanTheSurfaceItApproximates) {
  // 24 balls of radius 0.3 around the unit circle: their union approximates the torus R = 1,
  // r = 0.3 with a bump between each pair of balls.
  mg::MedialSurface ring;
  for (int k = 0; k < 24; ++k) {
    const double t = 2 * M_PI * k / 24;
    ring.atoms.push_back({Eigen::Vector3d(std::cos(t), std::sin(t), 0), 0.3});
  }
  const mg::PolygonSoup balls = ev::union_of_balls_mesh(ring, /*subdivisions=*/1);
  const mg::PolygonSoup torus = mg::make_torus(480, 160, 1.0, 0.3);
  const ev::NormalDeviation bumps = ev::normal_deviation(balls, torus, with_samples(100000));
  const ev::NormalDeviation fine = ev::normal_deviation(torus, torus, with_samples(100000));
  EXPECT_LT(fine.mean_deg, 1.0);
  EXPECT_GT(bumps.mean_deg, 5.0);
  EXPECT_GT(bumps.p95_deg, 10.0);
}

TEST(Normals, AnInvertedMeshIsAtHalfATurn) {
  mg::PolygonSoup sphere = mg::make_geodesic_sphere(8);
  mg::PolygonSoup inverted = sphere;
  for (auto& f : inverted.faces) std::reverse(f.begin(), f.end());
  const ev::NormalDeviation r =
      ev::normal_deviation(inverted, sphere, with_samples(10000, /*smooth=*/false));
  EXPECT_GT(r.mean_deg, 179.999);
}

TEST(Normals, ZeroAreaInputIsRefused) {
  mg::PolygonSoup flat;
  flat.points = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
  flat.faces = {{0, 1, 2}};
  const mg::PolygonSoup sphere = mg::make_geodesic_sphere(4);
  EXPECT_THROW(ev::normal_deviation(flat, sphere), mg::InvalidInput);
  EXPECT_THROW(ev::normal_deviation(sphere, flat), mg::InvalidInput);
}
