#include "garbing/refine_mesh.h"
#include "core/errors.h"
#include "core/mesh_topology.h"
#include "core/triangle_defects.h"
#include "garbing/detail/polygon_triangulation.h"
#include "garbing/garb.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>
#include <iostream>

#include "atom_sets.h"

namespace {

using Eigen::Vector3d;
using mg_test::atoms;

mg::garbing::RefinedMesh garb(const mg::MedialSurface& s,
                              const mg::garbing::RefineOptions& ropt = {},
                              const mg::garbing::OctreeOptions& topt = {},
                              const mg::garbing::ConeOptions& cones = {}) {
  return mg::garbing::garb(s, {cones, topt, ropt}).m2;
}

/// Cones of every intersecting pair adjacent in the regular triangulation, however shallow.
mg::garbing::ConeOptions every_cone() {
  mg::garbing::ConeOptions cones;
  cones.min_circle_ratio = 0;
  cones.max_collar = 0;
  return cones;
}

mg::garbing::ConeOptions no_cones() {
  mg::garbing::ConeOptions cones;
  cones.source = mg::garbing::ConeSource::none;
  return cones;
}

std::vector<Vector3d> points(const mg::Mesh& m) {
  std::vector<Vector3d> out;
  for (const auto v : m.vertices()) {
    const auto& p = m.point(v);
    out.emplace_back(p[0], p[1], p[2]);
  }
  return out;
}

void expect_sound(const mg::Mesh& m, const std::string& what) {
  const auto soup = mg::soup_from_mesh(m);
  const auto t = mg::mesh_topology(soup);
  EXPECT_TRUE(t.closed && t.manifold && t.oriented) << what << ": " << t.first_problem;
  const auto d = mg::find_triangle_defects(soup);
  EXPECT_TRUE(d.intersecting_pairs.empty()) << what << ": " << d.intersecting_pairs.size();
  EXPECT_TRUE(d.degenerate_faces.empty()) << what << ": " << d.degenerate_faces.size();
}

TEST(RefineMesh, OneSphereReproducesThePapersRowOnTheSphere) {
  const mg::MedialAtom ball{Vector3d(0.5, -1, 2), 1.5};
  const auto m2 = garb(atoms({ball}));
  EXPECT_EQ(m2.mesh.n_vertices(), 1344u);
  EXPECT_EQ(m2.mesh.n_faces(), 2684u);
  for (const Vector3d& p : points(m2.mesh))
    EXPECT_NEAR((p - ball.centre).norm(), ball.radius, 1e-9 * ball.radius);
  expect_sound(m2.mesh, "sphere");
  EXPECT_EQ(mg::mesh_topology(mg::soup_from_mesh(m2.mesh)).genus, 0);
}

TEST(RefineMesh, TwoOverlappingSpheresLandExactlyOnG) {
  const auto s = atoms({{Vector3d(0, 0, 0), 1.0}, {Vector3d(1.2, 0.3, -0.2), 0.7}});
  // Every cone: the circle radius is 0.80 of the smaller ball, the collar 2.4 rc / 8.
  const auto pairs = mg::garbing::cone_pairs(s, every_cone());
  ASSERT_EQ(pairs.size(), 1u);
  const mg::garbing::TargetShape shape(s, pairs);
  const auto m2 = garb(s, {}, {}, every_cone());
  for (const Vector3d& p : points(m2.mesh)) {
    EXPECT_LT(shape.distance(p), 1e-9) << p.transpose();
    // Not strictly inside any primitive, beyond rounding.
    for (int g = 0; g < 3; ++g) EXPECT_FALSE(shape.primitive_contains(g, p, 1e-9)) << p.transpose();
  }
  expect_sound(m2.mesh, "two spheres");
}

TEST(RefineMesh, RingOfSpheresHasGenusOneAndNoFolds) {
  const auto m2 = garb(mg_test::ring(60, 1.0, 0.3));
  expect_sound(m2.mesh, "ring");
  const auto t = mg::mesh_topology(mg::soup_from_mesh(m2.mesh));
  EXPECT_EQ(t.genus, 1);
  EXPECT_EQ(t.faces, 2 * t.vertices - 4 + 4 * 1);
}

/// A coarse octree keeps these meshes small (the automatic depth gives tens of thousands).
mg::garbing::OctreeOptions coarse() {
  mg::garbing::OctreeOptions opt;
  opt.min_depth = 5;
  return opt;
}

TEST(RefineMesh, AblationsAndSubdivisionStayClosed) {
  const auto s = mg_test::blob(12, 0.2, 0.4, 3);
  mg::garbing::RefineOptions opt;
  expect_sound(garb(s, opt, coarse(), no_cones()).mesh, "spheres only");
  opt.subdivisions = 1;
  const auto refined = garb(s, opt, coarse(), no_cones());
  expect_sound(refined.mesh, "spheres only, refine 1");
  EXPECT_GT(refined.stats.vertices_migrated, refined.mesh.n_vertices() / 2);
  opt = {};
  opt.dual = false;
  for (const auto& [what, cones] : {std::make_pair("no dual", mg::garbing::ConeOptions{}),
                                    std::make_pair("no dual, spheres only", no_cones())}) {
    const auto no_dual = garb(s, opt, coarse(), cones);
    const auto t = mg::mesh_topology(mg::soup_from_mesh(no_dual.mesh));
    EXPECT_TRUE(t.closed && t.oriented) << what << ": " << t.first_problem;
  }
}

TEST(RefineMesh, EveryVertexOfM1ItselfFindsItsPrimitives) {
  // --no-dual migrates M1's vertices, lattice corners on the boundary between active and
  // inactive leaves that reach the root frame a few ulps off. Each must still get the
  // primitives of an active leaf. (Measured before the fix: 7,839 and 19,494 vertices fell
  // back for want of a direction; after: 16 and 1, genuine zeros: a corner met by one cone
  // whose foot falls outside it, a gap split's midpoint in an inactive leaf.)
  mg::garbing::RefineOptions opt;
  opt.dual = false;
  for (const auto& [what, s] : {std::make_pair("ring", mg_test::ring(60, 1.0, 0.3)),
                                std::make_pair("blob", mg_test::blob(12, 0.2, 0.4, 3))}) {
    const auto m = garb(s, opt);
    EXPECT_GT(m.stats.vertices_migrated, 1000u) << what;
    EXPECT_LT(m.stats.fallback_zero_direction, m.stats.vertices_migrated / 100) << what;
  }
}

TEST(RefineMesh, SameOutputAtOneAndTwoThreads) {
  const auto s = mg_test::blob(20, 0.15, 0.35, 9);
  mg::PolygonSoup one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = mg::soup_from_mesh(garb(s, {}, coarse()).mesh);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = mg::soup_from_mesh(garb(s, {}, coarse()).mesh);
  }
  EXPECT_EQ(one.faces, two.faces);
  EXPECT_EQ(one.points, two.points);
}

