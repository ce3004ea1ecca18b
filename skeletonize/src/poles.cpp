// skeletonize(): the inner Voronoi poles of a closed mesh, the pipeline (samples -> Delaunay
// triangulation -> poles -> merging and pruning -> distances and clamping -> connectivity).
// The CGAL translation unit of mg::skeletonize for the Delaunay triangulation.
#include "skeletonize/poles.h"

#include "ball_tree.h"
#include "circumcentres.h"
#include "core/errors.h"
#include "core/timer.h"
#include "samples.h"
#include "skeletonize/union_topology.h"

#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <numeric>
#include <unordered_map>

namespace mg::skeletonize {
namespace {

using K = CGAL::Epick;
using Point = K::Point_3;
using Vec3 = Eigen::Vector3d;
// The Delaunay triangulation is built sequentially (CGAL's parallel insertion gains little on
// 2 cores and loses much as soon as they are shared: docs/performance.md). Everything after it
// runs in parallel. With CGAL's symbolic perturbation the triangulation does not depend on the
// insertion order (which CGAL's spatial sort randomises), and nothing below depends on how it
// stores its cells: results are the same at any thread count.
using Vb = CGAL::Triangulation_vertex_base_with_info_3<int, K>;
using Delaunay = CGAL::Delaunay_triangulation_3<K, CGAL::Triangulation_data_structure_3<Vb>>;

Point to_point(const Vec3& p) { return Point(p.x(), p.y(), p.z()); }

/// Integer grid cell of a point for neighbour lookups at spacing h.
struct GridKey {
  long x, y, z;
  bool operator==(const GridKey& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct GridHash {
  std::size_t operator()(const GridKey& k) const {
    return static_cast<std::size_t>(k.x * 73856093L ^ k.y * 19349663L ^ k.z * 83492791L);
  }
};
GridKey grid_key(const Vec3& p, double h) {
  return {static_cast<long>(std::floor(p.x() / h)), static_cast<long>(std::floor(p.y() / h)),
          static_cast<long>(std::floor(p.z() / h))};
}

}  // namespace

namespace {

class Skeletonizer {
 public:
  Skeletonizer(const PolygonSoup& mesh, const SkeletonOptions& opt, const std::string& name)
      : mesh_(mesh), opt_(opt), name_(name) {}

  Skeleton run() {
    Stopwatch t;
    detail::check_closed_mesh(mesh_, name_);
    if (!std::isfinite(opt_.merge_tol)) throw InvalidInput("merge tolerance must be finite");
    if (!(opt_.isolated_fraction >= 0 && std::isfinite(opt_.isolated_fraction)))
      throw InvalidInput("isolated-ball fraction must be finite and >= 0");
    out_.stats.diagonal = bbox_diagonal(mesh_.points);
    tol_ = opt_.merge_tol >= 0 ? opt_.merge_tol : 1e-3 * out_.stats.diagonal;
    out_.stats.merge_tol = tol_;
    out_.samples = detail::make_samples(mesh_, opt_);
    out_.stats.samples = out_.samples.size();
    deduplicate();
    solid_ = std::make_unique<SolidQuery>(mesh_);
    out_.stats.seconds_setup = t.restart();

    triangulate();
    out_.stats.seconds_delaunay = t.restart();
    find_poles();
    out_.stats.seconds_poles = t.restart();
    merge_poles();
    prune_contained();
    out_.stats.seconds_merge = t.restart();
    distances_and_clamping();
    out_.stats.seconds_distances = t.restart();
    if (opt_.connectivity) add_connectivity();
    out_.stats.seconds_connectivity = t.restart();
    finish();
    return std::move(out_);
  }

 private:
  /// Distinct sample positions in lexicographic order (the triangulation keeps one vertex per
  /// position; a canonical order keeps everything after it independent of insertion order).
  void deduplicate() {
    const auto& s = out_.samples;
    std::vector<int> order(s.size());
    std::iota(order.begin(), order.end(), 0);
    auto less = [&](int a, int b) {
      return std::lexicographical_compare(s[a].data(), s[a].data() + 3, s[b].data(),
                                          s[b].data() + 3);
    };
    std::stable_sort(order.begin(), order.end(), less);
    unique_of_sample_.assign(s.size(), -1);
    for (std::size_t k = 0; k < order.size(); ++k) {
      if (k == 0 || less(order[k - 1], order[k])) points_.push_back(s[order[k]]);
      unique_of_sample_[order[k]] = static_cast<int>(points_.size()) - 1;
    }
    out_.stats.duplicate_samples = s.size() - points_.size();
  }

