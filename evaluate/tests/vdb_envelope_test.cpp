// The OpenVDB baseline of a medial mesh's envelope: G's signed distance sampled, then meshed.
#include "core/errors.h"
#include "evaluate/mesh_checks.h"
#include "evaluate/vdb_mesh.h"
#include "garbing/frame.h"
#include "garbing/target_shape.h"

#include <gtest/gtest.h>

#include "test_util.h"

#include <tbb/global_control.h>

namespace ev = mg::evaluate;
namespace gb = mg::garbing;

namespace {

/// Two disjoint balls joined by an edge: the envelope is one capsule, the balls two spheres.
mg::MedialSurface capsule() {
  mg::MedialSurface s;
  s.atoms.push_back({Eigen::Vector3d(0, 0, 0), 0.5});
  s.atoms.push_back({Eigen::Vector3d(2, 0.1, -0.05), 0.35});
  s.edges.push_back({0, 1});
  return s;
}

/// One face: a slab over a triangle of three disjoint balls.
mg::MedialSurface one_face() {
  mg::MedialSurface s;
  s.atoms.push_back({Eigen::Vector3d(0, 0, 0), 0.3});
  s.atoms.push_back({Eigen::Vector3d(2, 0, 0.1), 0.2});
  s.atoms.push_back({Eigen::Vector3d(0.8, 1.6, 0), 0.25});
  s.faces.push_back({0, 1, 2});
  return s;
}

ev::VdbOptions with_voxel(double voxel) {
  ev::VdbOptions opt;
  opt.voxel = voxel;
  return opt;
}

void expect_one_closed_sphere(const mg::PolygonSoup& soup) {
  const ev::MeshCheck c = ev::check_mesh(soup);
  EXPECT_TRUE(c.topology.closed);
  EXPECT_TRUE(c.topology.manifold);
  EXPECT_TRUE(c.topology.oriented);
  EXPECT_EQ(c.topology.components, 1u);
  EXPECT_EQ(c.topology.genus, 0);
  EXPECT_EQ(c.intersecting_pairs, 0u);
  EXPECT_GT(mg_test::signed_volume(soup), 0.0);  // faces turned outward
}

/// Largest distance from a vertex to G (exact outside G, an upper bound inside).
double max_distance_to_g(const mg::PolygonSoup& soup, const mg::MedialSurface& atoms) {
  const gb::TargetShape g = gb::make_target_shape(atoms, gb::PrimitiveSet::envelope, {});
  double e = 0;
  for (const auto& p : soup.points) e = std::max(e, g.distance(p));
  return e;
}

}  // namespace

TEST(VdbEnvelope, CapsuleIsOneClosedComponentWithinAVoxelOfG) {
  const ev::VdbMesh m = ev::vdb_mesh(capsule(), with_voxel(0.03));
  EXPECT_TRUE(m.envelope);
  EXPECT_EQ(m.cones, 1u);
  EXPECT_EQ(m.slabs, 0u);
  EXPECT_EQ(m.dropped_spheres, 0u);
  expect_one_closed_sphere(m.mesh);
  EXPECT_LT(max_distance_to_g(m.mesh, capsule()), m.voxel);
}

TEST(VdbEnvelope, TheBallsAloneGiveTwoComponents) {
  ev::VdbOptions opt = with_voxel(0.03);
  opt.primitives = gb::PrimitiveSet::atoms;
  const ev::VdbMesh m = ev::vdb_mesh(capsule(), opt);
  EXPECT_FALSE(m.envelope);
  EXPECT_EQ(m.cones, 0u);
  const ev::MeshCheck c = ev::check_mesh(m.mesh);
  EXPECT_TRUE(c.topology.closed);
  EXPECT_EQ(c.topology.components, 2u);
}

TEST(VdbEnvelope, OneFaceIsOneComponentOfGenusZero) {
  const ev::VdbMesh m = ev::vdb_mesh(one_face(), with_voxel(0.02));
  EXPECT_EQ(m.cones, 3u);
  EXPECT_EQ(m.slabs, 1u);
  expect_one_closed_sphere(m.mesh);
  EXPECT_LT(max_distance_to_g(m.mesh, one_face()), m.voxel);
}

TEST(VdbEnvelope, SameMeshAtOneAndTwoThreads) {
  ev::VdbMesh one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = ev::vdb_mesh(one_face(), with_voxel(0.01));
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = ev::vdb_mesh(one_face(), with_voxel(0.01));
  }
  ASSERT_EQ(one.mesh.points.size(), two.mesh.points.size());
  EXPECT_EQ(one.mesh.points, two.mesh.points);
  EXPECT_EQ(one.mesh.faces, two.mesh.faces);
  EXPECT_EQ(one.leaves, two.leaves);
}

TEST(VdbEnvelope, VoxelSearchHitsAVertexCount) {
  const ev::VdbMatch m = ev::vdb_match_vertices(capsule(), 20000);
  EXPECT_TRUE(m.best.envelope);
  EXPECT_LE(m.probes.size(), 5u);
  EXPECT_NEAR(static_cast<double>(m.best.mesh.points.size()), 20000.0, 0.02 * 20000);
}

TEST(VdbEnvelope, RefusesGOutsideTheWorldFrameAndBadVoxels) {
  const gb::TargetShape local = gb::make_target_shape(capsule(), gb::PrimitiveSet::envelope, {},
                                                      gb::bounding_cube_frame(capsule()));
  EXPECT_THROW(ev::vdb_mesh(local, {}), mg::InvalidInput);
  EXPECT_THROW(ev::vdb_mesh(capsule(), with_voxel(-1)), mg::InvalidInput);
  EXPECT_THROW(ev::vdb_mesh(capsule(), with_voxel(1e-12)), mg::InvalidInput);
}
