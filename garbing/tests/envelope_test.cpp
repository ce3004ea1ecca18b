// Medial meshes: G as the envelope of balls, cones and slabs, garbed end to end on analytic
// envelopes whose topology is known.
#include "core/errors.h"
#include "core/mesh_topology.h"
#include "core/shapes.h"
#include "core/triangle_defects.h"
#include "garbing/garb.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>

#include "atom_sets.h"

namespace {

using Eigen::Vector3d;
namespace gb = mg::garbing;

/// The envelope garbed; min_depth 0 is the automatic depth (leaf <= rc / 8), coarser ones keep
/// the larger scenes quick.
gb::Garbing garb_envelope(const mg::MedialSurface& s, int min_depth = 0) {
  gb::GarbOptions opt;
  opt.primitives = gb::PrimitiveSet::envelope;
  opt.octree.min_depth = min_depth;
  return gb::garb(s, opt);
}

double diagonal(const mg::MedialSurface& s) {
  Eigen::AlignedBox3d box;
  for (const auto& a : s.atoms) {
    box.extend(Vector3d(a.centre - Vector3d::Constant(a.radius)));
    box.extend(Vector3d(a.centre + Vector3d::Constant(a.radius)));
  }
  return box.diagonal().norm();
}

/// M2 is a closed, oriented 2-manifold without intersecting or degenerate triangles, with the
/// given components and genus, and every vertex lies on G: inside no primitive deeper than
/// tol and within tol of one (tol relative to the envelope's diagonal).
void expect_garbed(const mg::MedialSurface& s, const gb::Garbing& r, int components, int genus,
                   const std::string& what, double relative_tol = 1e-9) {
  const auto soup = mg::soup_from_mesh(r.m2.mesh);
  const auto t = mg::mesh_topology(soup);
  EXPECT_TRUE(t.closed && t.manifold && t.oriented) << what << ": " << t.first_problem;
  EXPECT_EQ(t.components, static_cast<std::size_t>(components)) << what;
  EXPECT_EQ(t.genus, genus) << what;
  const auto d = mg::find_triangle_defects(soup);
  EXPECT_TRUE(d.intersecting_pairs.empty()) << what << ": " << d.intersecting_pairs.size();
  EXPECT_TRUE(d.degenerate_faces.empty()) << what << ": " << d.degenerate_faces.size();
  const double tol = relative_tol * diagonal(s);
  const gb::TargetShape& g = r.g;
  long off = 0;
  for (const auto& p : soup.points) {
    const Vector3d v = g.frame().to_local(p);
    bool deep = false;
    for (int i = 0; i < static_cast<int>(g.primitive_count()) && !deep; ++i)
      deep = g.primitive_contains(i, v, tol);
    off += deep || !g.within(v, tol);
  }
  EXPECT_EQ(off, 0) << what << ": vertices off G (of " << soup.points.size() << ")";
  EXPECT_FALSE(r.tree.hit_max_depth) << what;
}

/// A centre atom of radius 0.5 and six around it on a circle of radius 3 at heights z(k), radii
/// r(k); `faces` of the fan (k, k + 1 mod 6) around the centre.
template <class Z, class R>
mg::MedialSurface hexagon_fan(int faces, const Z& z, const R& r) {
  mg::MedialSurface s;
  s.atoms.push_back({Vector3d(0, 0, 0), 0.5});
  for (int k = 0; k < 6; ++k) {
    const double a = 2 * M_PI * k / 6;
    s.atoms.push_back({Vector3d(3 * std::cos(a), 3 * std::sin(a), z(k)), r(k)});
  }
  for (int k = 0; k < faces; ++k) s.faces.push_back({0, 1 + k, 1 + (k + 1) % 6});
  return s;
}

// One face of equal balls: atoms 1 and 2 touch (their centres 2r apart to rounding), atoms 0
// and 1 just miss each other. Cells holding ball 2 and the cone (0, 1) saw two primitives
// apart (the cone grazes ball 2 to rounding) and split down to the depth stop (14 levels
// against d = 6); the face's slab, left out of those cells' lists because ball 2 stands for
// it, joins them: the criteria see the full set through shared atoms.
TEST(Envelope, TouchingBallsOfAFaceStayAtTheMinimalDepth) {
  mg::MedialSurface s;
  s.atoms = {{Vector3d(0.10000000000000003, -0.45000000000000001, 0.0030000000000000018), 0.1},
             {Vector3d(0.3000000000000001, -0.45000000000000001, 0.027000000000000017), 0.1},
             {Vector3d(0.3000000000000001, -0.25, 0.027000000000000017), 0.1}};
  s.edges = {{0, 1}, {1, 2}, {0, 2}};
  s.faces = {{0, 1, 2}};
  const gb::Garbing r = garb_envelope(s);
  EXPECT_EQ(r.tree.depth, r.tree.min_depth);
  expect_garbed(s, r, 1, 0, "touching face");
}

// A sparse slab's volume is mostly its prism, far from its balls: cells inside a listed hull
// hold no boundary and are not split down to d (before: 157,090 active leaves at d for 18,564
// boundary leaves). Every such leaf lies inside G.
TEST(Envelope, CellsInsideOneHullAreNotSplitToTheMinimalDepth) {
  const mg::MedialSurface s = mg::make_medial_slab();
  const gb::Garbing r = garb_envelope(s);
  std::vector<int> owners;
  for (const auto& f : r.m1.faces) owners.push_back(f.owner);
  std::sort(owners.begin(), owners.end());
  owners.erase(std::unique(owners.begin(), owners.end()), owners.end());
  long active_at_d = 0, inside_hull = 0;
  for (int c : r.tree.leaves) {
    const gb::OctreeCell& cell = r.tree.cells[c];
    active_at_d += cell.is_active() && cell.level == r.tree.min_depth;
    if (!cell.inside_one_hull) continue;
    ++inside_hull;
    const Eigen::AlignedBox3d cube = r.tree.cube(cell);
    for (int k = 0; k < 8; ++k)
      EXPECT_TRUE(r.g.contains(cube.corner(static_cast<Eigen::AlignedBox3d::CornerType>(k))))
          << "leaf " << c;
    EXPECT_TRUE(r.g.contains(cube.center())) << "leaf " << c;
  }
  EXPECT_GT(inside_hull, 100);
  EXPECT_LT(active_at_d, 3 * static_cast<long>(owners.size()));
  expect_garbed(s, r, 1, 0, "sparse slab");
}

TEST(Envelope, PrimitivesOfAMedialMesh) {
  mg::MedialSurface s = mg_test::atoms({{Vector3d(0, 0, 0), 1},
                                        {Vector3d(4, 0, 0), 0.5},
                                        {Vector3d(0, 4, 0), 0.5},
                                        {Vector3d(0.1, 0, 0), 3},
                                        {Vector3d(8, 0, 0), 0.5}});
  s.edges = {{0, 1}, {1, 0}, {0, 3}, {1, 4}, {0, 1}};
  s.faces = {{0, 1, 2}, {2, 1, 0}, {0, 1, 4}};  // the last one collinear
  const gb::EnvelopePrimitives e = gb::envelope_primitives(s);
  const std::vector<std::array<int, 2>> cones = {{0, 1}, {0, 2}, {0, 4}, {1, 2}, {1, 4}};
  EXPECT_EQ(e.cones, cones);  // (0, 3): ball 3 holds ball 0
  ASSERT_EQ(e.slabs.size(), 1u);
  EXPECT_EQ(e.slabs[0], (std::array<int, 3>{0, 1, 2}));
  EXPECT_EQ(e.counts.edges, 6);
  EXPECT_EQ(e.counts.repeated_edges, 5 + 9 - 6);
  EXPECT_EQ(e.counts.edges_in_a_ball, 1);
  EXPECT_EQ(e.counts.faces, 2);
  EXPECT_EQ(e.counts.repeated_faces, 1);
  EXPECT_EQ(e.counts.collinear_faces, 1);
  EXPECT_EQ(gb::resolve(gb::PrimitiveSet::automatic, s), gb::PrimitiveSet::envelope);
  s.edges.clear();
  s.faces.clear();
  EXPECT_EQ(gb::resolve(gb::PrimitiveSet::automatic, s), gb::PrimitiveSet::atoms);
}

TEST(Envelope, CapsuleOfDisjointUnequalBalls) {
  const mg::MedialSurface s = mg::make_medial_capsule();
  const auto r = garb_envelope(s);
  EXPECT_EQ(r.g.cone_count(), 1u);
  expect_garbed(s, r, 1, 0, "capsule");
}

TEST(Envelope, OneSlabOfThreeBalls) {
  const mg::MedialSurface s = mg::make_medial_slab();  // its sides listed as edges too
  const auto r = garb_envelope(s);
  ASSERT_EQ(r.g.slab_count(), 1u);
  EXPECT_EQ(r.g.cone_count(), 3u);
  expect_garbed(s, r, 1, 0, "slab");
  // Vertices over the inside of a tangent triangle lie in its plane.
  const gb::Slab& slab = r.g.slab(r.g.slab_id(0));
  ASSERT_TRUE(slab.has_tangent_triangles);
  long on_triangles = 0;
  const double leaf = r.tree.side(r.tree.depth);
  for (const auto& p : mg::soup_from_mesh(r.m2.mesh).points) {
    const Vector3d v = r.g.frame().to_local(p);
    for (int side = 0; side < 2; ++side) {
      const auto& t = slab.tangent[side];
      const Vector3d n = slab.tangent_normal[side];
      const double height = n.dot(v - t[0]);
      if (std::abs(height) > leaf) continue;
      // Barycentric coordinates of the foot, kept a leaf away from the triangle's sides.
      const Vector3d q = v - height * n;
      const Vector3d e1 = t[1] - t[0], e2 = t[2] - t[0], w = q - t[0];
      const double d11 = e1.dot(e1), d12 = e1.dot(e2), d22 = e2.dot(e2);
      const double det = d11 * d22 - d12 * d12;
      const double b1 = (d22 * w.dot(e1) - d12 * w.dot(e2)) / det;
      const double b2 = (d11 * w.dot(e2) - d12 * w.dot(e1)) / det;
      const double margin = 2 * leaf / std::sqrt(std::max(d11, d22));
      if (b1 < margin || b2 < margin || 1 - b1 - b2 < margin) continue;
      ++on_triangles;
      EXPECT_LE(std::abs(height), 1e-9 * diagonal(s)) << "vertex off its tangent plane";
    }
  }
  EXPECT_GT(on_triangles, 20);
}

TEST(Envelope, RingOfEdgesHasGenusOne) {
  // 16 atoms, neighbouring balls overlapping on two arcs and disjoint on the other two.
  const mg::MedialSurface s = mg::make_medial_ring();
  const auto r = garb_envelope(s);
  expect_garbed(s, r, 1, 1, "ring");
}

TEST(Envelope, TriangulatedDiscIsOneBall) {
  // A closed hexagon fan on a bowl, its radii shrinking from the centre to the rim.
  const mg::MedialSurface s = mg::make_medial_disc(/*rings=*/1);
  const auto r = garb_envelope(s, 6);
  EXPECT_EQ(r.g.slab_count(), 6u);
  EXPECT_EQ(r.g.cone_count(), 12u);
  expect_garbed(s, r, 1, 0, "disc");
}

TEST(Envelope, ThreeSheetsMeetingAlongAnEdge) {
  // A non-manifold medial mesh: three quads (two triangles each) sharing the edge (0, 1).
  const mg::MedialSurface s = mg::make_medial_sheets();
  const auto r = garb_envelope(s, 6);
  EXPECT_EQ(r.g.slab_count(), 6u);
  expect_garbed(s, r, 1, 0, "three sheets");
}

TEST(Envelope, TwoComponentsStayApart) {
  // Two capsules far apart: two shells.
  mg::MedialSurface s = mg_test::atoms({{Vector3d(0, 0, 0), 0.5},
                                        {Vector3d(3, 0, 0), 0.5},
                                        {Vector3d(0, 3, 0), 0.5},
                                        {Vector3d(3, 3, 0), 0.3}});
  s.edges = {{0, 1}, {2, 3}};
  const auto r = garb_envelope(s);
  expect_garbed(s, r, 2, 0, "two capsules");
}

TEST(Envelope, PointedAtomsOfZeroRadius) {
  mg::MedialSurface s =
      mg_test::atoms({{Vector3d(0, 0, 0), 1}, {Vector3d(3, 0, 0), 0}, {Vector3d(0, 3, 0.5), 0.2}});
  s.faces = {{0, 1, 2}};
  const auto r = garb_envelope(s);
  expect_garbed(s, r, 1, 0, "pointed slab");
}

TEST(Envelope, SameMeshAtOneAndTwoThreads) {
  // An open fan of five faces, its rim zigzagging, the gap closed by an edge.
  mg::MedialSurface s = hexagon_fan(
      5, [](int k) { return 0.3 * (k % 2); }, [](int) { return 0.3; });
  s.edges = {{6, 1}};
  std::vector<Vector3d> one, two;
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
    one = mg::soup_from_mesh(garb_envelope(s, 6).m2.mesh).points;
  }
  {
    tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
    two = mg::soup_from_mesh(garb_envelope(s, 6).m2.mesh).points;
  }
  EXPECT_EQ(one, two);
  EXPECT_GT(one.size(), 100u);
}