  void triangulate() {
    Delaunay dt;
    {
      std::vector<std::pair<Point, int>> input;
      input.reserve(points_.size());
      for (std::size_t i = 0; i < points_.size(); ++i)
        input.emplace_back(to_point(points_[i]), static_cast<int>(i));
      dt.insert(input.begin(), input.end());
    }
    if (dt.dimension() < 3)
      throw InvalidInput(name_ + ": fewer than 4 non-coplanar samples: no Delaunay cell");

    // Cells as sorted sample quadruples (in the triangulation's storage order, which may vary:
    // nothing below depends on it).
    cells_.reserve(dt.number_of_finite_cells());
    for (auto c = dt.finite_cells_begin(); c != dt.finite_cells_end(); ++c) {
      std::array<int, 4> v;
      for (int k = 0; k < 4; ++k) v[k] = c->vertex(k)->info();
      std::sort(v.begin(), v.end());
      cells_.push_back(v);
    }
    out_.stats.cells = cells_.size();

    std::vector<Delaunay::Vertex_handle> hull;
    dt.adjacent_vertices(dt.infinite_vertex(), std::back_inserter(hull));
    out_.stats.hull_samples = hull.size();

    // Incident cells of each sample, in cell order (compressed rows).
    first_cell_.assign(points_.size() + 1, 0);
    for (const auto& c : cells_)
      for (int v : c) ++first_cell_[v + 1];
    std::partial_sum(first_cell_.begin(), first_cell_.end(), first_cell_.begin());
    incident_.resize(4 * cells_.size());
    std::vector<int> next(first_cell_.begin(), first_cell_.end() - 1);
    for (std::size_t c = 0; c < cells_.size(); ++c)
      for (int v : cells_[c]) incident_[next[v]++] = static_cast<int>(c);

    centre_.resize(cells_.size());
    valid_.assign(cells_.size(), 0);
    std::vector<char> exact(cells_.size(), 0);
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells_.size(), 2048),
                      [&](const auto& range) {
                        std::vector<std::size_t> hard;
                        {
                          CGAL::Protect_FPU_rounding<true> upward;
                          for (std::size_t i = range.begin(); i != range.end(); ++i)
                            if (detail::interval_circumcentre(corners(i), centre_[i]))
                              valid_[i] = 1;
                            else
                              hard.push_back(i);
                        }
                        for (std::size_t i : hard) {
                          exact[i] = 1;
                          valid_[i] = detail::exact_circumcentre(corners(i), centre_[i]);
                        }
                      });
    out_.stats.exact_circumcentres =
        static_cast<std::size_t>(std::count(exact.begin(), exact.end(), 1));
    out_.stats.rejected_cells =
        static_cast<std::size_t>(std::count(valid_.begin(), valid_.end(), 0));
  }

  std::array<Vec3, 4> corners(std::size_t cell) const {
    const auto& c = cells_[cell];
    return {points_[c[0]], points_[c[1]], points_[c[2]], points_[c[3]]};
  }

  /// Per sample: its incident cells' circumcentres from the farthest (ties: lexicographic on the
  /// centre, so the cells' storage order never matters); the first inside the object is the
  /// inner pole. Inside tests are memoised per cell.
  void find_poles() {
    const std::size_t n = points_.size();
    std::vector<std::atomic<signed char>> state(cells_.size());
    for (auto& s : state) s.store(-1, std::memory_order_relaxed);
    pole_radius_.assign(n, -1);
    pole_cell_.assign(n, -1);
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
      std::vector<std::pair<double, int>> order;
      for (int k = first_cell_[i]; k < first_cell_[i + 1]; ++k) {
        const int c = incident_[k];
        if (valid_[c]) order.push_back({(centre_[c] - points_[i]).squaredNorm(), c});
      }
      std::sort(order.begin(), order.end(), [&](const auto& a, const auto& b) {
        if (a.first != b.first) return a.first > b.first;
        const Vec3 &ca = centre_[a.second], &cb = centre_[b.second];
        return std::lexicographical_compare(ca.data(), ca.data() + 3, cb.data(), cb.data() + 3);
      });
      for (const auto& [d2, c] : order) {
        signed char s = state[c].load(std::memory_order_relaxed);
        if (s < 0) {
          s = solid_->contains(centre_[c]) ? 1 : 0;
          state[c].store(s, std::memory_order_relaxed);
        }
        if (s == 1) {
          pole_cell_[i] = c;
          pole_radius_[i] = std::sqrt(d2);
          return;
        }
      }
    });
    for (std::size_t i = 0; i < n; ++i) {
      if (pole_cell_[i] >= 0)
        ++out_.stats.poles;
      else
        ++out_.stats.skipped_samples;
    }
  }