/// The first entries found from the octree's lists (the vertex's leaf, then the leaves its
/// ray crosses, crease-only leaves among them) are the hierarchy's over all primitives: the
/// same M2, to the bit, with and without them, from the dual (on a blob where dropping the
/// crease-only cones of the crossed leaves changes M2), from M1 itself and subdivided.
TEST(RefineMesh, LocalLineQueriesMatchTheQueriesOverAllPrimitives) {
  struct Case {
    const char* what;
    mg::MedialSurface atoms;
    bool dual;
    int subdivisions;
  };
  const std::vector<Case> cases = {{"dual", mg_test::blob(40, 0.1, 0.35, 7), true, 0},
                                   {"dual, subdivided", mg_test::blob(30, 0.05, 0.3, 3), true, 1},
                                   {"no dual", mg_test::blob(30, 0.05, 0.3, 3), false, 0}};
  for (const Case& c : cases) {
    mg::garbing::RefineOptions local, global;
    local.dual = global.dual = c.dual;
    local.subdivisions = global.subdivisions = c.subdivisions;
    global.local_queries = false;
    const auto a = mg::soup_from_mesh(garb(c.atoms, local, coarse(), every_cone()).mesh);
    const auto b = mg::soup_from_mesh(garb(c.atoms, global, coarse(), every_cone()).mesh);
    ASSERT_GT(a.points.size(), 1000u) << c.what;
    EXPECT_EQ(a.faces, b.faces) << c.what;
    EXPECT_EQ(a.points, b.points) << c.what;
  }
}

