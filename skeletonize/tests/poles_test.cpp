#include "garbing/errors.h"
#include "garbing/shapes.h"
#include "skeletonize/poles.h"
#include "skeletonize/union_topology.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>

namespace {

using Eigen::Vector3d;
namespace sk = mg::skeletonize;

mg::MedialSurface balls(std::initializer_list<mg::MedialAtom> list) {
  mg::MedialSurface s;
  s.atoms = list;
  return s;
}

TEST(UnionTopology, OneBallTwoBallsAndARing) {
  const auto one = sk::union_topology(balls({{Vector3d(1, 2, 3), 0.5}}));
  EXPECT_EQ(one.components, 1u);
  EXPECT_EQ(one.euler, 2);
  const auto two = sk::union_topology(balls({{Vector3d(0, 0, 0), 1}, {Vector3d(3, 0, 0), 1}}));
  EXPECT_EQ(two.components, 2u);
  EXPECT_EQ(two.euler, 4);
  mg::MedialSurface ring;
  for (int k = 0; k < 60; ++k) {
    const double t = 2 * M_PI * k / 60;
    ring.atoms.push_back({Vector3d(std::cos(t), std::sin(t), 0), 0.3});
  }
  const auto torus = sk::union_topology(ring);  // coplanar centres: the planar complex
  EXPECT_EQ(torus.components, 1u);
  EXPECT_EQ(torus.euler, 0);
  // The same ring, tilted out of any plane by a small wave: the 3D complex.
  for (int k = 0; k < 60; ++k) ring.atoms[k].centre.z() = 0.05 * std::sin(3 * 2 * M_PI * k / 60);
  EXPECT_EQ(sk::union_topology(ring).euler, 0);
}

TEST(UnionTopology, HiddenBallsAndHollowShells) {
  // Balls inside another change nothing: a concentric one is hidden in the regular
  // triangulation; off-centre ones keep (empty-looking) power cells far away and are isolated
  // singular vertices of CGAL's alpha shape, which must not count as components.
  const auto nested = sk::union_topology(balls({{Vector3d(0, 0, 0), 1}, {Vector3d(0.2, 0, 0), 0.3},
                                                {Vector3d(0, 0.1, 0.1), 0.2}, {Vector3d(2, 2, 2), 0.1},
                                                {Vector3d(0, 0, 0), 0.5}}));
  EXPECT_EQ(nested.components, 2u);
  EXPECT_EQ(nested.euler, 4);
  EXPECT_GE(nested.hidden_atoms, 1u);
  // A shell of balls around a void: boundary = two spheres, Euler characteristic 4.
  mg::MedialSurface shell;
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 24; ++j) {
      const double th = M_PI * (i + 0.5) / 12, ph = 2 * M_PI * j / 24;
      shell.atoms.push_back({Vector3d(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)), 0.25});
    }
  const auto hollow = sk::union_topology(shell);
  EXPECT_EQ(hollow.components, 1u);
  EXPECT_EQ(hollow.euler, 4);
}

TEST(Skeletonize, SphereGivesOneAtomAtItsCentre) {
  mg::PolygonSoup sphere = mg::make_geodesic_sphere(12, 2.0);
  for (auto& p : sphere.points) p += Vector3d(0.3, -0.2, 1.0);
  const auto s = sk::skeletonize(sphere, {}, "sphere");
  ASSERT_EQ(s.atoms.atoms.size(), 1u);
  EXPECT_LT((s.atoms.atoms[0].centre - Vector3d(0.3, -0.2, 1.0)).norm(), 1e-3 * 2.0);
  EXPECT_NEAR(s.atoms.atoms[0].radius, 2.0, 2e-3);
}

TEST(Skeletonize, ExactTorusGivesSixtyAtomsOnTheCoreCircle) {
  const auto s = sk::skeletonize(mg::make_torus(60, 20, 1.0, 0.3), {}, "torus");
  ASSERT_EQ(s.atoms.atoms.size(), 60u);
  for (const auto& a : s.atoms.atoms) {
    EXPECT_LT(std::hypot(std::hypot(a.centre.x(), a.centre.y()) - 1.0, a.centre.z()), 2e-3);
    EXPECT_NEAR(a.radius, 0.3, 0.02 * 0.3);
  }
  EXPECT_GT(s.stats.exact_circumcentres, 0u);  // the regular grid needs the exact fallback
}

TEST(Skeletonize, RandomSamplesAndMidpointsAddToTheVertices) {
  const auto torus = mg::make_torus(24, 8, 1.0, 0.3);
  sk::SkeletonOptions opt;
  opt.random_samples = 500;
  EXPECT_EQ(sk::skeletonize(torus, opt, "t").stats.samples, 24u * 8 + 500);
  opt = {};
  opt.edge_midpoints = true;
  EXPECT_EQ(sk::skeletonize(torus, opt, "t").stats.samples, 24u * 8 * 4);  // V + E = V + 3V
}

TEST(Skeletonize, ConnectivityKeepsInsideSimplices) {
  sk::SkeletonOptions opt;
  opt.connectivity = true;
  const auto s = sk::skeletonize(mg::make_torus(60, 20, 1.0, 0.3), opt, "torus");
  // The 60 atoms around the ring: each links to its two neighbours at least; no triangle of
  // the planar triangulation crosses the hole.
  EXPECT_GE(s.atoms.edges.size(), 60u);
  mg::validate(s.atoms);
}

TEST(Skeletonize, RefusesOpenNonManifoldEmptyAndFlatMeshes) {
  auto error = [](const mg::PolygonSoup& m) {
    try {
      sk::skeletonize(m, {}, "m.off");
    } catch (const mg::InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  mg::PolygonSoup open = mg::make_box(Vector3d::Zero(), Vector3d::Ones());
  open.faces.pop_back();
  EXPECT_EQ(error(open), "m.off: open mesh (4 boundary edges): poles need a closed surface");
  mg::PolygonSoup fin = mg::make_box(Vector3d::Zero(), Vector3d::Ones());
  fin.points.push_back(Vector3d(0.5, -1, 0));
  fin.faces.push_back({0, 1, 8});
  EXPECT_EQ(error(fin).rfind("m.off: non-manifold mesh: edge (0, 1) is shared by 3 faces", 0), 0u);
  EXPECT_EQ(error(mg::PolygonSoup{}), "m.off: empty mesh (no faces)");
  // A closed but flat mesh: two triangles back to back.
  mg::PolygonSoup flat;
  flat.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  flat.faces = {{0, 1, 2}, {0, 2, 1}};
  EXPECT_EQ(error(flat), "m.off: fewer than 4 non-coplanar samples: no Delaunay cell");
}

TEST(Skeletonize, SameAtomsAtOneAndTwoThreads) {
  const auto mesh = mg::make_bumpy_torus(40, 30, 1.0, 0.35, 0.1, 6, 3);
  sk::SkeletonOptions opt;
  opt.random_samples = 2000;
  mg::MedialSurface one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = sk::skeletonize(mesh, opt, "b").atoms;
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = sk::skeletonize(mesh, opt, "b").atoms;
  }
  ASSERT_EQ(one.atoms.size(), two.atoms.size());
  for (std::size_t i = 0; i < one.atoms.size(); ++i) {
    EXPECT_EQ(one.atoms[i].centre, two.atoms[i].centre);
    EXPECT_EQ(one.atoms[i].radius, two.atoms[i].radius);
  }
}

}  // namespace
