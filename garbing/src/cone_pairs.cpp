// cone_pairs(): which pairs of atoms get a cone. The one CGAL translation unit of mg::garbing.
#include "core/detail/cgal_conversions.h"
#include "core/errors.h"
#include "garbing/detail/regular_edges.h"
#include "garbing/target_shape.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Regular_triangulation_3.h>
#include <CGAL/Regular_triangulation_cell_base_3.h>
#include <CGAL/Regular_triangulation_vertex_base_3.h>
#include <CGAL/Spatial_lock_grid_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <tuple>

namespace mg::garbing {
namespace {

using K = CGAL::Epick;
using Vb =
    CGAL::Triangulation_vertex_base_with_info_3<int, K,
                                                CGAL::Regular_triangulation_vertex_base_3<K>>;
// Hidden points are not kept: only the edges are read, and keeping them costs a list per cell.
using Cb = CGAL::Regular_triangulation_cell_base_3<K, CGAL::Triangulation_cell_base_3<K>,
                                                   CGAL::Discard_hidden_points>;
// Built in parallel (TBB, CGAL's lock grid): CGAL perturbs ties symbolically, so the regular
// triangulation of a set of distinct weighted points is one, whatever the insertion order.
using Tds = CGAL::Triangulation_data_structure_3<Vb, Cb, CGAL::Parallel_tag>;
using Regular =
    CGAL::Regular_triangulation_3<K, Tds, CGAL::Spatial_lock_grid_3<CGAL::Tag_priority_blocking>>;

}  // namespace

/// Hidden atoms (whose power cell is empty) have no vertex and no edge; of atoms whose
/// weighted points are equal (centre and r^2), only the first (lowest index) is inserted, so which
/// of them carries the vertex does not depend on the threads' order.
std::vector<std::array<int, 2>> detail::regular_edges(const MedialSurface& atoms) {
  const std::size_t count = atoms.atoms.size();
  std::vector<int> order(count);
  for (std::size_t i = 0; i < count; ++i) order[i] = static_cast<int>(i);
  auto ball = [&](int i) {
    const MedialAtom& a = atoms.atoms[static_cast<std::size_t>(i)];
    return std::make_tuple(a.centre.x(), a.centre.y(), a.centre.z(), a.radius * a.radius);
  };
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return std::make_pair(ball(a), a) < std::make_pair(ball(b), b); });
  // The first of each run of equal balls (the lowest index) is kept; the points go to CGAL in
  // input order (it sorts them spatially itself).
  std::vector<std::uint8_t> first_of_its_ball(count, 0);
  for (std::size_t x = 0; x < count; ++x)
    first_of_its_ball[order[x]] = x == 0 || ball(order[x]) != ball(order[x - 1]);
  std::vector<std::pair<Regular::Weighted_point, int>> points;
  points.reserve(count);
  CGAL::Bbox_3 box;
  for (std::size_t i = 0; i < count; ++i) {
    if (!first_of_its_ball[i]) continue;
    const MedialAtom& a = atoms.atoms[i];
    points.emplace_back(mg::detail::to_weighted_point<K>(a), static_cast<int>(i));
    box += CGAL::Bbox_3(a.centre.x(), a.centre.y(), a.centre.z(), a.centre.x(), a.centre.y(),
                        a.centre.z());
  }
  Regular::Lock_data_structure locks(box, 50);
  auto rt = std::make_unique<Regular>(points.begin(), points.end(), &locks);
  std::vector<std::pair<Regular::Weighted_point, int>>().swap(points);
  std::vector<std::uint8_t>().swap(first_of_its_ball);
  std::vector<int>().swap(order);
  // The six edges of every finite cell, bucketed by their lower atom and each kept once.
  // (CGAL's edge iterator turns around every edge to visit it once, and
  // number_of_finite_edges() runs it too: most of this function's time when it was used.) A
  // triangulation of fewer than four points has no cell: its edges come from the iterator.
  std::vector<std::array<int, 2>> edges;
  if (rt->dimension() < 3) {
    for (auto e = rt->finite_edges_begin(); e != rt->finite_edges_end(); ++e) {
      int a = e->first->vertex(e->second)->info(), b = e->first->vertex(e->third)->info();
      if (a > b) std::swap(a, b);
      edges.push_back({a, b});
    }
    std::sort(edges.begin(), edges.end());
    return edges;
  }
  const std::size_t n = atoms.atoms.size();
  // The finite cells' atoms, read in one pass over CGAL's cells (in memory order: random
  // access to them was the slow part), then the triangulation goes and the edges are gathered
  // from the flat array in parallel: 16 bytes a cell (104 MB at a million atoms) against the
  // triangulation's ~120 B. Each cell lists an edge once per cell around it (about five
  // times): the upper atoms are bucketed by lower atom, then sorted and counted once each.
  std::vector<std::array<int, 4>> cells;
  cells.reserve(rt->number_of_cells());  // the infinite ones included: a bound, O(1)
  for (auto c = rt->finite_cells_begin(); c != rt->finite_cells_end(); ++c)
    cells.push_back(
        {c->vertex(0)->info(), c->vertex(1)->info(), c->vertex(2)->info(), c->vertex(3)->info()});
  rt.reset();
  // In parallel over the cells: the order in which a bucket fills is the threads', but each
  // bucket is sorted below, so the edges are the same at any thread count.
  auto each_edge = [&](auto&& f) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells.size(), 1 << 14),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t c = r.begin(); c != r.end(); ++c) {
                          const auto& v = cells[c];
                          for (int i = 0; i < 4; ++i)
                            for (int j = i + 1; j < 4; ++j)
                              f(std::min(v[i], v[j]), std::max(v[i], v[j]));
                        }
                      });
  };
  std::vector<std::size_t> start(n + 1, 0);
  each_edge([&](int a, int) { __atomic_fetch_add(&start[a + 1], 1, __ATOMIC_RELAXED); });
  for (std::size_t a = 1; a < start.size(); ++a) start[a] += start[a - 1];
  std::vector<int> upper(start[n]);
  {
    std::vector<std::size_t> fill(start.begin(), start.end() - 1);
    each_edge([&](int a, int b) { upper[__atomic_fetch_add(&fill[a], 1, __ATOMIC_RELAXED)] = b; });
  }
  std::vector<std::array<int, 4>>().swap(cells);
  // Per atom, in parallel: its upper neighbours counted once each and sorted, then written. A
  // bucket holds about 39 entries for 8 distinct atoms: the repeats go by a scan of those kept
  // so far (no memory per thread), a long bucket (a large ball's) by sort and unique.
  std::vector<std::size_t> distinct(n + 1, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t a = r.begin(); a != r.end(); ++a) {
                        const auto first = upper.begin() + static_cast<long>(start[a]);
                        const auto end = upper.begin() + static_cast<long>(start[a + 1]);
                        auto last = first;
                        if (end - first <= 256) {
                          for (auto b = first; b != end; ++b)
                            if (std::find(first, last, *b) == last) *last++ = *b;
                          std::sort(first, last);
                        } else {
                          std::sort(first, end);
                          last = std::unique(first, end);
                        }
                        distinct[a + 1] = static_cast<std::size_t>(last - first);
                      }
                    });
  for (std::size_t a = 0; a < n; ++a) distinct[a + 1] += distinct[a];
  edges.resize(distinct[n]);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t a = r.begin(); a != r.end(); ++a)
                        for (std::size_t k = distinct[a]; k < distinct[a + 1]; ++k)
                          edges[k] = {static_cast<int>(a), upper[start[a] + k - distinct[a]]};
                    });
  return edges;
}

