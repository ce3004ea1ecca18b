// find_triangle_defects(): the CGAL translation unit of mg::garbing for exact triangle tests.
#include "core/triangle_defects.h"

#include "core/detail/box_grid.h"
#include "core/errors.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>
#include <CGAL/intersections.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>

#include <algorithm>
#include <cstdint>

namespace mg {
namespace {

using K = CGAL::Epick;
using Point = K::Point_3;
using Triangle = K::Triangle_3;
using Segment = K::Segment_3;
using Box = CGAL::Box_intersection_d::Box_with_info_d<double, 3, int>;

/// Every pair (f < g) of the faces `ids` whose closed boxes (`boxes`, by face) overlap and that
/// pass `test(f, g)`, sorted: the full check's broad phase with its narrow phase run in place
/// (no list of the overlapping pairs, which outnumber the triangles tenfold), in parallel. A
/// grid of cells as large as the 90th percentile of the boxes' largest sides; each box is
/// listed in the cells it overlaps (one over more than 64 cells is tested against every box
/// instead), and an overlapping pair is tested only in the cell holding the low corner of the
/// two boxes' intersection, so once (and a big box's pairs only from the big box, or the
/// smaller index when both are big).
template <class Test>
std::vector<std::array<int, 2>> overlapping_pairs(
    const std::vector<Eigen::AlignedBox3d>& face_boxes, const std::vector<int>& ids,
    const Test& test) {
  std::vector<std::array<int, 2>> out;
  if (ids.size() < 2) return out;
  std::vector<double> extent(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) extent[i] = face_boxes[ids[i]].sizes().maxCoeff();
  const auto nth = extent.begin() + static_cast<std::ptrdiff_t>(extent.size() * 9 / 10);
  std::nth_element(extent.begin(), nth, extent.end());
  const double h = *nth;  // > 0: a triangle that is not degenerate has distinct corners
  auto box = [&](std::size_t b) -> const Eigen::AlignedBox3d& { return face_boxes[ids[b]]; };
  auto pair_of = [&](std::size_t x, std::size_t y) {
    return std::array<int, 2>{std::min(ids[x], ids[y]), std::max(ids[x], ids[y])};
  };
  std::vector<std::array<std::int64_t, 6>> range(ids.size());
  std::vector<std::size_t> start(ids.size() + 1, 0);
  std::vector<std::size_t>
      big;  // over more than 64 cells (or not finite): tested against every box
  for (std::size_t b = 0; b < ids.size(); ++b) {
    auto& r = range[b];
    const bool gridded = detail::cell_range(box(b), h, &r[0], &r[3]);
    if (!gridded) big.push_back(b);
    start[b + 1] =
        start[b] + (gridded ? static_cast<std::size_t>((r[3] - r[0] + 1) * (r[4] - r[1] + 1) *
                                                       (r[5] - r[2] + 1))
                            : 0);
  }
  std::vector<std::pair<std::uint64_t, int>> entries(start.back());  // (cell, box position)
  tbb::parallel_for(std::size_t(0), ids.size(), [&](std::size_t b) {
    if (start[b + 1] == start[b]) return;
    const auto& r = range[b];
    std::size_t e = start[b];
    for (std::int64_t i = r[0]; i <= r[3]; ++i)
      for (std::int64_t j = r[1]; j <= r[4]; ++j)
        for (std::int64_t k = r[2]; k <= r[5]; ++k)
          entries[e++] = {detail::cell_key(i, j, k), static_cast<int>(b)};
  });
  tbb::parallel_sort(entries.begin(), entries.end());
  std::vector<std::size_t> runs;
  for (std::size_t e = 0; e < entries.size(); ++e)
    if (e == 0 || entries[e].first != entries[e - 1].first) runs.push_back(e);
  runs.push_back(entries.size());
  tbb::enumerable_thread_specific<std::vector<std::array<int, 2>>> found;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, runs.size() - 1, 64),
                    [&](const tbb::blocked_range<std::size_t>& rr) {
                      auto& mine = found.local();
                      for (std::size_t r = rr.begin(); r != rr.end(); ++r) {
                        const std::uint64_t here = entries[runs[r]].first;
                        for (std::size_t x = runs[r]; x < runs[r + 1]; ++x)
                          for (std::size_t y = x + 1; y < runs[r + 1]; ++y) {
                            const std::size_t bx = entries[x].second, by = entries[y].second;
                            if (!box(bx).intersects(box(by))) continue;
                            // The overlap's low corner lies in both boxes' cell ranges: its cell is
                            // one of theirs.
                            std::int64_t c[3];
                            for (int a = 0; a < 3; ++a) c[a] = std::max(range[bx][a], range[by][a]);
                            const std::uint64_t low = detail::cell_key(c[0], c[1], c[2]);
                            if (low != here) continue;
                            const auto pair = pair_of(bx, by);
                            if (test(pair[0], pair[1])) mine.push_back(pair);
                          }
                      }
                    });
  std::vector<char> is_big(ids.size(), 0);
  for (std::size_t b : big) is_big[b] = 1;
  tbb::parallel_for(std::size_t(0), big.size(), [&](std::size_t i) {
    auto& mine = found.local();
    const std::size_t bx = big[i];
    for (std::size_t by = 0; by < ids.size(); ++by) {
      if (by == bx || (is_big[by] && by < bx) || !box(bx).intersects(box(by))) continue;
      const auto pair = pair_of(bx, by);
      if (test(pair[0], pair[1])) mine.push_back(pair);
    }
  });
  for (auto& part : found) out.insert(out.end(), part.begin(), part.end());
  tbb::parallel_sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

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
  std::vector<char> in_subset(soup.faces.size(), subset ? 0 : 1);
  if (subset)
    for (int f : *subset) in_subset[f] = 1;
  std::vector<Eigen::AlignedBox3d> box(soup.faces.size());
  for (std::size_t f = 0; f < soup.faces.size(); ++f) {
    box[f] = Eigen::AlignedBox3d(soup.points[soup.faces[f][0]]);
    box[f].extend(soup.points[soup.faces[f][1]]).extend(soup.points[soup.faces[f][2]]);
  }
  // A local change (subset): only the boxes near the subset's can pair with them.
  std::vector<Eigen::AlignedBox3d> probes;
  if (subset)
    for (int f : *subset) probes.push_back(box[f]);
  const detail::BoxGrid grid(probes);
  std::vector<int> kept;  // the faces that take part: not degenerate (and near, for a subset)
  for (std::size_t f = 0; f < soup.faces.size(); ++f) {
    const int i = static_cast<int>(f);
    if (!in_subset[f] && !grid.near(box[f])) continue;
    if (CGAL::collinear(corner(i, 0), corner(i, 1), corner(i, 2))) {
      if (in_subset[f]) out.degenerate_faces.push_back(i);
      continue;
    }
    kept.push_back(i);
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
    // When one triangle's two other corners lie strictly on one side of the other's plane, the
    // triangle leaves that plane at the shared vertex: they meet there only (exact test first).
    const Point& fp = corner(f, (fa[0] + 1) % 3);
    const Point& fq = corner(f, (fa[0] + 2) % 3);
    const Point& gp = corner(g, (gb[0] + 1) % 3);
    const Point& gq = corner(g, (gb[0] + 2) % 3);
    const Point& shared_point = corner(f, fa[0]);
    auto one_side = [](const Point& p0, const Point& p1, const Point& p2, const Point& x,
                       const Point& y) {
      const CGAL::Orientation ox = CGAL::orientation(p0, p1, p2, x);
      return ox != CGAL::COPLANAR && ox == CGAL::orientation(p0, p1, p2, y);
    };
    if (one_side(shared_point, fp, fq, gp, gq) || one_side(shared_point, gp, gq, fp, fq))
      return false;
    const Segment opposite_f(fp, fq);
    const Segment opposite_g(gp, gq);
    return CGAL::do_intersect(opposite_f, tg) || CGAL::do_intersect(opposite_g, tf);
  };