/// Largest distance from G of the vertices, edge midpoints and centroids of a mesh.
double farthest_sample(const mg::Mesh& m, const mg::garbing::TargetShape& shape) {
  const auto soup = mg::soup_from_mesh(m);
  double worst = 0;
  for (const auto& f : soup.faces) {
    const Vector3d a = soup.points[f[0]], b = soup.points[f[1]], c = soup.points[f[2]];
    for (const Vector3d& p :
         std::initializer_list<Vector3d>{a, (a + b) / 2, (b + c) / 2, (c + a) / 2, (a + b + c) / 3})
      worst = std::max(worst, shape.distance(p));
  }
  return worst;
}

/// Two unit balls meeting at a sharp concave crease (no cone: its groove stays open). M2's
/// edges across the groove bridge it: without gap splitting M2 strays more than a leaf from
/// G (measured 0.126 with a leaf of 0.122); the split edges' vertices land in the groove.
TEST(RefineMesh, GapSplittingFollowsASharpCrease) {
  const auto s = atoms({{Vector3d(0, 0, 0), 1.0}, {Vector3d(1.9, 0, 0), 1.0}});
  const mg::garbing::TargetShape g = mg_test::shape_of(s, no_cones());
  const mg::garbing::Octree tree = mg::garbing::build_octree(g);
  const mg::garbing::CoarseMesh m1 = mg::garbing::extract_coarse_mesh(tree);
  const mg::garbing::TargetShape shape(s, {});  // in world coordinates, as M2
  const double leaf = tree.side(tree.min_depth);
  mg::garbing::RefineOptions off;
  off.max_gap = 0;
  const auto bridged = mg::garbing::refine_mesh(m1, tree, g, off);
  EXPECT_EQ(bridged.stats.gap_splits, 0u);
  EXPECT_GT(farthest_sample(bridged.mesh, shape), leaf);
  const auto split = mg::garbing::refine_mesh(m1, tree, g);
  EXPECT_GT(split.stats.gap_splits, 100u);
  EXPECT_EQ(split.mesh.n_vertices(), bridged.mesh.n_vertices() + split.stats.gap_splits);
  EXPECT_LT(farthest_sample(split.mesh, shape), 0.75 * leaf);
  expect_sound(split.mesh, "two balls, gap splitting");
  EXPECT_EQ(split.stats.intersecting_before, 0u);  // the splitting adds no fold
  for (const Vector3d& p : points(split.mesh)) EXPECT_LT(shape.distance(p), 1e-9) << p.transpose();
  // The same at one and two threads.
  mg::PolygonSoup one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = mg::soup_from_mesh(mg::garbing::refine_mesh(m1, tree, g).mesh);
  }
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
    two = mg::soup_from_mesh(mg::garbing::refine_mesh(m1, tree, g).mesh);
  }
  EXPECT_EQ(one.faces, two.faces);
  EXPECT_EQ(one.points, two.points);
}