namespace {

/// Every pair of intersecting balls, found through the primitives' hierarchy.
std::vector<std::array<int, 2>> intersecting_pairs(const MedialSurface& atoms) {
  const TargetShape spheres(atoms, {});
  std::vector<std::array<int, 2>> pairs;
  std::vector<PrimitiveId> near;
  for (std::size_t i = 0; i < atoms.atoms.size(); ++i) {
    const auto& a = atoms.atoms[i];
    near.clear();
    spheres.primitives_meeting_box(a.centre - Eigen::Vector3d::Constant(a.radius),
                                   a.centre + Eigen::Vector3d::Constant(a.radius), near);
    for (int j : near)
      if (j > static_cast<int>(i)) pairs.push_back({static_cast<int>(i), j});
  }
  return pairs;
}

}  // namespace

void require_positive_radii(const MedialSurface& atoms) {
  // A ball of radius 0 is a point: the union of balls has nothing to garb there. Only hulls
  // (a medial mesh's cones and slabs) give such atoms a volume.
  for (std::size_t i = 0; i < atoms.atoms.size(); ++i)
    if (!(atoms.atoms[i].radius > 0))
      throw InvalidInput("atom " + std::to_string(i) +
                         " has radius 0: G of the atoms alone (rt) needs radii > 0; the "
                         "envelope of a medial mesh (ma) takes them");
}

