// CGAL translation unit of the geometric checks: box intersection and exact triangle predicates.
#include "evaluate/mesh_checks.h"

#include "evaluate/distances.h"
#include "garbing/detail/cgal_conversions.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace mg::evaluate {
namespace {

using Kernel = CGAL::Epick;
using Point = Kernel::Point_3;
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, std::size_t>;

constexpr double kDegrees = 57.29577951308232;  // 180 / pi

struct Tri {
  std::array<int, 3> v;
  std::array<Point, 3> p;
  Kernel::Triangle_3 triangle() const { return {p[0], p[1], p[2]}; }
};

/// Whether two non-degenerate triangles intersect other than along what their indices share.
bool improper_intersection(const Tri& a, const Tri& b) {
  int shared = 0;
  int ia = -1, ib = -1;  // a corner of a / b that the other does not share (last found)
  std::array<bool, 3> a_shared{}, b_shared{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (a.v[i] == b.v[j]) {
        ++shared;
        a_shared[i] = b_shared[j] = true;
      }
  for (int i = 0; i < 3; ++i) {
    if (!a_shared[i]) ia = i;
    if (!b_shared[i]) ib = i;
  }
  switch (shared) {
    case 0:
      return CGAL::do_intersect(a.triangle(), b.triangle());
    case 1: {
      // They meet at the shared vertex; anything more shows as the opposite edge of one
      // crossing the other triangle.
      std::array<int, 2> ea{}, eb{};
      int na = 0, nb = 0;
      for (int i = 0; i < 3; ++i) {
        if (!a_shared[i]) ea[na++] = i;
        if (!b_shared[i]) eb[nb++] = i;
      }
      const Kernel::Segment_3 sa(a.p[ea[0]], a.p[ea[1]]), sb(b.p[eb[0]], b.p[eb[1]]);
      return CGAL::do_intersect(sa, b.triangle()) || CGAL::do_intersect(sb, a.triangle());
    }
    case 2: {
      // Sharing an edge pq: they overlap iff coplanar with the free corners on the same side.
      int p = -1, q = -1;
      for (int i = 0; i < 3; ++i)
        if (a_shared[i]) (p < 0 ? p : q) = i;
      const Point &pp = a.p[p], &pq = a.p[q], &r = a.p[ia], &s = b.p[ib];
      return CGAL::coplanar(pp, pq, r, s) &&
             CGAL::coplanar_orientation(pp, pq, r, s) == CGAL::POSITIVE;
    }
    default:
      return true;  // the same three vertices: a duplicated face
  }
}

}  // namespace

MeshCheck check_mesh(const PolygonSoup& soup) {
  MeshCheck c;
  c.topology = mesh_topology(soup);
  for (const auto& f : soup.faces)
    if (f.size() > 3) ++c.non_triangle_faces;

  const Triangles fan = fan_triangles(soup);
  c.triangles = fan.corners.size();
  std::vector<Tri> tris;
  std::vector<std::size_t> face_of;
  std::vector<Box> boxes;
  double min_angle = 180;
  for (std::size_t i = 0; i < fan.corners.size(); ++i) {
    Tri t;
    t.v = fan.corners[i];
    for (int k = 0; k < 3; ++k) t.p[k] = detail::to_cgal_point<Kernel>(soup.points[t.v[k]]);
    if (CGAL::collinear(t.p[0], t.p[1], t.p[2])) {
      if (c.degenerate_triangles++ == 0)
        c.first_degenerate =
            "face " + std::to_string(fan.face[i]) + " is degenerate (collinear corners)";
      continue;
    }
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d e1 = soup.points[t.v[(k + 1) % 3]] - soup.points[t.v[k]];
      const Eigen::Vector3d e2 = soup.points[t.v[(k + 2) % 3]] - soup.points[t.v[k]];
      min_angle = std::min(min_angle, kDegrees * std::atan2(e1.cross(e2).norm(), e1.dot(e2)));
    }
    boxes.emplace_back(t.triangle().bbox(), tris.size());
    tris.push_back(t);
    face_of.push_back(fan.face[i]);
  }
  c.min_angle_deg = tris.empty() ? 0.0 : min_angle;

  // Candidate pairs: overlapping closed boxes, pairs within one polygon excluded.
  std::vector<std::pair<std::size_t, std::size_t>> candidates;
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& a, const Box& b) {
    const std::size_t i = std::min(a.info(), b.info()), j = std::max(a.info(), b.info());
    if (face_of[i] != face_of[j]) candidates.emplace_back(i, j);
  });
  std::vector<char> hit(candidates.size(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, candidates.size(), 256),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t k = r.begin(); k != r.end(); ++k)
                        hit[k] = improper_intersection(tris[candidates[k].first],
                                                       tris[candidates[k].second]);
                    });
  std::vector<std::pair<std::size_t, std::size_t>> face_pairs;
  for (std::size_t k = 0; k < candidates.size(); ++k)
    if (hit[k]) {
      const std::size_t fa = face_of[candidates[k].first], fb = face_of[candidates[k].second];
      face_pairs.emplace_back(std::min(fa, fb), std::max(fa, fb));
    }
  std::sort(face_pairs.begin(), face_pairs.end());
  face_pairs.erase(std::unique(face_pairs.begin(), face_pairs.end()), face_pairs.end());
  c.intersecting_pairs = face_pairs.size();
  if (!face_pairs.empty())
    c.first_intersection = "faces " + std::to_string(face_pairs.front().first) + " and " +
                           std::to_string(face_pairs.front().second) + " intersect";

  // Valence: distinct neighbours through the faces' sides.
  std::vector<std::pair<int, int>> edges;
  for (const auto& f : soup.faces)
    for (std::size_t i = 0; i < f.size(); ++i) {
      const int a = f[i], b = f[(i + 1) % f.size()];
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<std::size_t> valence(soup.points.size(), 0);
  for (const auto& [a, b] : edges) {
    ++valence[a];
    ++valence[b];
  }
  for (std::size_t v : valence)
    if (v > 0) ++c.valence_histogram[v];
  return c;
}

}  // namespace mg::evaluate
