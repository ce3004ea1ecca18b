// Baselines on one atom (skin surface, union of balls, OpenVDB), voxel searches, timing.
#include "evaluate/baselines.h"
#include "core/errors.h"
#include "core/shapes.h"
#include "evaluate/mesh_checks.h"
#include "evaluate/timing.h"
#include "evaluate/vdb_mesh.h"

#include <gtest/gtest.h>

#include "test_util.h"

#include <tbb/global_control.h>
#include <chrono>
#include <thread>

#include <cmath>

namespace ev = mg::evaluate;

namespace {

const Eigen::Vector3d kCentre(0.5, -0.25, 0.125);
constexpr double kRadius = 0.7;
/// CGAL's skin mesher bisects a segment across the surface until its squared length is
/// <= 1e-8 (Skin_surface_base_3::intersect) and takes the midpoint: vertices lie within 5e-5
/// model units of the surface (an absolute tolerance).
constexpr double kCgalSkinTolerance = 5e-5;

mg::MedialSurface one_atom() {
  mg::MedialSurface s;
  s.atoms.push_back({kCentre, kRadius});
  return s;
}

using mg_test::signed_volume;

/// Largest | |p - centre| - r | over the vertices.
double radial_error(const mg::PolygonSoup& soup) {
  double e = 0;
  for (const auto& p : soup.points) e = std::max(e, std::abs((p - kCentre).norm() - kRadius));
  return e;
}

void expect_closed_sphere(const mg::PolygonSoup& soup) {
  const ev::MeshCheck c = ev::check_mesh(soup);
  EXPECT_TRUE(c.topology.closed);
  EXPECT_TRUE(c.topology.manifold);
  EXPECT_TRUE(c.topology.oriented);
  EXPECT_EQ(c.topology.components, 1u);
  EXPECT_EQ(c.topology.genus, 0);
  EXPECT_EQ(c.intersecting_pairs, 0u);
  EXPECT_EQ(c.degenerate_triangles, 0u);
  EXPECT_GT(signed_volume(soup), 0.0);  // faces turned outward
}

}  // namespace

TEST(Baselines, SkinSurfaceOfOneAtomIsItsSphere) {
  for (int subdivisions : {0, 1}) {
    ev::SkinOptions opt;
    opt.subdivisions = subdivisions;
    const mg::PolygonSoup skin = ev::skin_surface_mesh(one_atom(), opt);
    expect_closed_sphere(skin);
    EXPECT_LT(radial_error(skin), kCgalSkinTolerance) << subdivisions;
  }
}

TEST(Baselines, UnionOfBallsOfOneAtomIsItsSphere) {
  const mg::PolygonSoup balls = ev::union_of_balls_mesh(one_atom(), 1);
  expect_closed_sphere(balls);
  EXPECT_LT(radial_error(balls), kCgalSkinTolerance);
}

TEST(Baselines, SkinRefusesShrinkOneAndAbove) {
  ev::SkinOptions opt;
  for (double shrink : {1.0, 1.5}) {
    opt.shrink = shrink;
    try {
      ev::skin_surface_mesh(one_atom(), opt);
      ADD_FAILURE() << "shrink " << shrink << " accepted";
    } catch (const mg::InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find("evaluate union"), std::string::npos) << e.what();
    }
  }
  for (double shrink : {0.0, -0.5, std::nan("")}) {
    opt.shrink = shrink;
    EXPECT_THROW(ev::skin_surface_mesh(one_atom(), opt), mg::InvalidInput);
  }
  opt.shrink = 0.5;
  opt.subdivisions = -1;
  EXPECT_THROW(ev::skin_surface_mesh(one_atom(), opt), mg::InvalidInput);
  EXPECT_THROW(ev::skin_surface_mesh(mg::MedialSurface{}, {}), mg::InvalidInput);
  EXPECT_THROW(ev::union_of_balls_mesh(mg::MedialSurface{}), mg::InvalidInput);
}

TEST(Baselines, OpenVdbOfOneAtomIsItsSphereWithinAVoxel) {
  const ev::VdbMesh m = ev::vdb_mesh(one_atom());
  const double diagonal = 2 * kRadius * std::sqrt(3.0);
  EXPECT_NEAR(ev::spheres_bbox_diagonal(one_atom()), diagonal, 1e-12);
  EXPECT_NEAR(m.voxel, diagonal / 400, 1e-15);
  EXPECT_EQ(m.dropped_spheres, 0u);  // 115 voxels: above OpenVDB's own 100-voxel cap
  expect_closed_sphere(m.mesh);
  EXPECT_LT(radial_error(m.mesh), m.voxel);
}

