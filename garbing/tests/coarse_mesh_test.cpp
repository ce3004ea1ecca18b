#include "garbing/coarse_mesh.h"
#include "core/mesh_topology.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <set>
#include <tuple>

#include "atom_sets.h"

namespace {

using mg_test::atoms;
using FaceKey = std::tuple<int, int, int, long, long, long>;  // axis, sign, level, corner

mg::MeshTopology topology_of(const mg::garbing::CoarseMesh& m1) {
  return mg::mesh_topology(mg::soup_from_mesh(m1.mesh));
}

mg::garbing::CoarseMesh m1_of(const mg::MedialSurface& s, mg::garbing::OctreeOptions opt = {}) {
  return mg::garbing::extract_coarse_mesh(mg_test::octree_of(s, opt));
}

std::set<FaceKey> face_set(const mg::garbing::CoarseMesh& m1) {
  std::set<FaceKey> out;
  for (const auto& f : m1.faces)
    out.insert({f.axis, f.sign, f.level, f.corner[0], f.corner[1], f.corner[2]});
  return out;
}

void expect_closed_manifold(const mg::garbing::CoarseMesh& m1, const std::string& what) {
  const auto t = topology_of(m1);
  EXPECT_TRUE(t.closed) << what;
  EXPECT_TRUE(t.manifold) << what << ": " << t.first_problem;
  EXPECT_TRUE(t.oriented) << what << ": " << t.first_problem;
}

TEST(CoarseMesh, OneSphereAtAutomaticDepthHasThePapersFaceCount) {
  const auto m1 = m1_of(atoms({{Eigen::Vector3d(0.3, -2, 5), 1.0}}));
  EXPECT_EQ(m1.mesh.n_faces(), 1344u);  // the paper's Sphere row: M2 has 1344 vertices
  expect_closed_manifold(m1, "sphere");
  EXPECT_EQ(topology_of(m1).genus, 0);
}

/// Faces between active and inactive cells of a uniform grid at `level` over the same root.
std::set<FaceKey> uniform_grid_faces(const mg::MedialAtom& ball, const mg::garbing::Octree& t,
                                     int level) {
  const long n = 1L << level;
  const double s = t.side(level);
  const Eigen::Vector3d c = t.to_local(ball.centre);
  auto active = [&](long i, long j, long k) {
    if (i < 0 || j < 0 || k < 0 || i >= n || j >= n || k >= n) return false;
    const long ijk[3] = {i, j, k};
    double d2 = 0;
    for (int a = 0; a < 3; ++a) {
      const double lo = ijk[a] * s, hi = lo + s;
      const double d = std::max({lo - c[a], 0.0, c[a] - hi});
      d2 += d * d;
    }
    return d2 <= ball.radius * ball.radius;
  };
  std::set<FaceKey> out;
  for (long i = 0; i < n; ++i)
    for (long j = 0; j < n; ++j)
      for (long k = 0; k < n; ++k) {
        if (!active(i, j, k)) continue;
        for (int axis = 0; axis < 3; ++axis)
          for (int sign : {-1, 1}) {
            long nb[3] = {i, j, k};
            nb[axis] += sign;
            if (active(nb[0], nb[1], nb[2])) continue;
            long corner[3] = {i, j, k};
            corner[axis] += sign > 0 ? 1 : 0;
            out.insert({axis, sign, level, corner[0], corner[1], corner[2]});
          }
      }
  return out;
}

TEST(CoarseMesh, OneSphereMatchesTheUniformGridAtDepths4To6) {
  const mg::MedialAtom ball{Eigen::Vector3d(0.1, 0.2, -0.3), 0.7};
  for (int level : {4, 5, 6}) {
    mg::garbing::OctreeOptions opt;
    opt.min_depth = level;
    const auto t = mg_test::octree_of(atoms({ball}), opt);
    const auto m1 = mg::garbing::extract_coarse_mesh(t);
    EXPECT_EQ(face_set(m1), uniform_grid_faces(ball, t, level)) << "level " << level;
    expect_closed_manifold(m1, "sphere at level " + std::to_string(level));
  }
}

TEST(CoarseMesh, ClosedManifoldWithEachCriterionOff) {
  mg::MedialSurface chains;
  mg_test::add_chain(chains, Eigen::Vector3d(-1, 0, 0), Eigen::Vector3d(1, 0, 0), 21, 0.1);
  mg_test::add_chain(chains, Eigen::Vector3d(0, -1, 0.21), Eigen::Vector3d(0, 1, 0.21), 21, 0.1);
  const std::vector<std::pair<std::string, mg::MedialSurface>> inputs = {
      {"blob", mg_test::blob(30, 0.1, 0.3, 11)},
      {"ring", mg_test::ring(60, 1.0, 0.3)},
      {"chains", chains},
      {"gap", atoms({{Eigen::Vector3d(-1.005, 0, 0), 1}, {Eigen::Vector3d(1.005, 0, 0), 1}})}};
  for (const auto& [name, s] : inputs)
    for (int off = 0; off <= 4; ++off) {
      mg::garbing::OctreeOptions opt;
      opt.max_depth = 11;  // bounds the tree where near-touching balls drive criterion 3
      if (off > 0) opt.criteria[off - 1] = false;
      expect_closed_manifold(m1_of(s, opt), name + " without criterion " + std::to_string(off));
    }
}

TEST(CoarseMesh, InteriorCellShortcutChangesNoFace) {
  for (const auto& s : {mg_test::blob(30, 0.1, 0.3, 11), mg_test::ring(60, 1.0, 0.3)}) {
    mg::garbing::OctreeOptions full;
    full.skip_interior_cells = false;
    const auto a = m1_of(s), b = m1_of(s, full);
    EXPECT_EQ(face_set(a), face_set(b));
  }
}

TEST(CoarseMesh, RingOfSpheresHasGenusOne) {
  const auto t = topology_of(m1_of(mg_test::ring(60, 1.0, 0.3)));
  EXPECT_TRUE(t.closed && t.oriented);
  EXPECT_EQ(t.components, 1u);
  EXPECT_EQ(t.genus, 1);
}

/// Two balls whose active cells, with criterion 3 off, meet only along an edge (2D diagonal)
/// or at a corner (3D diagonal): the edge or vertex is duplicated, two closed spheres result.
TEST(CoarseMesh, LeavesMeetingAlongAnEdgeOrAtACornerCloseSeparately) {
  struct Case {
    const char* name;
    mg::MedialSurface s;
    int depth;
  };
  const double c2 = 0.75, c3 = 0.65;
  const std::vector<Case> cases = {
      {"edge", atoms({{Eigen::Vector3d(-c2, -c2, 0), 1}, {Eigen::Vector3d(c2, c2, 0), 1}}), 6},
      {"corner", atoms({{Eigen::Vector3d(-c3, -c3, -c3), 1}, {Eigen::Vector3d(c3, c3, c3), 1}}),
       5}};
  for (const auto& tc : cases) {
    for (bool criterion3 : {false, true}) {
      mg::garbing::OctreeOptions opt;
      opt.min_depth = tc.depth;
      opt.criteria[2] = criterion3;
      const auto m1 = m1_of(tc.s, opt);
      const auto t = topology_of(m1);
      EXPECT_TRUE(t.closed && t.manifold && t.oriented) << tc.name << ": " << t.first_problem;
      EXPECT_EQ(t.components, 2u) << tc.name;
      EXPECT_EQ(t.euler, 4) << tc.name;
      if (!criterion3) {
        EXPECT_GT(m1.split_vertices, 0u) << tc.name << ": the contact was expected";
      }
    }
  }
}

TEST(CoarseMesh, TwoBallsWithASmallGapStaySeparateUnlessCriterionThreeIsOff) {
  const auto s = atoms({{Eigen::Vector3d(-1.005, 0, 0), 1}, {Eigen::Vector3d(1.005, 0, 0), 1}});
  const auto t = mg_test::octree_of(s);
  EXPECT_GE(t.depth, 10);
  EXPECT_EQ(topology_of(mg::garbing::extract_coarse_mesh(t)).components, 2u);
  mg::garbing::OctreeOptions opt;
  opt.criteria[2] = false;
  const auto glued = topology_of(m1_of(s, opt));
  EXPECT_EQ(glued.components, 1u);  // without criterion 3 the two balls are glued
  EXPECT_EQ(glued.genus, 0);
}

TEST(CoarseMesh, TwoChainsPassingCloseStaySeparate) {
  mg::MedialSurface s;
  mg_test::add_chain(s, Eigen::Vector3d(-1, 0, 0), Eigen::Vector3d(1, 0, 0), 21, 0.1);
  mg_test::add_chain(s, Eigen::Vector3d(0, -1, 0.21), Eigen::Vector3d(0, 1, 0.21), 21, 0.1);
  const auto t = topology_of(m1_of(s));
  EXPECT_TRUE(t.closed && t.oriented);
  EXPECT_EQ(t.components, 2u);
  EXPECT_EQ(t.genus, 0);
}

TEST(CoarseMesh, FaceCentresAreTheSquareCentres) {
  const auto t = mg_test::octree_of(mg_test::blob(20, 0.1, 0.3, 5));
  const auto m1 = mg::garbing::extract_coarse_mesh(t);
  ASSERT_EQ(m1.face_centres.size(), m1.mesh.n_faces());
  EXPECT_GT(m1.hanging_corners, 0u);  // faces of several levels meet
  // Every loop vertex lies in the square's plane within the half-diagonal of the square, and
  // the square's four corners are at exactly the half-diagonal (hanging corners are closer).
  for (const auto f : m1.mesh.faces()) {
    const auto& face = m1.faces[f.idx()];
    const Eigen::Vector3d c = t.to_local(m1.face_centres[f.idx()]);
    const double half_diagonal = t.side(face.level) * std::sqrt(0.5);
    int at_corner = 0;
    for (const auto v : m1.mesh.fv_range(f)) {
      const auto& p = m1.mesh.point(v);
      const Eigen::Vector3d q = t.to_local(Eigen::Vector3d(p[0], p[1], p[2]));
      EXPECT_NEAR(q[face.axis], c[face.axis], 1e-12);
      const double d = (q - c).norm();
      EXPECT_LE(d, half_diagonal + 1e-12);
      if (std::abs(d - half_diagonal) < 1e-12) ++at_corner;
    }
    EXPECT_EQ(at_corner, 4);
  }
}

TEST(CoarseMesh, SameOutputAtOneAndTwoThreads) {
  const auto s = mg_test::blob(40, 0.1, 0.25, 13);
  mg::PolygonSoup one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = mg::soup_from_mesh(m1_of(s).mesh);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = mg::soup_from_mesh(m1_of(s).mesh);
  }
  EXPECT_EQ(one.faces, two.faces);
  ASSERT_EQ(one.points.size(), two.points.size());
  for (std::size_t i = 0; i < one.points.size(); ++i) EXPECT_EQ(one.points[i], two.points[i]);
}

}  // namespace
