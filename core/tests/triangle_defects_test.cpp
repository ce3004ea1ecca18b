#include "core/triangle_defects.h"

#include <gtest/gtest.h>

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
      if (std::count(some.begin(), some.end(), p[0]) || std::count(some.begin(), some.end(), p[1])) expected.push_back(p);
    EXPECT_FALSE(expected.empty()) << seed;
    EXPECT_EQ(part.intersecting_pairs, expected) << seed;
  }
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
