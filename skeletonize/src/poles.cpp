// Inner Voronoi poles of a closed mesh: the CGAL translation unit of mg::skeletonize for the
// Delaunay triangulation, inside tests and distances.
#include "skeletonize/poles.h"

#include "garbing/errors.h"
#include "garbing/mesh_topology.h"
#include "skeletonize/union_topology.h"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Delaunay_triangulation_3.h>
#include <CGAL/Delaunay_triangulation_cell_base_3.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Triangulation_cell_base_with_info_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <map>
#include <unordered_map>

namespace mg::skeletonize {
namespace {

using K = CGAL::Epick;
using EK = CGAL::Epeck;
using Point = K::Point_3;
using Vec3 = Eigen::Vector3d;
using Vb = CGAL::Triangulation_vertex_base_with_info_3<int, K>;
using Cb = CGAL::Triangulation_cell_base_with_info_3<int, K, CGAL::Delaunay_triangulation_cell_base_3<K>>;
using Delaunay = CGAL::Delaunay_triangulation_3<K, CGAL::Triangulation_data_structure_3<Vb, Cb>>;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<SurfaceMesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;
using Inside = CGAL::Side_of_triangle_mesh<SurfaceMesh, K, CGAL::Default, Tree>;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

Vec3 to_vec(const Point& p) { return Vec3(p.x(), p.y(), p.z()); }
Point to_point(const Vec3& p) { return Point(p.x(), p.y(), p.z()); }

/// splitmix64: sample k of the random stream depends only on (seed, k).
double uniform(std::uint64_t seed, std::uint64_t k) {
  std::uint64_t x = seed * 0x9e3779b97f4a7c15ULL + k + 0x632be59bd9b4e019ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  x ^= x >> 31;
  return static_cast<double>(x >> 11) * 0x1.0p-53;
}

void check_mesh(const PolygonSoup& mesh, const std::string& name) {
  if (mesh.faces.empty()) throw InvalidInput(name + ": empty mesh (no faces)");
  const MeshTopology t = mesh_topology(mesh);
  if (!t.manifold) throw InvalidInput(name + ": non-manifold mesh: " + t.first_problem);
  if (!t.closed)
    throw InvalidInput(name + ": open mesh (" + std::to_string(t.boundary_edges) +
                       " boundary edges): poles need a closed surface");
  if (!t.oriented) throw InvalidInput(name + ": " + t.first_problem);
}

/// Triangles of the mesh (polygons fanned) as a CGAL surface mesh.
SurfaceMesh triangle_mesh(const PolygonSoup& soup) {
  SurfaceMesh sm;
  std::vector<SurfaceMesh::Vertex_index> v;
  v.reserve(soup.points.size());
  for (const auto& p : soup.points) v.push_back(sm.add_vertex(to_point(p)));
  for (const auto& f : soup.faces)
    for (std::size_t i = 1; i + 1 < f.size(); ++i) sm.add_face(v[f[0]], v[f[i]], v[f[i + 1]]);
  return sm;
}

std::vector<Vec3> make_samples(const PolygonSoup& mesh, const SkeletonOptions& opt) {
  std::vector<Vec3> samples;
  std::vector<char> used(mesh.points.size(), 0);
  for (const auto& f : mesh.faces)
    for (int v : f) used[v] = 1;
  for (std::size_t i = 0; i < mesh.points.size(); ++i)
    if (used[i]) samples.push_back(mesh.points[i]);
  if (opt.edge_midpoints) {
    std::vector<std::pair<int, int>> edges;
    for (const auto& f : mesh.faces)
      for (std::size_t i = 0; i < f.size(); ++i) edges.push_back(std::minmax(f[i], f[(i + 1) % f.size()]));
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    for (const auto& [a, b] : edges) samples.push_back((mesh.points[a] + mesh.points[b]) / 2);
  }
  if (opt.random_samples > 0) {
    std::vector<std::array<int, 3>> tris;
    std::vector<double> cumulative;
    double total = 0;
    for (const auto& f : mesh.faces)
      for (std::size_t i = 1; i + 1 < f.size(); ++i) {
        tris.push_back({f[0], f[i], f[i + 1]});
        total += (mesh.points[f[i]] - mesh.points[f[0]]).cross(mesh.points[f[i + 1]] - mesh.points[f[0]]).norm() / 2;
        cumulative.push_back(total);
      }
    for (std::size_t k = 0; k < opt.random_samples; ++k) {
      const double pick = uniform(opt.seed, 3 * k) * total;
      const std::size_t t = std::min<std::size_t>(
          std::upper_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin(), tris.size() - 1);
      double u = uniform(opt.seed, 3 * k + 1), v = uniform(opt.seed, 3 * k + 2);
      if (u + v > 1) {
        u = 1 - u;
        v = 1 - v;
      }
      const Vec3& a = mesh.points[tris[t][0]];
      samples.push_back(a + u * (mesh.points[tris[t][1]] - a) + v * (mesh.points[tris[t][2]] - a));
    }
  }
  return samples;
}

/// Circumcentre of a cell: the inexact construction when it passes a residual check (equal
/// distances to the four corners, relative 1e-10), else the exact one. False when not even the
/// exact one is a finite double (a numerical rejection; geometry never rejects a cell).
bool circumcentre(const Point& p, const Point& q, const Point& r, const Point& s, Vec3& out, bool& exact) {
  exact = false;
  const Point c = CGAL::circumcenter(p, q, r, s);
  const double d0 = CGAL::squared_distance(c, p);
  const double tol = 1e-10 * d0;
  if (std::isfinite(d0) && std::abs(CGAL::squared_distance(c, q) - d0) <= tol &&
      std::abs(CGAL::squared_distance(c, r) - d0) <= tol && std::abs(CGAL::squared_distance(c, s) - d0) <= tol) {
    out = to_vec(c);
    return true;
  }
  exact = true;
  const CGAL::Cartesian_converter<K, EK> to_exact;
  const EK::Point_3 e = CGAL::circumcenter(to_exact(p), to_exact(q), to_exact(r), to_exact(s));
  out = Vec3(CGAL::to_double(e.x()), CGAL::to_double(e.y()), CGAL::to_double(e.z()));
  return out.allFinite();
}

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

/// Clamped balls under this fraction of the diagonal that meet no other ball are dropped
/// (measured: clamped pole sets of hand and anchor_dense leave isolated balls of 1e-3 to 3e-3 of
/// the diagonal, each a spurious component).
constexpr double kIsolatedBall = 1e-2;

}  // namespace

struct SolidQuery::Impl {
  SurfaceMesh surface;
  std::unique_ptr<Tree> tree;
  std::unique_ptr<Inside> inside;
};

SolidQuery::SolidQuery(const PolygonSoup& mesh) : impl_(std::make_unique<Impl>()) {
  impl_->surface = triangle_mesh(mesh);
  impl_->tree = std::make_unique<Tree>(faces(impl_->surface).first, faces(impl_->surface).second, impl_->surface);
  impl_->tree->accelerate_distance_queries();
  impl_->inside = std::make_unique<Inside>(*impl_->tree);
}

SolidQuery::~SolidQuery() = default;

bool SolidQuery::contains(const Vec3& p) const {
  return (*impl_->inside)(to_point(p)) == CGAL::ON_BOUNDED_SIDE;
}

double SolidQuery::distance(const Vec3& p) const {
  return std::sqrt(impl_->tree->squared_distance(to_point(p)));
}

namespace {

class Skeletonizer {
 public:
  Skeletonizer(const PolygonSoup& mesh, const SkeletonOptions& opt, const std::string& name)
      : mesh_(mesh), opt_(opt), name_(name) {}