  /// Greedy clusters, largest radius first: a pole within tol / 2 of an atom's centre joins it.
  /// The atom's ball is an empty circumsphere at least as large, so every sample of the cluster
  /// lies within tol / 2 of its surface.
  void merge_poles() {
    std::vector<int> order;
    for (std::size_t i = 0; i < points_.size(); ++i)
      if (pole_cell_[i] >= 0) order.push_back(static_cast<int>(i));
    std::stable_sort(order.begin(), order.end(),
                     [&](int a, int b) { return pole_radius_[a] > pole_radius_[b]; });
    // Grid of side h >= tol: the poles within tol / 2 of a point lie in the 2 x 2 x 2 cells
    // nearest to it. (tol = 0 merges equal poles only.)
    const double h = std::max(tol_, 1e-12 * out_.stats.diagonal);
    std::unordered_map<GridKey, std::vector<int>, GridHash> atoms_near;  // lookups only
    atom_of_point_.assign(points_.size(), -1);
    for (int i : order) {
      const Vec3& pole = centre_[pole_cell_[i]];
      const GridKey g = grid_key(pole, h);
      const Vec3 frac = pole / h - Vec3(g.x, g.y, g.z);
      const long sx = frac.x() < 0.5 ? -1 : 1, sy = frac.y() < 0.5 ? -1 : 1,
                 sz = frac.z() < 0.5 ? -1 : 1;
      int found = -1;
      for (int k = 0; k < 8 && found < 0; ++k) {
        const auto it =
            atoms_near.find({g.x + (k & 1) * sx, g.y + (k >> 1 & 1) * sy, g.z + (k >> 2 & 1) * sz});
        if (it == atoms_near.end()) continue;
        for (int a : it->second)
          if ((out_.atoms.atoms[a].centre - pole).norm() <= tol_ / 2) {
            found = a;
            break;
          }
      }
      if (found < 0) {
        found = static_cast<int>(out_.atoms.atoms.size());
        out_.atoms.atoms.push_back({pole, pole_radius_[i]});
        founder_.push_back(i);
        atoms_near[g].push_back(found);
      } else {
        ++out_.stats.merged;
      }
      atom_of_point_[i] = found;
    }
  }

  /// Drops every ball inside a larger kept ball up to tol / 2: |ci - cj| + ri <= rj + tol / 2.
  /// With the merge's tol / 2, every sample then lies within tol of its atom's surface
  /// (containers are kept balls, so there are no chains). Atoms are in decreasing radius.
  void prune_contained() {
    const auto& atoms = out_.atoms.atoms;
    const detail::BallTree tree(atoms);
    auto contains = [&](std::size_t i, auto&& accept) {
      int found = -1;
      tree.find_containing(atoms[i].centre, atoms[i].radius, tol_ / 2, [&](int j) {
        if (j >= static_cast<int>(i) || !accept(j)) return false;
        found = j;
        return true;
      });
      return found;
    };
    // In parallel, a first container of each ball (none: kept whatever happens). Then, in order
    // of decreasing radius, each ball with a container is dropped if a kept ball contains it
    // (most often its first container: no second search).
    std::vector<int> first(atoms.size(), -1);
    tbb::parallel_for(std::size_t(0), atoms.size(),
                      [&](std::size_t i) { first[i] = contains(i, [](int) { return true; }); });
    std::vector<char> kept(atoms.size(), 0);
    std::vector<int> target(atoms.size(), -1);
    for (std::size_t i = 0; i < atoms.size(); ++i) {
      if (first[i] >= 0)
        target[i] = kept[first[i]] ? first[i] : contains(i, [&](int j) { return kept[j] != 0; });
      kept[i] = target[i] < 0;
    }
    out_.stats.pruned = static_cast<std::size_t>(std::count(kept.begin(), kept.end(), 0));
    remap(target);
  }