  // Candidate pairs from the boxes, then the exact tests in parallel; the pairs come out
  // sorted whatever the thread count.
  if (!subset) {
    out.intersecting_pairs = overlapping_pairs(box, kept, intersect);
    return out;
  }
  std::vector<std::array<int, 2>> candidates;
  {
    auto cgal_box = [&](int f) {
      const auto& b = box[f];
      return Box(CGAL::Bbox_3(b.min().x(), b.min().y(), b.min().z(), b.max().x(), b.max().y(),
                              b.max().z()),
                 f);
    };
    std::vector<Box> boxes, chosen;
    for (int f : kept) {
      boxes.push_back(cgal_box(f));
      if (in_subset[f]) chosen.push_back(cgal_box(f));
    }
    CGAL::box_intersection_d(
        chosen.begin(), chosen.end(), boxes.begin(), boxes.end(), [&](const Box& x, const Box& y) {
          if (x.info() != y.info())
            candidates.push_back({std::min(x.info(), y.info()), std::max(x.info(), y.info())});
        });
    std::sort(candidates.begin(), candidates.end());
    candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  }
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

TriangleDefects find_triangle_defects(const PolygonSoup& soup) {
  return find_defects(soup, nullptr);
}

TriangleDefects find_triangle_defects(const PolygonSoup& soup, const std::vector<int>& subset) {
  return find_defects(soup, &subset);
}

}  // namespace mg
