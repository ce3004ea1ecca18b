#include "core/triangle_defects.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/intersections.h>
#include <gtest/gtest.h>

#include <boost/variant/get.hpp>

#include <numeric>
#include <random>

namespace {

/// Random triangles over a shared pool of points (so many share a vertex or an edge), most
/// small, a few spanning the whole cube, a few degenerate.
mg::PolygonSoup random_soup(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0, 1), small(-0.05, 0.05);
  std::uniform_int_distribution<int> pick(0, 299);
  mg::PolygonSoup soup;
  for (int i = 0; i < 300; ++i) soup.points.emplace_back(unit(rng), unit(rng), unit(rng));
  for (int f = 0; f < 600; ++f) {
    if (f % 40 == 0) {  // large: over the whole cube
      soup.faces.push_back({pick(rng), pick(rng), pick(rng)});
    } else if (f % 97 == 0) {  // degenerate: a corner twice (as another point)
      const int a = pick(rng), b = pick(rng);
      soup.points.push_back(soup.points[a]);
      soup.faces.push_back({a, b, static_cast<int>(soup.points.size()) - 1});
    } else {  // small, near a pool point, sometimes sharing one
      const int a = pick(rng);
      const Eigen::Vector3d c = soup.points[a];
      const int n = static_cast<int>(soup.points.size());
      soup.points.emplace_back(c + Eigen::Vector3d(small(rng), small(rng), small(rng)));
      soup.points.emplace_back(c + Eigen::Vector3d(small(rng), small(rng), small(rng)));
      soup.faces.push_back({f % 3 == 0 ? a : n + 1, n, f % 3 == 0 ? n + 1 : a});
    }
  }
  return soup;
}

/// The full check's parallel grid broad phase against the subset check over every face,
/// which runs CGAL's box intersection: the same pairs, on soups with hundreds of them.
TEST(TriangleDefects, FullCheckMatchesTheSubsetCheckOverEveryFace) {
  for (unsigned seed : {1u, 2u, 3u}) {
    const mg::PolygonSoup soup = random_soup(seed);
    std::vector<int> all(soup.faces.size());
    std::iota(all.begin(), all.end(), 0);
    const mg::TriangleDefects full = mg::find_triangle_defects(soup);
    const mg::TriangleDefects reference = mg::find_triangle_defects(soup, all);
    EXPECT_GT(full.intersecting_pairs.size(), 100u) << seed;
    EXPECT_EQ(full.intersecting_pairs, reference.intersecting_pairs) << seed;
    EXPECT_FALSE(full.degenerate_faces.empty()) << seed;
    EXPECT_EQ(full.degenerate_faces, reference.degenerate_faces) << seed;
    // A subset's result is the full result restricted to the pairs touching it; small faces
    // only, so the subset's grid filter leaves most faces out.
    const std::vector<int> some = {3, 5, 77, 123, 401};
    const mg::TriangleDefects part = mg::find_triangle_defects(soup, some);
    std::vector<std::array<int, 2>> expected;
    for (const auto& p : full.intersecting_pairs)
      if (std::count(some.begin(), some.end(), p[0]) || std::count(some.begin(), some.end(), p[1]))
        expected.push_back(p);
    EXPECT_FALSE(expected.empty()) << seed;
    EXPECT_EQ(part.intersecting_pairs, expected) << seed;
  }
}