TEST(Garb, RefusesBadAtomsNamingTheCallersIndexBeforeSorting) {
  // The atoms are checked as given: an edge out of range is refused (not renumbered), and a
  // ball of radius 0 is named by its index in the caller's list, not in Z-order.
  mg::MedialSurface s = mg_test::atoms({{Vector3d(5, 5, 5), 1}, {Vector3d(0, 0, 0), 1}});
  s.edges = {{0, 7}};
  EXPECT_THROW(gb::garb(s), mg::InvalidInput);
  mg::MedialSurface t = mg_test::atoms({{Vector3d(5, 5, 5), 1}, {Vector3d(0, 0, 0), 0}});
  try {
    gb::garb(t);
    ADD_FAILURE() << "a ball of radius 0 was garbed as a ball";
  } catch (const mg::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("atom 1 has radius 0"), std::string::npos) << e.what();
  }
}

TEST(Envelope, SameMeshWithTheAtomsRenumbered) {
  // The fan above with its atoms in reverse order and its edges and faces renumbered to match
  // (and written the other way round): the same medial mesh, so the same M2, point for point.
  mg::MedialSurface s = hexagon_fan(
      5, [](int k) { return 0.3 * (k % 2); }, [](int k) { return 0.25 + 0.02 * k; });
  s.edges = {{6, 1}, {2, 3}};
  mg::MedialSurface t;
  const int n = static_cast<int>(s.atoms.size());
  t.atoms.assign(s.atoms.rbegin(), s.atoms.rend());
  for (const auto& e : s.edges) t.edges.push_back({n - 1 - e[1], n - 1 - e[0]});
  for (const auto& f : s.faces) t.faces.push_back({n - 1 - f[2], n - 1 - f[0], n - 1 - f[1]});
  const mg::PolygonSoup one = mg::soup_from_mesh(garb_envelope(s, 6).m2.mesh);
  const mg::PolygonSoup two = mg::soup_from_mesh(garb_envelope(t, 6).m2.mesh);
  EXPECT_EQ(one.points, two.points);
  EXPECT_EQ(one.faces, two.faces);
  EXPECT_GT(one.points.size(), 100u);
}

}  // namespace