  Skeleton run() {
    check_mesh(mesh_, name_);
    out_.stats.diagonal = bbox_diagonal(mesh_.points);
    tol_ = opt_.merge_tol >= 0 ? opt_.merge_tol : 1e-3 * out_.stats.diagonal;
    out_.stats.merge_tol = tol_;
    out_.samples = make_samples(mesh_, opt_);
    out_.stats.samples = out_.samples.size();

    solid_ = std::make_unique<SolidQuery>(mesh_);

    const auto t0 = Clock::now();
    triangulate();
    out_.stats.seconds_delaunay = seconds_since(t0);
    const auto t1 = Clock::now();
    find_poles();
    out_.stats.seconds_poles = seconds_since(t1);
    const auto t2 = Clock::now();
    merge_poles();
    prune_contained();
    out_.stats.seconds_merge = seconds_since(t2);
    const auto t3 = Clock::now();
    if (opt_.clamp_radius) clamp();
    measure_overshoot();
    out_.stats.seconds_clamp = seconds_since(t3);
    const auto t4 = Clock::now();
    if (opt_.connectivity) add_connectivity();
    out_.stats.seconds_connectivity = seconds_since(t4);
    finish();
    return std::move(out_);
  }

 private:
  bool inside(const Vec3& p) const { return solid_->contains(p); }
  double distance_to_mesh(const Vec3& p) const { return solid_->distance(p); }