TEST(DualFaceTriangulation, ShortestDiagonalsAndNoRepeatedEdge) {
  // A hexagon stretched along x: the least total diagonal length is a zigzag of the three
  // short chords across it, never a long chord along it.
  const std::vector<Vector3d> hexagon = {{0, 0, 0}, {1, -1, 0}, {3, -1, 0},
                                         {4, 0, 0}, {3, 1, 0},  {1, 1, 0}};
  mg::garbing::detail::EdgeSet edges(hexagon.size());
  const std::vector<int> poly = {0, 1, 2, 3, 4, 5};
  for (int i = 0; i < 6; ++i) edges.insert(poly[i], poly[(i + 1) % 6]);
  std::vector<std::array<int, 3>> out;
  ASSERT_TRUE(mg::garbing::detail::min_diagonal_triangulation(poly, hexagon, edges, out));
  ASSERT_EQ(out.size(), 4u);
  double total = 0;
  int diagonals = 0;
  for (int a = 0; a < 6; ++a)
    for (int b = a + 2; b < 6; ++b)
      if (!(a == 0 && b == 5) && edges.contains(a, b)) {
        total += (hexagon[a] - hexagon[b]).norm();
        ++diagonals;
      }
  EXPECT_EQ(diagonals, 3);
  EXPECT_NEAR(total, 4 + 2 * std::sqrt(2.0), 1e-12);  // 1-5 and 2-4 (2 each), 1-4 or 2-5
  EXPECT_FALSE(edges.contains(0, 3));

  // Two quads sharing the vertex pair (0, 2): the first takes the short diagonal 0-2, so the
  // second must take its own long diagonal 1-3 instead of repeating 0-2.
  const std::vector<Vector3d> p = {{0, 0, 0}, {1, -3, 0}, {2, 0, 0}, {1, 3, 0}};
  mg::garbing::detail::EdgeSet shared(p.size());
  const std::vector<int> first = {0, 1, 2, 3}, second = {0, 3, 2, 1};
  for (const auto* q : {&first, &second})
    for (int i = 0; i < 4; ++i) shared.insert((*q)[i], (*q)[(i + 1) % 4]);
  std::vector<std::array<int, 3>> tris;
  ASSERT_TRUE(mg::garbing::detail::min_diagonal_triangulation(first, p, shared, tris));
  EXPECT_TRUE(shared.contains(0, 2));
  EXPECT_FALSE(shared.contains(1, 3));
  ASSERT_TRUE(mg::garbing::detail::min_diagonal_triangulation(second, p, shared, tris));
  EXPECT_TRUE(shared.contains(1, 3));
  ASSERT_EQ(tris.size(), 4u);
  for (std::size_t t = 2; t < 4; ++t) {  // the second quad's triangles both hold 1 and 3
    EXPECT_NE(std::find(tris[t].begin(), tris[t].end(), 1), tris[t].end());
    EXPECT_NE(std::find(tris[t].begin(), tris[t].end(), 3), tris[t].end());
  }

  // Chords in `avoid` are forbidden too: without its two shortest chords the hexagon takes
  // others; with every chord avoided it is refused and nothing changes.
  mg::garbing::detail::EdgeSet ring(hexagon.size()), avoid(hexagon.size());
  for (int i = 0; i < 6; ++i) ring.insert(poly[i], poly[(i + 1) % 6]);
  avoid.insert(1, 5);
  avoid.insert(2, 4);
  std::vector<std::array<int, 3>> kept;
  ASSERT_TRUE(mg::garbing::detail::min_diagonal_triangulation(poly, hexagon, ring, kept, &avoid));
  EXPECT_EQ(kept.size(), 4u);
  EXPECT_FALSE(ring.contains(1, 5));
  EXPECT_FALSE(ring.contains(2, 4));
  mg::garbing::detail::EdgeSet fresh(hexagon.size()), every_chord(hexagon.size());
  for (int i = 0; i < 6; ++i) fresh.insert(poly[i], poly[(i + 1) % 6]);
  for (int a = 0; a < 6; ++a)
    for (int b = a + 2; b < 6; ++b) every_chord.insert(a, b);
  kept.clear();
  EXPECT_FALSE(
      mg::garbing::detail::min_diagonal_triangulation(poly, hexagon, fresh, kept, &every_chord));
  EXPECT_TRUE(kept.empty());
  EXPECT_FALSE(fresh.contains(0, 3));

  // A third quad on the same four vertices has no diagonal left: refused, nothing changed.
  const std::vector<int> third = {0, 1, 2, 3};
  const std::size_t before = tris.size();
  EXPECT_FALSE(mg::garbing::detail::min_diagonal_triangulation(third, p, shared, tris));
  EXPECT_EQ(tris.size(), before);
}

