// The OpenVDB baseline of a medial mesh's envelope: G's signed distance sampled, then meshed.
#include "core/errors.h"
#include "core/shapes.h"
#include "evaluate/atoms_distance.h"
#include "evaluate/mesh_checks.h"
#include "evaluate/vdb_mesh.h"
#include "garbing/frame.h"
#include "garbing/target_shape.h"

#include <gtest/gtest.h>

#include "test_util.h"

#include <tbb/global_control.h>

#include <algorithm>
#include <limits>
#include <utility>

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

// A block of 64 voxels reached only by a ball's cap: the cone is found by its frustum's box,
// which leaves the caps out, so the ball must stay a candidate there. With the balls of every
// cone dropped, the analytic capsule lost both caps from a voxel of 0.01 on (open mesh, 416
// boundary edges).
TEST(VdbEnvelope, CapsuleCapsSurviveFineVoxels) {
  const mg::MedialSurface s = mg::make_medial_capsule();
  for (const double voxel : {0.01, 0.005}) {
    const ev::VdbMesh m = ev::vdb_mesh(s, with_voxel(voxel));
    const ev::MeshCheck c = ev::check_mesh(m.mesh);  // volumeToMesh may fold a few quads
    EXPECT_TRUE(c.topology.closed && c.topology.manifold && c.topology.oriented) << voxel;
    EXPECT_EQ(c.topology.components, 1u) << voxel;
    EXPECT_EQ(c.topology.genus, 0) << voxel;
    EXPECT_LT(max_distance_to_g(m.mesh, s), voxel);
    Eigen::AlignedBox3d box;
    for (const auto& p : m.mesh.points) box.extend(p);
    const Eigen::AlignedBox3d balls =
        gb::bounding_box(s.atoms[0]).merged(gb::bounding_box(s.atoms[1]));
    EXPECT_LT((box.min() - balls.min()).norm(), voxel) << voxel;
    EXPECT_LT((box.max() - balls.max()).norm(), voxel) << voxel;
  }
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

namespace {

/// H(mesh, G) in % of the atoms' spheres' diagonal, as `evaluate atoms` measures it; samples
/// 0 = its default, else raised to twice the vertex count as the search does.
double hausdorff_to_g_pct(const mg::PolygonSoup& soup, const mg::MedialSurface& atoms,
                          const ev::AtomsDistanceOptions& search = {}) {
  ev::AtomsDistanceOptions opt = search;
  if (opt.samples > 0) opt.samples = std::max(opt.samples, 2 * soup.points.size());
  const ev::AtomsDistance d = ev::atoms_distance(soup, atoms, opt, "vdb mesh");
  return 100 * d.distance.hausdorff / ev::spheres_bbox_diagonal(atoms);
}

/// Few samples (twice the vertex count: every vertex and as many edge and face points) keep the
/// searches' first probe, at the diagonal / 400, under a second.
ev::AtomsDistanceOptions few_samples(gb::PrimitiveSet primitives = gb::PrimitiveSet::automatic) {
  ev::AtomsDistanceOptions opt;
  opt.primitives = primitives;
  opt.samples = 1;
  return opt;
}

/// The search's promise: within 15% of the target after at most 5 probes, or clamped.
void expect_near_target(const ev::VdbMatch& m, double target) {
  EXPECT_LE(m.probes.size(), 5u);
  if (!m.clamped) {
    EXPECT_NEAR(m.value, target, 0.15 * target);
  }
}

}  // namespace

TEST(VdbEnvelope, HausdorffToGShrinksWithTheVoxel) {
  double previous = std::numeric_limits<double>::infinity();
  for (double voxel : {0.08, 0.04, 0.02}) {
    const double h =
        hausdorff_to_g_pct(ev::vdb_mesh(one_face(), with_voxel(voxel)).mesh, one_face());
    EXPECT_LT(h, previous) << "voxel " << voxel;
    previous = h;
  }
}

TEST(VdbEnvelope, VoxelSearchHitsAHausdorffDistanceToG) {
  for (const auto& [atoms, target] : {std::pair{capsule(), 0.2}, std::pair{one_face(), 0.2}}) {
    const ev::VdbMatch m = ev::vdb_match_envelope(atoms, target, 0, few_samples());
    EXPECT_TRUE(m.best.envelope);
    EXPECT_FALSE(m.out_of_reach);
    expect_near_target(m, target);
    // The value is `evaluate atoms`'s Hausdorff (same G, samples and seed), in % of the
    // spheres' diagonal.
    EXPECT_DOUBLE_EQ(m.value, hausdorff_to_g_pct(m.best.mesh, atoms, few_samples()));
    ASSERT_FALSE(m.probes.empty());
    EXPECT_DOUBLE_EQ(m.probes.front().voxel, ev::spheres_bbox_diagonal(atoms) / 400);
  }
}

TEST(VdbEnvelope, VoxelSearchOnAGivenDiagonalScalesTheTarget) {
  // Twice the diagonal, half the percentage: the same distance in model units.
  const double diagonal = 2 * ev::spheres_bbox_diagonal(capsule());
  const ev::VdbMatch m = ev::vdb_match_envelope(capsule(), 0.1, diagonal, few_samples());
  expect_near_target(m, 0.1);
  EXPECT_DOUBLE_EQ(m.value, hausdorff_to_g_pct(m.best.mesh, capsule(), few_samples()) / 2);
}

TEST(VdbEnvelope, VoxelSearchOnTheSpheresPathMeasuresBallsAndCones) {
  // The capsule's balls are disjoint: G of the balls and cones is the two balls.
  const ev::AtomsDistanceOptions opt = few_samples(gb::PrimitiveSet::atoms);
  const ev::VdbMatch m = ev::vdb_match_envelope(capsule(), 0.2, 0, opt);
  EXPECT_FALSE(m.best.envelope);
  expect_near_target(m, 0.2);
  EXPECT_DOUBLE_EQ(m.value, hausdorff_to_g_pct(m.best.mesh, capsule(), opt));
}

TEST(VdbEnvelope, VoxelSearchStopsAtTheConeTheSpheresNeverFill) {
  // Two deeply overlapping balls: G of balls and cones has their cylinder, 0.032 outside the
  // crease (0.26% of the diagonal, stretched by a far small ball); the spheres' mesh never
  // fills it, so a target of 0.2% is out of reach.
  mg::MedialSurface s;
  s.atoms = {{Eigen::Vector3d(0, 0, 0), 1.0},
             {Eigen::Vector3d(0.5, 0, 0), 1.0},
             {Eigen::Vector3d(10, 0, 0), 0.1}};
  ASSERT_EQ(gb::make_target_shape(s, gb::PrimitiveSet::atoms, {}).cone_count(), 1u);
  const ev::VdbMatch m = ev::vdb_match_envelope(s, 0.2, 0, few_samples());
  EXPECT_FALSE(m.best.envelope);
  EXPECT_TRUE(m.out_of_reach);
  EXPECT_FALSE(m.clamped);
  EXPECT_EQ(m.probes.size(), 2u);
  EXPECT_GT(m.value, 0.2 * 1.15);
}

TEST(VdbEnvelope, VoxelSearchReportsAClampedVoxel) {
  // 20% is beyond the coarsest voxel, diagonal / 20: the search stops there and says so.
  const ev::VdbMatch m = ev::vdb_match_envelope(capsule(), 20, 0, few_samples());
  EXPECT_TRUE(m.clamped);
  EXPECT_LE(m.probes.size(), 5u);
  EXPECT_DOUBLE_EQ(m.best.voxel, ev::spheres_bbox_diagonal(capsule()) / 20);
  EXPECT_LT(m.value, 20.0);
}

TEST(VdbEnvelope, VoxelSearchRefusesBadTargets) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (double percent : {0.0, -1.0, nan, inf})
    EXPECT_THROW(ev::vdb_match_envelope(capsule(), percent), mg::InvalidInput) << percent;
  for (double diagonal : {-1.0, nan, inf})
    EXPECT_THROW(ev::vdb_match_envelope(capsule(), 0.5, diagonal), mg::InvalidInput) << diagonal;
  EXPECT_THROW(ev::vdb_match_envelope(capsule(), 0.5, 0, {}, /*max_probes=*/0), mg::InvalidInput);
  EXPECT_THROW(ev::vdb_match_envelope(mg::MedialSurface{}, 0.5), mg::InvalidInput);
}

TEST(VdbEnvelope, AtomsDistanceOnAPrebuiltGIsTheSame) {
  const ev::VdbMesh m = ev::vdb_mesh(one_face(), with_voxel(0.04));
  const ev::AtomsDistanceOptions opt;
  const ev::AtomsDistance built = ev::atoms_distance(m.mesh, one_face(), opt, "vdb");
  const gb::TargetShape g = gb::make_target_shape(one_face(), gb::PrimitiveSet::envelope, {});
  const ev::AtomsDistance given = ev::atoms_distance(m.mesh, g, opt, "vdb");
  EXPECT_EQ(built.distance.hausdorff, given.distance.hausdorff);
  EXPECT_EQ(built.distance.rms, given.distance.rms);
  EXPECT_EQ(built.cones, given.cones);
  EXPECT_EQ(built.slabs, given.slabs);
  EXPECT_TRUE(built.envelope);
  EXPECT_FALSE(given.envelope);  // G does not say what it was built from
  const gb::TargetShape local = gb::make_target_shape(one_face(), gb::PrimitiveSet::envelope, {},
                                                      gb::bounding_cube_frame(one_face()));
  EXPECT_THROW(ev::atoms_distance(m.mesh, local, opt, "vdb"), mg::InvalidInput);
}