std::vector<std::array<int, 2>> cone_pairs(const MedialSurface& atoms, const ConeOptions& opt) {
  validate(atoms);
  require_positive_radii(atoms);
  if (!(opt.min_circle_ratio >= 0 && opt.min_circle_ratio <= 1))
    throw InvalidInput("cone filter: the minimal circle ratio must be in [0, 1]");
  if (!(opt.max_collar >= 0)) throw InvalidInput("cone filter: the maximal collar must be >= 0");
  std::vector<std::array<int, 2>> candidates;
  switch (opt.source) {
    case ConeSource::none:
      return {};
    case ConeSource::regular_triangulation:
      candidates = detail::regular_edges(atoms);
      break;
    case ConeSource::all_pairs:
      candidates = intersecting_pairs(atoms);
      break;
    case ConeSource::ma_edges:
      for (auto e : atoms.edges) {
        if (e[0] == e[1]) continue;
        if (e[0] > e[1]) std::swap(e[0], e[1]);
        candidates.push_back(e);
      }
      break;
  }
  if (!std::is_sorted(candidates.begin(), candidates.end()))  // the triangulation's already are
    std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  // The collar limit in model units: max_collar times rc / 8, the automatic octree's leaf
  // side bound (from the atoms alone).
  const double collar_limit =
      opt.max_collar > 0 ? opt.max_collar * characteristic_radius(atoms) / 8 : INFINITY;
  auto kept = [&](int i, int j) {
    const MedialAtom& a = atoms.atoms[i];
    const MedialAtom& b = atoms.atoms[j];
    const double L = (b.centre - a.centre).norm();
    if (!(L < a.radius + b.radius) || !(L > std::abs(a.radius - b.radius))) return false;
    // Radius of the intersection circle against the smaller radius.
    const Crease c = crease(L, a.radius, b.radius);
    const double x = c.along, h = c.radius;
    if (h < opt.min_circle_ratio * std::min(a.radius, b.radius)) return false;
    // Collar: how far the lateral surface stands off the crease where the two spheres meet
    // (in the axial section the lateral line is x sin(phi) + y cos(phi) = r1, the crease is
    // the point (x, h)).
    const double sin_phi = (a.radius - b.radius) / L;
    const double cos_phi = std::sqrt(std::max(0.0, 1 - sin_phi * sin_phi));
    return !(a.radius - (x * sin_phi + h * cos_phi) > collar_limit);
  };
  // Each candidate on its own, in parallel; kept in the candidates' order.
  std::vector<std::uint8_t> keep(candidates.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, candidates.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t k = r.begin(); k != r.end(); ++k)
                        keep[k] = kept(candidates[k][0], candidates[k][1]);
                    });
  std::vector<std::array<int, 2>> pairs;
  for (std::size_t k = 0; k < candidates.size(); ++k)
    if (keep[k]) pairs.push_back(candidates[k]);
  return pairs;
}

}  // namespace mg::garbing