TEST(RefineMesh, RefusesBadOptions) {
  const auto s = atoms({{Vector3d::Zero(), 1.0}});
  const mg::garbing::TargetShape g = mg_test::shape_of(s);
  const mg::garbing::Octree tree = mg::garbing::build_octree(g);
  const auto m1 = mg::garbing::extract_coarse_mesh(tree);
  mg::garbing::RefineOptions opt;
  opt.subdivisions = -1;
  EXPECT_THROW(mg::garbing::refine_mesh(m1, tree, g, opt), mg::InvalidInput);
  opt = {};
  opt.max_travel = 0;
  EXPECT_THROW(mg::garbing::refine_mesh(m1, tree, g, opt), mg::InvalidInput);
  opt = {};
  opt.max_gap = -1;
  EXPECT_THROW(mg::garbing::refine_mesh(m1, tree, g, opt), mg::InvalidInput);
  opt = {};
  opt.gap_rounds = -1;
  EXPECT_THROW(mg::garbing::refine_mesh(m1, tree, g, opt), mg::InvalidInput);
  // The tree must come from this G.
  const mg::garbing::TargetShape other = mg_test::shape_of(atoms({{Vector3d(5, 0, 0), 2.0}}));
  EXPECT_THROW(mg::garbing::refine_mesh(m1, tree, other), mg::InvalidInput);
  mg::garbing::ConeOptions cones;
  cones.min_circle_ratio = 2;
  EXPECT_THROW(mg_test::shape_of(s, cones), mg::InvalidInput);
}

}  // namespace

namespace {

/// Every cone kept, however deep its crease: the octree wraps the cones too, so M1 lies
/// outside G over the creases and the migration lands every vertex on G, within a leaf of
/// where it started, with (almost) nothing to repair. Before the octree wrapped the cones,
/// this blob folded into thousands of intersecting pairs that the repair left off G.
TEST(RefineMesh, DeepCreasesOfEveryConeLandOnG) {
  const auto s = mg_test::blob(30, 0.05, 0.3, 3);
  const mg::garbing::TargetShape g = mg_test::shape_of(s, every_cone());
  const mg::garbing::Octree tree = mg::garbing::build_octree(g, coarse());
  long crease_leaves = 0;
  for (int c : tree.leaves)
    crease_leaves += tree.cells[c].is_active() && tree.cells[c].spheres.empty();
  ASSERT_GT(crease_leaves, 100);
  const auto m2 = mg::garbing::refine_mesh(mg::garbing::extract_coarse_mesh(tree), tree, g);
  expect_sound(m2.mesh, "blob, every cone");
  std::cout << "intersecting before repair " << m2.stats.intersecting_before << ", left off G "
            << m2.stats.left_off_g << ", crease leaves " << crease_leaves << "\n";
  EXPECT_EQ(m2.stats.left_off_g, 0u);
  const mg::garbing::TargetShape shape = mg::garbing::make_target_shape(s, every_cone());
  const double leaf = tree.side(tree.min_depth);
  double worst = 0;
  for (const Vector3d& p : points(m2.mesh)) worst = std::max(worst, shape.distance(p));
  EXPECT_LT(worst, 1e-9 * leaf);
}

}  // namespace