TEST(Baselines, OpenVdbCountsTheSpheresItDrops) {
  mg::MedialSurface s = one_atom();
  s.atoms.push_back({Eigen::Vector3d(3, 0, 0), 0.001});  // far under 1.5 voxels
  s.atoms.push_back({Eigen::Vector3d(0, 3, 0), 0.002});
  const ev::VdbMesh m = ev::vdb_mesh(s);
  EXPECT_EQ(m.dropped_spheres, 2u);
  for (const auto& p : m.mesh.points) EXPECT_LT((p - kCentre).norm(), kRadius + m.voxel);

  ev::VdbOptions huge;
  huge.voxel = 10.0;  // every sphere under 1.5 voxels
  EXPECT_THROW(ev::vdb_mesh(one_atom(), huge), mg::InvalidInput);
  huge.voxel = -1;
  EXPECT_THROW(ev::vdb_mesh(one_atom(), huge), mg::InvalidInput);
}

TEST(Baselines, OpenVdbGivesTheSameMeshAtOneAndTwoThreads) {
  mg::MedialSurface s;
  for (int k = 0; k < 12; ++k) {
    const double t = 2 * M_PI * k / 12;
    s.atoms.push_back({Eigen::Vector3d(std::cos(t), std::sin(t), 0), 0.3 + 0.02 * (k % 3)});
  }
  ev::VdbOptions opt;
  opt.voxel = 0.02;
  ev::VdbMesh one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = ev::vdb_mesh(s, opt);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = ev::vdb_mesh(s, opt);
  }
  ASSERT_EQ(one.mesh.points.size(), two.mesh.points.size());
  EXPECT_EQ(one.mesh.points, two.mesh.points);
  EXPECT_EQ(one.mesh.faces, two.mesh.faces);
  const ev::MeshCheck c = ev::check_mesh(one.mesh);
  EXPECT_TRUE(c.topology.closed);
  EXPECT_EQ(c.topology.genus, 1);
}

TEST(Baselines, VoxelSearchHitsAVertexCount) {
  const ev::VdbMatch m = ev::vdb_match_vertices(one_atom(), 20000);
  EXPECT_LE(m.probes.size(), 5u);
  EXPECT_NEAR(static_cast<double>(m.best.mesh.points.size()), 20000.0, 0.02 * 20000);
  EXPECT_EQ(m.value, static_cast<double>(m.best.mesh.points.size()));
  EXPECT_FALSE(m.clamped);
  EXPECT_THROW(ev::vdb_match_vertices(one_atom(), 0), mg::InvalidInput);
  EXPECT_THROW(ev::vdb_match_vertices(one_atom(), 100, 0), mg::InvalidInput);
}

TEST(Baselines, VoxelSearchHitsAHausdorffDistance) {
  // The reference: the atom's sphere, finely tessellated.
  mg::PolygonSoup reference = mg::make_geodesic_sphere(40, kRadius);
  for (auto& p : reference.points) p += kCentre;
  ev::MeshDistanceOptions dist;
  dist.samples = 100000;
  dist.vertices_and_edges = false;
  const ev::VdbMatch m = ev::vdb_match_hausdorff(one_atom(), 0.5, reference, dist, "reference");
  EXPECT_LE(m.probes.size(), 5u);
  EXPECT_NEAR(m.value, 0.5, 0.05);
  EXPECT_THROW(ev::vdb_match_hausdorff(one_atom(), -1, reference, dist, "r"), mg::InvalidInput);
}

TEST(Timing, ReportsMinMedianMax) {
  int calls = 0;
  const ev::StageTiming t = ev::time_stage(3, [&] {
    ++calls;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  });
  EXPECT_EQ(calls, 3);
  ASSERT_EQ(t.seconds.size(), 3u);
  EXPECT_LE(t.min, t.median);
  EXPECT_LE(t.median, t.max);
  EXPECT_GE(t.min, 0.002);  // each run slept 2 ms
  EXPECT_THROW(ev::time_stage(0, [] {}), mg::InvalidInput);
  EXPECT_THROW(ev::time_stage(2, [] { throw mg::InvalidInput("x"); }), mg::InvalidInput);
}