  /// Removes the atoms with target[i] != -1 (-2: dropped without a target), renumbering the
  /// rest and sending the removed atoms' samples to their target.
  void remap(const std::vector<int>& target) {
    auto& atoms = out_.atoms.atoms;
    std::vector<int> new_index(atoms.size(), -1);
    std::vector<MedialAtom> kept;
    std::vector<int> kept_founder;
    for (std::size_t i = 0; i < atoms.size(); ++i)
      if (target[i] == -1) {
        new_index[i] = static_cast<int>(kept.size());
        kept.push_back(atoms[i]);
        kept_founder.push_back(founder_[i]);
      }
    for (int& a : atom_of_point_) {
      if (a < 0) continue;
      int t = a;
      while (target[t] >= 0) t = target[t];
      a = target[t] == -2 ? -1 : new_index[t];
    }
    atoms = std::move(kept);
    founder_ = std::move(kept_founder);
  }

  /// Distances from the centres to the mesh (searches start at each atom's own sample):
  /// overshoot before and after clamping, and the clamping itself.
  void distances_and_clamping() {
    auto& atoms = out_.atoms.atoms;
    std::vector<double> distance(atoms.size());
    tbb::parallel_for(std::size_t(0), atoms.size(), [&](std::size_t i) {
      distance[i] = solid_->distance(atoms[i].centre, points_[founder_[i]]);
    });
    double worst = 0;
    for (std::size_t i = 0; i < atoms.size(); ++i)
      worst = std::max(worst, atoms[i].radius - distance[i]);
    out_.stats.pole_overshoot = worst;
    if (opt_.clamp_radius) {
      for (std::size_t i = 0; i < atoms.size(); ++i)
        atoms[i].radius = std::min(atoms[i].radius, distance[i]);
      const std::vector<int> target = small_groups();
      out_.stats.dropped_small =
          static_cast<std::size_t>(std::count(target.begin(), target.end(), -2));
      std::vector<double> kept_distance;
      for (std::size_t i = 0; i < atoms.size(); ++i)
        if (target[i] == -1) kept_distance.push_back(distance[i]);
      remap(target);
      distance = std::move(kept_distance);
    }
    worst = 0;
    for (std::size_t i = 0; i < atoms.size(); ++i)
      worst = std::max(worst, atoms[i].radius - distance[i]);
    out_.stats.worst_overshoot = worst;
  }

  /// Clamped balls can break away from the rest: the poles of convex corners shrink to the
  /// local distance to the mesh and may then meet no other ball. Each group of clamped balls
  /// that meet each other (a component of their union) whose largest ball is under
  /// opt_.isolated_fraction of the diagonal is dropped, except the group of the largest ball;
  /// so are balls clamped to radius 0. Returns the remap target (-2: dropped, -1: kept).
  std::vector<int> small_groups() const {
    const auto& atoms = out_.atoms.atoms;
    const double small = opt_.isolated_fraction * out_.stats.diagonal;
    const detail::BallTree tree(atoms);
    std::vector<int> target(atoms.size(), -1);
    const int largest = static_cast<int>(
        std::max_element(atoms.begin(), atoms.end(),
                         [](const auto& a, const auto& b) { return a.radius < b.radius; }) -
        atoms.begin());
    // Per ball: 0 not reached yet, 1 in the group being grown, 2 in a group that reaches a
    // larger ball (so does every group meeting it), 3 dropped.
    std::vector<char> state(atoms.size(), 0);
    for (std::size_t i = 0; i < atoms.size(); ++i) {
      if (!(atoms[i].radius > 0)) target[i] = -2;
      if (state[i] != 0 || !(atoms[i].radius > 0 && atoms[i].radius < small)) continue;
      // The group through small balls only; it stays if it reaches a larger ball.
      std::vector<int> group = {static_cast<int>(i)};
      state[i] = 1;
      bool anchored = false;
      for (std::size_t k = 0; k < group.size() && !anchored; ++k)
        anchored = tree.find_meeting(atoms[group[k]].centre, atoms[group[k]].radius, [&](int j) {
          if (!(atoms[j].radius > 0) || state[j] == 1) return false;
          if (state[j] == 2 || !(atoms[j].radius < small)) return true;
          state[j] = 1;
          group.push_back(j);
          return false;
        });
      const bool keep = anchored || std::find(group.begin(), group.end(), largest) != group.end();
      for (int j : group) {
        state[j] = keep ? 2 : 3;
        if (!keep) target[j] = -2;
      }
    }
    return target;
  }

