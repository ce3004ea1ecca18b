// Inner poles on generated shapes: analytic atoms, options, determinism, refusals.
#include "skeletonize/poles.h"
#include "core/errors.h"
#include "core/random.h"
#include "core/shapes.h"
#include "skeletonize/union_topology.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <sstream>

namespace {

using Eigen::Vector3d;
namespace sk = mg::skeletonize;

std::string ma_text(const mg::MedialSurface& s) {
  std::ostringstream out;
  mg::format_medial_surface(out, s);
  return out.str();
}

std::string refusal(const mg::PolygonSoup& m) {
  try {
    sk::skeletonize(m, {}, "m.off");
  } catch (const mg::InvalidInput& e) {
    return e.what();
  }
  return "(accepted)";
}

TEST(Skeletonize, SphereGivesOneAtomAtItsCentre) {
  const double R = 2.0;
  const Vector3d centre(0.3, -0.2, 1.0);
  mg::PolygonSoup sphere = mg::make_geodesic_sphere(12, R);
  for (auto& p : sphere.points) p += centre;
  const auto s = sk::skeletonize(sphere, {}, "sphere");
  ASSERT_EQ(s.atoms.atoms.size(), 1u);
  EXPECT_LT((s.atoms.atoms[0].centre - centre).norm(), 1e-3 * R);
  EXPECT_NEAR(s.atoms.atoms[0].radius, R, 1e-3 * R);
  EXPECT_GT(s.stats.merged, 1000u);  // 1442 poles, all near the centre
  EXPECT_EQ(s.stats.skipped_samples, 0u);
  EXPECT_EQ(s.stats.hull_samples, s.stats.samples);  // every vertex of a convex mesh
  // Clamped: the distance to the inscribed polyhedron, a little under R.
  sk::SkeletonOptions clamp;
  clamp.clamp_radius = true;
  const auto c = sk::skeletonize(sphere, clamp, "sphere");
  ASSERT_EQ(c.atoms.atoms.size(), 1u);
  EXPECT_LT(c.atoms.atoms[0].radius, R);
  EXPECT_GT(c.atoms.atoms[0].radius, 0.99 * R);
  EXPECT_EQ(c.stats.worst_overshoot, 0.0);
  // The pole's ball pokes out of the inscribed polyhedron by what clamping took off it.
  EXPECT_GT(c.stats.pole_overshoot, 0.0);
  EXPECT_DOUBLE_EQ(c.stats.pole_overshoot, s.atoms.atoms[0].radius - c.atoms.atoms[0].radius);
  EXPECT_DOUBLE_EQ(s.stats.pole_overshoot, c.stats.pole_overshoot);
  EXPECT_DOUBLE_EQ(s.stats.worst_overshoot, s.stats.pole_overshoot);  // unclamped: the same ball
}

TEST(Skeletonize, ExactTorusGivesSixtyAtomsOnTheCoreCircle) {
  const auto s = sk::skeletonize(mg::make_torus(60, 20, 1.0, 0.3), {}, "torus");
  ASSERT_EQ(s.atoms.atoms.size(), 60u);
  for (const auto& a : s.atoms.atoms) {
    EXPECT_LT(std::hypot(std::hypot(a.centre.x(), a.centre.y()) - 1.0, a.centre.z()), 2e-3);
    EXPECT_NEAR(a.radius, 0.3, 0.02 * 0.3);
  }
  // Its grid puts 4 samples on one circle: those cells need the exact circumcentre.
  EXPECT_GT(s.stats.exact_circumcentres, 0u);
  EXPECT_EQ(s.stats.rejected_cells, 0u);
  const auto t = sk::union_topology(s.atoms);
  EXPECT_EQ(t.components, 1u);
  EXPECT_EQ(t.euler, 0);
}

TEST(Skeletonize, SamplesAreVerticesMidpointsAndSeededPointsOnTheFaces) {
  const auto torus = mg::make_torus(24, 8, 1.0, 0.3);
  sk::SkeletonOptions opt;
  opt.random_samples = 500;
  const auto a = sk::skeletonize(torus, opt, "t");
  EXPECT_EQ(a.stats.samples, 24u * 8 + 500);
  const sk::SolidQuery solid(torus);
  for (const auto& p : a.samples) EXPECT_LT(solid.distance(p), 1e-12);
  opt.seed = 2;
  const auto b = sk::skeletonize(torus, opt, "t");
  EXPECT_NE(a.samples.back(), b.samples.back());  // another stream
  opt.seed = 1;
  EXPECT_EQ(sk::skeletonize(torus, opt, "t").samples, a.samples);  // the same stream
  opt = {};
  opt.edge_midpoints = true;
  EXPECT_EQ(sk::skeletonize(torus, opt, "t").stats.samples, 24u * 8 * 4);  // V + E = V + 3V
}

TEST(Skeletonize, MergeToleranceDecidesWhatIsOneAtom) {
  const auto sphere = mg::make_geodesic_sphere(8, 1.0);
  sk::SkeletonOptions opt;
  opt.merge_tol = 0;  // only equal poles merge: the sphere's poles scatter around its centre
  const auto s = sk::skeletonize(sphere, opt, "sphere");
  EXPECT_GT(s.atoms.atoms.size(), 1u);
  for (std::size_t i = 0; i < s.samples.size(); ++i)  // still on their (unmerged) poles' balls
    EXPECT_NEAR((s.samples[i] - s.atoms.atoms[s.atom_of_sample[i]].centre).norm(),
                s.atoms.atoms[s.atom_of_sample[i]].radius, 1e-9);
  opt.merge_tol = 0.01;  // poles within 0.005 of each other
  const auto m = sk::skeletonize(sphere, opt, "sphere");
  EXPECT_EQ(m.stats.merge_tol, 0.01);
  EXPECT_EQ(m.atoms.atoms.size(), 1u);
}

TEST(Skeletonize, SameFileAtOneAndTwoThreadsAndAnyVertexOrder) {
  const auto bumpy = mg::make_bumpy_torus(40, 30, 1.0, 0.35, 0.1, 6, 3);
  const auto torus = mg::make_torus(60, 20, 1.0, 0.3);
  sk::SkeletonOptions random;
  random.random_samples = 2000;
  sk::SkeletonOptions full;
  full.clamp_radius = full.connectivity = full.edge_midpoints = true;
  for (const auto& [mesh, opt] : {std::pair{bumpy, random}, std::pair{torus, full}}) {
    std::string one, two;
    {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
      one = ma_text(sk::skeletonize(mesh, opt, "m").atoms);
    }
    {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
      two = ma_text(sk::skeletonize(mesh, opt, "m").atoms);
    }
    EXPECT_EQ(one, two);
    // The same mesh with its vertices and faces in another order: the same file.
    mg::PolygonSoup shuffled = mesh;
    const int n = static_cast<int>(mesh.points.size());
    auto moved = [n](int v) { return (v * 7919 + 13) % n; };  // a permutation (7919 is prime)
    for (int v = 0; v < n; ++v) shuffled.points[moved(v)] = mesh.points[v];
    for (auto& f : shuffled.faces)
      for (int& v : f) v = moved(v);
    std::reverse(shuffled.faces.begin(), shuffled.faces.end());
    if (opt.random_samples == 0) {  // random points depend on the face order
      EXPECT_EQ(ma_text(sk::skeletonize(shuffled, opt, "m").atoms), one);
    }
  }
}

TEST(Skeletonize, ConnectivityKeepsTheRegularSimplicesInsideTheObject) {
  sk::SkeletonOptions opt;
  opt.connectivity = true;
  const auto s = sk::skeletonize(mg::make_torus(60, 20, 1.0, 0.3), opt, "torus");
  ASSERT_EQ(s.atoms.atoms.size(), 60u);
  mg::validate(s.atoms);
  const auto& a = s.atoms.atoms;
  // Inside the solid torus (the mesh's flat faces dip up to 1e-3 below its inner equator).
  auto inside = [](const Vector3d& p) {
    return std::hypot(std::hypot(p.x(), p.y()) - 1.0, p.z()) < 0.3 + 2e-3;
  };
  for (const auto& e : s.atoms.edges)
    for (double t = 0; t <= 1; t += 0.05)
      EXPECT_TRUE(inside((1 - t) * a[e[0]].centre + t * a[e[1]].centre));
  for (const auto& f : s.atoms.faces)
    for (double u = 0; u <= 1; u += 0.1)
      for (double v = 0; u + v <= 1; v += 0.1)
        EXPECT_TRUE(inside(a[f[0]].centre + u * (a[f[1]].centre - a[f[0]].centre) +
                           v * (a[f[2]].centre - a[f[0]].centre)));
  // Every atom is linked to its two neighbours around the ring; chords across the hole are not.
  std::size_t neighbours = 0;
  for (const auto& e : s.atoms.edges)
    neighbours += (a[e[0]].centre - a[e[1]].centre).norm() < 2 * std::sin(1.5 * M_PI / 60);
  EXPECT_EQ(neighbours, 60u);
  EXPECT_LT(s.atoms.edges.size(), sk::regular_simplices(s.atoms).edges.size());
  EXPECT_LT(s.atoms.faces.size(), sk::regular_simplices(s.atoms).triangles.size());
  EXPECT_EQ(s.stats.hidden_atoms, 0u);
}

TEST(SolidQuery, InsideTestsAndDistancesOnABox) {
  const sk::SolidQuery box(mg::make_box(Vector3d::Zero(), Vector3d(2, 1, 1)));
  EXPECT_TRUE(box.contains(Vector3d(1, 0.5, 0.5)));
  EXPECT_FALSE(box.contains(Vector3d(3, 0.5, 0.5)));
  EXPECT_NEAR(box.distance(Vector3d(1, 0.5, 0.5)), 0.5, 1e-15);
  EXPECT_NEAR(box.distance(Vector3d(1, 0.5, 0.5), Vector3d(2, 0.5, 0.5)), 0.5, 1e-15);
  EXPECT_NEAR(box.distance(Vector3d(3, 0.5, 0.5)), 1.0, 1e-15);
  EXPECT_TRUE(box.segment_inside(Vector3d(0.1, 0.5, 0.5), Vector3d(1.9, 0.5, 0.5)));
  EXPECT_FALSE(box.segment_inside(Vector3d(0.1, 0.5, 0.5), Vector3d(2.1, 0.5, 0.5)));
  EXPECT_TRUE(
      box.triangle_inside(Vector3d(0.1, 0.1, 0.1), Vector3d(1.9, 0.1, 0.1), Vector3d(1, 0.9, 0.9)));
  EXPECT_FALSE(
      box.triangle_inside(Vector3d(0.1, 0.1, 0.1), Vector3d(1.9, 0.1, 0.1), Vector3d(1, 1.5, 0.5)));
}

TEST(SolidQuery, PlainDistancesAgreeWithCgalsOnASphereAndADegenerateFace) {
  // A geodesic sphere (curved: every region of the triangle projection is met) with one
  // vertex of a face pushed onto the segment of the other two (a collinear face).
  mg::PolygonSoup sphere = mg::make_geodesic_sphere(4, 1.0);
  const auto& f = sphere.faces.front();
  sphere.points[f[2]] = 0.5 * (sphere.points[f[0]] + sphere.points[f[1]]);
  const sk::SolidQuery cgal(sphere);
  const sk::SolidQuery plain(sphere, sk::SolidQuery::Distances::plain);
  auto coordinate = [](std::uint64_t k) { return 4 * mg::unit_interval(mg::splitmix64(k)) - 2; };
  for (std::uint64_t i = 0; i < 2000; ++i) {
    const Vector3d p(coordinate(3 * i), coordinate(3 * i + 1), coordinate(3 * i + 2));
    ASSERT_NEAR(plain.distance(p), cgal.distance(p), 1e-12) << p.transpose();
    ASSERT_NEAR((plain.closest_point(p) - p).norm(), cgal.distance(p), 1e-12) << p.transpose();
    ASSERT_NEAR(plain.distance(p, sphere.points[i % sphere.points.size()]), cgal.distance(p),
                1e-12);
  }
  // Points nearest the degenerate face: on its segment.
  const Vector3d mid = 0.5 * (sphere.points[f[0]] + sphere.points[f[1]]);
  for (const Vector3d& p : {Vector3d(1.3 * mid), Vector3d(0.7 * mid)})
    EXPECT_NEAR(plain.distance(p), cgal.distance(p), 1e-12);
}

TEST(Skeletonize, RefusesOpenNonManifoldEmptyFlatAndBrokenMeshes) {
  mg::PolygonSoup open = mg::make_box(Vector3d::Zero(), Vector3d::Ones());
  open.faces.pop_back();
  EXPECT_EQ(refusal(open), "m.off: open mesh (4 boundary edges): poles need a closed surface");
  mg::PolygonSoup fin = mg::make_box(Vector3d::Zero(), Vector3d::Ones());
  fin.points.push_back(Vector3d(0.5, -1, 0));
  fin.faces.push_back({0, 1, 8});
  EXPECT_EQ(refusal(fin).rfind("m.off: non-manifold mesh: edge (0, 1) is shared by 3 faces", 0),
            0u);
  EXPECT_EQ(refusal(mg::PolygonSoup{}), "m.off: empty mesh (no faces)");
  // Closed but flat: two triangles back to back.
  mg::PolygonSoup flat;
  flat.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  flat.faces = {{0, 1, 2}, {0, 2, 1}};
  EXPECT_EQ(refusal(flat), "m.off: fewer than 4 non-coplanar samples: no Delaunay cell");
  mg::PolygonSoup nan = mg::make_box(Vector3d::Zero(), Vector3d::Ones());
  nan.points[3].y() = NAN;
  EXPECT_EQ(refusal(nan), "m.off: vertex 3 has a non-finite coordinate");
  mg::PolygonSoup range = mg::make_box(Vector3d::Zero(), Vector3d::Ones());
  range.faces[2][1] = 8;
  EXPECT_EQ(refusal(range), "m.off: face 2: vertex index 8 out of range [0, 8)");
  mg::PolygonSoup inverted = mg::make_box(Vector3d::Zero(), Vector3d::Ones());
  std::reverse(inverted.faces[0].begin(), inverted.faces[0].end());
  EXPECT_EQ(refusal(inverted).rfind("m.off: ", 0), 0u);
  EXPECT_NE(refusal(inverted), "(accepted)");
}

}  // namespace