  void triangulate() {
    std::vector<std::pair<Point, int>> points;
    points.reserve(out_.samples.size());
    for (std::size_t i = 0; i < out_.samples.size(); ++i)
      points.emplace_back(to_point(out_.samples[i]), static_cast<int>(i));
    dt_.insert(points.begin(), points.end());
    if (dt_.dimension() < 3)
      throw InvalidInput(name_ + ": fewer than 4 non-coplanar samples: no Delaunay cell");
    out_.stats.duplicate_samples = out_.samples.size() - dt_.number_of_vertices();
    // Cells numbered in iteration order; each sample lists its incident finite cells.
    incident_.assign(out_.samples.size(), {});
    for (auto c = dt_.finite_cells_begin(); c != dt_.finite_cells_end(); ++c) {
      c->info() = static_cast<int>(cells_.size());
      cells_.push_back(c);
      for (int k = 0; k < 4; ++k) incident_[c->vertex(k)->info()].push_back(c->info());
    }
    out_.stats.cells = cells_.size();
    hull_.assign(out_.samples.size(), 0);
    for (auto c = dt_.all_cells_begin(); c != dt_.all_cells_end(); ++c)
      if (dt_.is_infinite(c))
        for (int k = 0; k < 4; ++k)
          if (!dt_.is_infinite(c->vertex(k))) hull_[c->vertex(k)->info()] = 1;
    out_.stats.hull_samples = static_cast<std::size_t>(std::count(hull_.begin(), hull_.end(), 1));
    centre_.resize(cells_.size());
    valid_.assign(cells_.size(), 0);
    std::vector<char> exact(cells_.size(), 0);
    tbb::parallel_for(std::size_t(0), cells_.size(), [&](std::size_t i) {
      const auto& c = cells_[i];
      bool used_exact = false;
      valid_[i] = circumcentre(c->vertex(0)->point(), c->vertex(1)->point(), c->vertex(2)->point(),
                               c->vertex(3)->point(), centre_[i], used_exact);
      exact[i] = used_exact;
    });
    out_.stats.exact_circumcentres = static_cast<std::size_t>(std::count(exact.begin(), exact.end(), 1));
    out_.stats.rejected_cells = static_cast<std::size_t>(std::count(valid_.begin(), valid_.end(), 0));
  }

  /// Per sample: its incident cells' circumcentres from the farthest; the first inside the
  /// object is the inner pole. Inside tests are memoised per cell (atomic, thread-safe).
  void find_poles() {
    const std::size_t n = out_.samples.size();
    std::vector<std::atomic<signed char>> state(cells_.size());
    for (auto& s : state) s.store(-1, std::memory_order_relaxed);
    pole_.assign(n, Vec3::Zero());
    pole_radius_.assign(n, -1);
    tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
      std::vector<std::pair<double, int>> order;
      for (int c : incident_[i])
        if (valid_[c]) order.push_back({-(centre_[c] - out_.samples[i]).squaredNorm(), c});
      std::sort(order.begin(), order.end());
      for (const auto& [neg_d2, c] : order) {
        signed char s = state[c].load(std::memory_order_relaxed);
        if (s < 0) {
          s = inside(centre_[c]) ? 1 : 0;
          state[c].store(s, std::memory_order_relaxed);
        }
        if (s == 1) {
          pole_[i] = centre_[c];
          pole_radius_[i] = std::sqrt(-neg_d2);
          return;
        }
      }
    });
    for (std::size_t i = 0; i < n; ++i) {
      if (pole_radius_[i] > 0)
        ++out_.stats.poles;
      else if (!incident_[i].empty())
        ++out_.stats.skipped_samples;
    }
  }

