// find_triangle_defects(): the CGAL translation unit of mg::garbing for exact triangle tests.
#include "garbing/triangle_defects.h"

#include "garbing/detail/box_grid.h"
#include "garbing/errors.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>
#include <tbb/parallel_for.h>

#include <algorithm>

namespace mg {
namespace {

using K = CGAL::Epick;
using Point = K::Point_3;
using Triangle = K::Triangle_3;
using Segment = K::Segment_3;
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, int>;

}  // namespace

namespace {

TriangleDefects find_defects(const PolygonSoup& soup, const std::vector<int>* subset) {
  const int n = static_cast<int>(soup.points.size());
  std::vector<Point> points;
  points.reserve(soup.points.size());
  for (const auto& p : soup.points) points.emplace_back(p.x(), p.y(), p.z());
  for (std::size_t f = 0; f < soup.faces.size(); ++f) {
    if (soup.faces[f].size() != 3)
      throw InvalidInput("face " + std::to_string(f) + " is not a triangle");
    for (int v : soup.faces[f])
      if (v < 0 || v >= n) throw InvalidInput("face " + std::to_string(f) + ": index out of range");
  }
  auto corner = [&](int f, int k) { return points[soup.faces[f][k]]; };

  TriangleDefects out;
  std::vector<Box> boxes, chosen;
  std::vector<char> in_subset(soup.faces.size(), subset ? 0 : 1);
  if (subset)
    for (int f : *subset) in_subset[f] = 1;
  std::vector<CGAL::Bbox_3> bbox(soup.faces.size());
  for (std::size_t f = 0; f < soup.faces.size(); ++f) {
    const int i = static_cast<int>(f);
    bbox[f] = corner(i, 0).bbox() + corner(i, 1).bbox() + corner(i, 2).bbox();
  }
  // A local change (subset): only the boxes near the subset's can pair with them.
  auto eigen_box = [](const CGAL::Bbox_3& b) {
    return Eigen::AlignedBox3d(Eigen::Vector3d(b.xmin(), b.ymin(), b.zmin()), Eigen::Vector3d(b.xmax(), b.ymax(), b.zmax()));
  };
  std::vector<Eigen::AlignedBox3d> probes;
  if (subset)
    for (int f : *subset) probes.push_back(eigen_box(bbox[f]));
  const detail::BoxGrid grid(probes);
  for (std::size_t f = 0; f < soup.faces.size(); ++f) {
    const int i = static_cast<int>(f);
    if (!in_subset[f] && !grid.near(eigen_box(bbox[f]))) continue;
    if (CGAL::collinear(corner(i, 0), corner(i, 1), corner(i, 2))) {
      if (in_subset[f]) out.degenerate_faces.push_back(i);
      continue;
    }
    boxes.emplace_back(bbox[f], i);
    if (subset && in_subset[f]) chosen.emplace_back(bbox[f], i);
  }

  auto intersect = [&](int f, int g) {
    const auto& a = soup.faces[f];
    const auto& b = soup.faces[g];
    int shared = 0, fa[3], gb[3];  // positions of shared vertices
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (a[i] == b[j]) {
          fa[shared] = i;
          gb[shared] = j;
          ++shared;
        }
    const Triangle tf(corner(f, 0), corner(f, 1), corner(f, 2));
    const Triangle tg(corner(g, 0), corner(g, 1), corner(g, 2));
    if (shared == 0) return CGAL::do_intersect(tf, tg);
    if (shared == 3) return true;  // the same triangle twice
    if (shared == 2) {
      // Sharing an edge: they overlap only if coplanar with the opposite corners on one side.
      const Point& p = corner(f, fa[0]);
      const Point& q = corner(f, fa[1]);
      const Point& r = corner(f, 3 - fa[0] - fa[1]);
      const Point& s = corner(g, 3 - gb[0] - gb[1]);
      return CGAL::coplanar(p, q, r, s) && CGAL::coplanar_orientation(p, q, r, s) == CGAL::POSITIVE;
    }
    // Sharing one vertex: they meet elsewhere iff an opposite edge meets the other triangle.
    const Segment opposite_f(corner(f, (fa[0] + 1) % 3), corner(f, (fa[0] + 2) % 3));
    const Segment opposite_g(corner(g, (gb[0] + 1) % 3), corner(g, (gb[0] + 2) % 3));
    return CGAL::do_intersect(opposite_f, tg) || CGAL::do_intersect(opposite_g, tf);
  };

  // Candidate pairs from the boxes (sequential), then the exact tests in parallel; the pairs
  // come out sorted whatever the thread count.
  std::vector<std::array<int, 2>> candidates;
  auto report = [&](const Box& x, const Box& y) {
    if (x.info() == y.info()) return;
    candidates.push_back({std::min(x.info(), y.info()), std::max(x.info(), y.info())});
  };
  if (subset) {
    CGAL::box_intersection_d(chosen.begin(), chosen.end(), boxes.begin(), boxes.end(), report);
  }
  else
    CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), report);
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  std::vector<char> hit(candidates.size(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, candidates.size(), 1024),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i)
                        hit[i] = intersect(candidates[i][0], candidates[i][1]) ? 1 : 0;
                    });
  for (std::size_t i = 0; i < candidates.size(); ++i)
    if (hit[i]) out.intersecting_pairs.push_back(candidates[i]);
  return out;
}

}  // namespace

TriangleDefects find_triangle_defects(const PolygonSoup& soup) { return find_defects(soup, nullptr); }

TriangleDefects find_triangle_defects(const PolygonSoup& soup, const std::vector<int>& subset) {
  return find_defects(soup, &subset);
}

}  // namespace mg