/// An oracle of its own: every pair of triangles, their exact intersection constructed (CGAL
/// Epeck) and compared with what their indices share. A pair intersects improperly when the
/// intersection holds more than the shared vertex or edge: any point at all for disjoint
/// indices, a point other than the shared vertex, anything but the shared edge itself.
/// Degenerate triangles (collinear corners) are left out, as find_triangle_defects does.
std::vector<std::array<int, 2>> brute_force_pairs(const mg::PolygonSoup& soup) {
  using K = CGAL::Epeck;
  auto point = [&](int v) {
    return K::Point_3(soup.points[v].x(), soup.points[v].y(), soup.points[v].z());
  };
  auto triangle = [&](int f) {
    const auto& t = soup.faces[f];
    return K::Triangle_3(point(t[0]), point(t[1]), point(t[2]));
  };
  std::vector<char> degenerate(soup.faces.size());
  for (std::size_t f = 0; f < soup.faces.size(); ++f)
    degenerate[f] = triangle(static_cast<int>(f)).is_degenerate();
  std::vector<std::array<int, 2>> out;
  for (int f = 0; f < static_cast<int>(soup.faces.size()); ++f) {
    if (degenerate[f]) continue;
    for (int g = f + 1; g < static_cast<int>(soup.faces.size()); ++g) {
      if (degenerate[g]) continue;
      std::vector<int> shared;
      for (int a : soup.faces[f])
        for (int b : soup.faces[g])
          if (a == b) shared.push_back(a);
      const auto hit = CGAL::intersection(triangle(f), triangle(g));
      if (!hit) continue;
      bool improper = true;
      if (const K::Point_3* p = boost::get<K::Point_3>(&*hit)) {
        improper = !(shared.size() >= 1 && std::any_of(shared.begin(), shared.end(),
                                                       [&](int v) { return *p == point(v); }));
      } else if (const K::Segment_3* e = boost::get<K::Segment_3>(&*hit)) {
        improper = !(shared.size() == 2 &&
                     ((e->source() == point(shared[0]) && e->target() == point(shared[1])) ||
                      (e->source() == point(shared[1]) && e->target() == point(shared[0]))));
      }  // a triangle or a polygon: an overlap, improper whatever is shared
      if (improper) out.push_back({f, g});
    }
  }
  return out;
}

TEST(TriangleDefects, MatchesTheBruteForceOracleOfExactIntersections) {
  for (unsigned seed : {1u, 2u}) {
    const mg::PolygonSoup soup = random_soup(seed);
    const auto expected = brute_force_pairs(soup);
    EXPECT_GT(expected.size(), 100u) << seed;
    EXPECT_EQ(mg::find_triangle_defects(soup).intersecting_pairs, expected) << seed;
  }
}

TEST(TriangleDefects, TouchingAndOverlappingCasesMatchTheOracle) {
  // Hand-made pairs around one triangle: sharing a vertex and crossing elsewhere, sharing a
  // vertex and meeting nowhere else, sharing an edge and folding onto it (coplanar, same
  // side), sharing an edge on the other side, touching at a vertex by position only, and the
  // same triangle listed twice.
  mg::PolygonSoup soup;
  soup.points = {{0, 0, 0},    {1, 0, 0},     {0, 1, 0}, {0.2, 0.2, -1}, {0.2, 0.2, 1}, {-1, -1, 1},
                 {-1, 0.5, 0}, {0.3, 0.3, 0}, {1, 1, 0}, {0, 0, 1},      {2, 0, 0},     {2, 1, 0}};
  soup.faces = {{0, 1, 2}, {0, 3, 4},   {0, 5, 6}, {0, 1, 7},
                {1, 2, 8}, {1, 10, 11}, {9, 1, 2}, {0, 1, 2}};
  const auto expected = brute_force_pairs(soup);
  EXPECT_EQ(mg::find_triangle_defects(soup).intersecting_pairs, expected);
  // Faces 1 (through the plane at (0.2, 0.2)), 3 (folded over face 0) and 7 (face 0 again)
  // meet face 0 improperly; 2, 4, 5 and 6 do not.
  for (const std::array<int, 2> p : {std::array<int, 2>{0, 1}, {0, 3}, {0, 7}})
    EXPECT_TRUE(std::find(expected.begin(), expected.end(), p) != expected.end())
        << p[0] << ", " << p[1];
  for (int g : {2, 4, 5, 6})
    EXPECT_TRUE(std::find(expected.begin(), expected.end(), std::array<int, 2>{0, g}) ==
                expected.end())
        << g;
}

TEST(TriangleDefects, SharedEdgesAndVerticesAreNotIntersections) {
  mg::PolygonSoup soup;
  soup.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 0}};
  soup.faces = {{0, 1, 2}, {0, 3, 1}, {1, 4, 2}, {0, 2, 3}};
  EXPECT_TRUE(mg::find_triangle_defects(soup).intersecting_pairs.empty());
  soup.points.push_back({0.25, 0.25, 0});  // a fold: a triangle over face 0, sharing its edge 0-1
  soup.faces.push_back({1, 0, 5});
  const auto d = mg::find_triangle_defects(soup);
  ASSERT_EQ(d.intersecting_pairs.size(), 1u);
  EXPECT_EQ(d.intersecting_pairs[0], (std::array<int, 2>{0, 4}));
}

}  // namespace