  /// Greedy clusters, largest radius first: a pole within tol / 2 of a representative joins
  /// it. The representative's ball is an empty circumsphere, so every sample of the cluster
  /// lies within tol / 2 of its surface.
  void merge_poles() {
    std::vector<int> order;
    for (std::size_t i = 0; i < pole_.size(); ++i)
      if (pole_radius_[i] > 0) order.push_back(static_cast<int>(i));
    std::sort(order.begin(), order.end(), [&](int a, int b) {
      return pole_radius_[a] > pole_radius_[b] || (pole_radius_[a] == pole_radius_[b] && a < b);
    });
    const double h = std::max(tol_ / 2, 1e-300);
    std::unordered_map<GridKey, std::vector<int>, GridHash> reps;  // lookups only
    out_.atom_of_sample.assign(out_.samples.size(), -1);
    for (int i : order) {
      const GridKey g = grid_key(pole_[i], h);
      int found = -1;
      for (long dx = -1; dx <= 1 && found < 0; ++dx)
        for (long dy = -1; dy <= 1 && found < 0; ++dy)
          for (long dz = -1; dz <= 1 && found < 0; ++dz) {
            const auto it = reps.find({g.x + dx, g.y + dy, g.z + dz});
            if (it == reps.end()) continue;
            for (int a : it->second)
              if ((out_.atoms.atoms[a].centre - pole_[i]).norm() <= tol_ / 2) {
                found = a;
                break;
              }
          }
      if (found < 0) {
        found = static_cast<int>(out_.atoms.atoms.size());
        out_.atoms.atoms.push_back({pole_[i], pole_radius_[i]});
        reps[g].push_back(found);
      } else {
        ++out_.stats.merged;
      }
      out_.atom_of_sample[i] = found;
    }
  }

