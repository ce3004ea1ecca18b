#include "core/shapes.h"
#include "core/errors.h"
#include "core/mesh_topology.h"

#include <gtest/gtest.h>

#include "test_util.h"

#include <cmath>

namespace {

using mg_test::signed_volume;

constexpr double kPi = 3.14159265358979323846;

TEST(Shapes, GeodesicSphereIsClosedOutwardAndOnTheSphere) {
  const auto s = mg::make_geodesic_sphere(18, 2.0);
  const auto t = mg::mesh_topology(s);
  EXPECT_TRUE(t.closed && t.oriented);
  EXPECT_EQ(t.genus, 0);
  EXPECT_EQ(s.points.size(), 10u * 18 * 18 + 2);
  for (const auto& p : s.points) EXPECT_NEAR(p.norm(), 2.0, 1e-12);
  EXPECT_GT(signed_volume(s), 0.99 * 4.0 / 3.0 * kPi * 8.0);
}

TEST(Shapes, TorusIsClosedGenusOneOutwardAndExact) {
  const auto s = mg::make_torus(60, 20, 1.0, 0.3);
  const auto t = mg::mesh_topology(s);
  EXPECT_TRUE(t.closed && t.oriented);
  EXPECT_EQ(t.genus, 1);
  EXPECT_EQ(s.points.size(), 1200u);
  EXPECT_EQ(s.faces.size(), 2400u);
  for (const auto& p : s.points) {
    const double ring = std::hypot(p.x(), p.y()) - 1.0;
    EXPECT_NEAR(std::hypot(ring, p.z()), 0.3, 1e-12);
  }
  EXPECT_GT(signed_volume(s), 0.95 * 2 * kPi * kPi * 1.0 * 0.09);
}

TEST(Shapes, BumpyTorusIsClosedGenusOneWithBumps) {
  const auto s = mg::make_bumpy_torus(126, 126, 1.0, 0.35, 0.1, 12, 6);
  const auto t = mg::mesh_topology(s);
  EXPECT_TRUE(t.closed && t.oriented);
  EXPECT_EQ(t.genus, 1);
  EXPECT_EQ(t.vertices, 15876u);
  EXPECT_EQ(t.faces, 31752u);
  double lo = 1e9, hi = 0;
  for (const auto& p : s.points) {
    const double r = std::hypot(std::hypot(p.x(), p.y()) - 1.0, p.z());
    lo = std::min(lo, r);
    hi = std::max(hi, r);
  }
  EXPECT_NEAR(lo, 0.35 * 0.9, 0.35 * 0.01);
  EXPECT_NEAR(hi, 0.35 * 1.1, 0.35 * 0.01);
  EXPECT_GT(signed_volume(s), 0);
}

TEST(Shapes, BoxIsClosedAndOutward) {
  const auto s = mg::make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 2, 3));
  const auto t = mg::mesh_topology(s);
  EXPECT_TRUE(t.closed && t.oriented);
  EXPECT_NEAR(signed_volume(s), 6.0, 1e-12);
}

TEST(Shapes, PreconditionsAreChecked) {
  EXPECT_THROW(mg::make_geodesic_sphere(0), mg::InvalidInput);
  EXPECT_THROW(mg::make_geodesic_sphere(2, -1.0), mg::InvalidInput);
  EXPECT_THROW(mg::make_torus(2, 20, 1, 0.3), mg::InvalidInput);
  EXPECT_THROW(mg::make_torus(60, 20, 0.3, 1), mg::InvalidInput);
  EXPECT_THROW(mg::make_bumpy_torus(60, 20, 1, 0.3, 1.5, 3, 3), mg::InvalidInput);
  EXPECT_THROW(mg::make_box(Eigen::Vector3d::Ones(), Eigen::Vector3d::Zero()), mg::InvalidInput);
}

}  // namespace