  void add_connectivity() {
    UnionComplex dual;
    const RegularSimplices rs = regular_simplices(out_.atoms, &dual);
    out_.union_complex = std::move(dual);
    out_.stats.hidden_atoms = rs.hidden_atoms;
    const auto& a = out_.atoms.atoms;
    std::vector<char> keep_edge(rs.edges.size()), keep_triangle(rs.triangles.size());
    tbb::parallel_for(std::size_t(0), rs.edges.size(), [&](std::size_t i) {
      keep_edge[i] = solid_->segment_inside(a[rs.edges[i][0]].centre, a[rs.edges[i][1]].centre);
    });
    tbb::parallel_for(std::size_t(0), rs.triangles.size(), [&](std::size_t i) {
      const auto& t = rs.triangles[i];
      keep_triangle[i] = solid_->triangle_inside(a[t[0]].centre, a[t[1]].centre, a[t[2]].centre);
    });
    for (std::size_t i = 0; i < rs.edges.size(); ++i)
      if (keep_edge[i]) out_.atoms.edges.push_back(rs.edges[i]);
    for (std::size_t i = 0; i < rs.triangles.size(); ++i)
      if (keep_triangle[i]) out_.atoms.faces.push_back(rs.triangles[i]);
    // Cells: the tetrahedra whose four triangles were kept (the kept faces are sorted).
    const auto& kept = out_.atoms.faces;
    auto has = [&](int x, int y, int z) {
      return std::binary_search(kept.begin(), kept.end(), std::array<int, 3>{x, y, z});
    };
    for (const auto& c : rs.tetrahedra)
      if (has(c[0], c[1], c[2]) && has(c[0], c[1], c[3]) && has(c[0], c[2], c[3]) &&
          has(c[1], c[2], c[3]))
        out_.cells.push_back(c);
  }

  void finish() {
    const auto& atoms = out_.atoms.atoms;
    if (atoms.empty())
      throw InvalidInput(name_ +
                         ": no Voronoi vertex of the samples lies inside the mesh (add samples: " +
                         "edge midpoints or random points)");
    out_.atom_of_sample.resize(out_.samples.size());
    for (std::size_t s = 0; s < out_.samples.size(); ++s)
      out_.atom_of_sample[s] = atom_of_point_[unique_of_sample_[s]];
    out_.stats.atoms = atoms.size();
    out_.stats.rmin = INFINITY;
    out_.stats.rmax = 0;
    for (const auto& x : atoms) {
      out_.stats.rmin = std::min(out_.stats.rmin, x.radius);
      out_.stats.rmax = std::max(out_.stats.rmax, x.radius);
    }
  }

  const PolygonSoup& mesh_;
  const SkeletonOptions& opt_;
  const std::string& name_;
  double tol_ = 0;
  Skeleton out_;
  std::unique_ptr<SolidQuery> solid_;
  std::vector<Vec3> points_;               // distinct samples, lexicographic
  std::vector<int> unique_of_sample_;      // sample -> points_ index
  std::vector<std::array<int, 4>> cells_;  // finite Delaunay cells, canonical order
  std::vector<int> first_cell_, incident_;
  std::vector<char> valid_;
  std::vector<Vec3> centre_;         // per cell
  std::vector<double> pole_radius_;  // per point
  std::vector<int> pole_cell_;       // per point; -1: no pole
  std::vector<int> atom_of_point_;   // per point; -1: none
  std::vector<int> founder_;         // per atom: the point whose pole it is
};

}  // namespace

Skeleton skeletonize(const PolygonSoup& mesh, const SkeletonOptions& opt, const std::string& name) {
  return Skeletonizer(mesh, opt, name).run();
}

}  // namespace mg::skeletonize