  /// Drops every ball inside a larger kept ball up to tol / 2: |ci - cj| + ri <= rj + tol / 2.
  /// With the merge's tol / 2, every sample then lies within tol of its atom's surface
  /// (containers are kept balls, so there are no chains).
  void prune_contained() {
    auto& atoms = out_.atoms.atoms;
    const std::size_t n = atoms.size();
    std::vector<int> order(n);
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) {
      return atoms[a].radius > atoms[b].radius || (atoms[a].radius == atoms[b].radius && a < b);
    });
    // Kept balls bucketed by centre at the largest radius (a container's centre lies within
    // r_j + tol of the contained one's centre); the scan stops at the first container.
    const double h = std::max(atoms.empty() ? 1.0 : atoms[order[0]].radius + tol_, 1e-300);
    std::unordered_map<GridKey, std::vector<int>, GridHash> kept;  // lookups only
    std::vector<int> container(n, -1);
    for (int i : order) {
      const GridKey g = grid_key(atoms[i].centre, h);
      for (long dx = -1; dx <= 1 && container[i] < 0; ++dx)
        for (long dy = -1; dy <= 1 && container[i] < 0; ++dy)
          for (long dz = -1; dz <= 1 && container[i] < 0; ++dz) {
            const auto it = kept.find({g.x + dx, g.y + dy, g.z + dz});
            if (it == kept.end()) continue;
            for (int j : it->second)
              if ((atoms[i].centre - atoms[j].centre).norm() + atoms[i].radius <= atoms[j].radius + tol_ / 2) {
                container[i] = j;
                break;
              }
          }
      if (container[i] < 0) kept[g].push_back(i);
    }
    remap(container);
    out_.stats.pruned += static_cast<std::size_t>(std::count_if(container.begin(), container.end(),
                                                                [](int c) { return c >= 0; }));
  }

  /// Removes the atoms with target[i] >= 0 (-2: drop without a target), renumbering and
  /// sending their samples to the target.
  void remap(const std::vector<int>& target) {
    auto& atoms = out_.atoms.atoms;
    std::vector<int> new_index(atoms.size(), -1);
    std::vector<MedialAtom> kept;
    for (std::size_t i = 0; i < atoms.size(); ++i)
      if (target[i] == -1) {
        new_index[i] = static_cast<int>(kept.size());
        kept.push_back(atoms[i]);
      }
    for (int& a : out_.atom_of_sample) {
      if (a < 0) continue;
      int t = a;
      while (t >= 0 && target[t] >= 0) t = target[t];
      a = t >= 0 ? new_index[t] : -1;
      if (t >= 0 && target[t] == -2) a = -1;
    }
    atoms = std::move(kept);
  }

  void clamp() {
    auto& atoms = out_.atoms.atoms;
    tbb::parallel_for(std::size_t(0), atoms.size(), [&](std::size_t i) {
      atoms[i].radius = std::min(atoms[i].radius, distance_to_mesh(atoms[i].centre));
    });
    // Small balls that meet no other ball are spurious components of the union (poles of
    // convex corners shrink away from the rest) and would drive the octree deep.
    const double small = kIsolatedBall * out_.stats.diagonal;
    std::vector<int> target(atoms.size(), -1);
    for (std::size_t i = 0; i < atoms.size(); ++i) {
      if (!(atoms[i].radius < small)) continue;
      bool meets = false;
      for (std::size_t j = 0; j < atoms.size() && !meets; ++j)
        meets = j != i && (atoms[i].centre - atoms[j].centre).norm() <= atoms[i].radius + atoms[j].radius;
      if ((!meets && atoms.size() > 1) || !(atoms[i].radius > 0)) target[i] = -2;
    }
    out_.stats.dropped_small =
        static_cast<std::size_t>(std::count(target.begin(), target.end(), -2));
    remap(target);
  }

  void measure_overshoot() {
    const auto& atoms = out_.atoms.atoms;
    std::vector<double> over(atoms.size());
    tbb::parallel_for(std::size_t(0), atoms.size(), [&](std::size_t i) {
      over[i] = atoms[i].radius - distance_to_mesh(atoms[i].centre);
    });
    out_.stats.worst_overshoot = atoms.empty() ? 0 : std::max(0.0, *std::max_element(over.begin(), over.end()));
  }

  void add_connectivity() {
    const RegularSimplices rs = regular_simplices(out_.atoms);
    out_.stats.hidden_atoms = rs.hidden_atoms;
    const auto& a = out_.atoms.atoms;
    std::vector<char> keep_edge(rs.edges.size()), keep_triangle(rs.triangles.size());
    tbb::parallel_for(std::size_t(0), rs.edges.size(), [&](std::size_t i) {
      keep_edge[i] = inside((a[rs.edges[i][0]].centre + a[rs.edges[i][1]].centre) / 2);
    });
    tbb::parallel_for(std::size_t(0), rs.triangles.size(), [&](std::size_t i) {
      const auto& t = rs.triangles[i];
      keep_triangle[i] = inside((a[t[0]].centre + a[t[1]].centre + a[t[2]].centre) / 3);
    });
    for (std::size_t i = 0; i < rs.edges.size(); ++i)
      if (keep_edge[i]) out_.atoms.edges.push_back(rs.edges[i]);
    for (std::size_t i = 0; i < rs.triangles.size(); ++i)
      if (keep_triangle[i]) out_.atoms.faces.push_back(rs.triangles[i]);
  }

  void finish() {
    const auto& atoms = out_.atoms.atoms;
    if (atoms.empty()) throw InvalidInput(name_ + ": no inner pole found (is the mesh oriented outward?)");
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
  Delaunay dt_;
  std::vector<Delaunay::Cell_handle> cells_;
  std::vector<std::vector<int>> incident_;
  std::vector<char> hull_, valid_;
  std::vector<Vec3> centre_, pole_;
  std::vector<double> pole_radius_;
};

}  // namespace

Skeleton skeletonize(const PolygonSoup& mesh, const SkeletonOptions& opt, const std::string& name) {
  return Skeletonizer(mesh, opt, name).run();
}

}  // namespace mg::skeletonize
