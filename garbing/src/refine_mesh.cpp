#include "garbing/refine_mesh.h"

#include "garbing/detail/box_grid.h"
#include "garbing/detail/line_box.h"
#include "garbing/detail/polygon_triangulation.h"
#include "garbing/errors.h"
#include "garbing/triangle_defects.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>

namespace mg {
namespace {

using Vec3 = Eigen::Vector3d;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

enum class Outcome { ray, zero_direction, missed, too_far };

using PrimitiveList = std::shared_ptr<const std::vector<PrimitiveId>>;

/// What a vertex migrates with: P (shared by the vertices of one leaf), the leaf side that
/// scales its travel, and a closed box `cover` holding the vertex's start such that P lists
/// every primitive meeting it (no box: `cover` empty).
struct Locale {
  PrimitiveList prims;
  double side = 0;
  Eigen::AlignedBox3d cover;
};

const std::vector<PrimitiveId>& list_of(const PrimitiveList& list) {
  static const std::vector<PrimitiveId> none;
  return list ? *list : none;
}

/// The vertex-migration worker: everything in the octree's root frame, G built there too.
class Refiner {
 public:
  Refiner(const CoarseMesh& m1, const Octree& tree, const MedialSurface& atoms,
          const RefineOptions& opt)
      : m1_(m1), tree_(tree), opt_(opt) {
    const auto t0 = Clock::now();
    MedialSurface local = atoms;
    for (auto& a : local.atoms) a.centre = tree.to_local(a.centre);
    shape_ = std::make_unique<TargetShape>(local, tree.cone_pairs);
    stats_.cones = shape_->cone_count();
    stats_.seconds_cones = seconds_since(t0);
  }

  RefinedMesh run() {
    const auto t0 = Clock::now();
    if (opt_.dual)
      start_from_dual();
    else
      start_from_m1();
    migrate_all();
    std::vector<std::array<int, 3>> triangles = triangulate();
    // Later rounds test only the edges at vertices the round before added.
    for (std::size_t round = 0, fresh = 0; opt_.max_gap > 0 && round < std::size_t(opt_.gap_rounds); ++round) {
      const std::size_t added = start_.size();
      if (!split_gaps(triangles, fresh)) break;
      fresh = added;
    }
    stats_.seconds_migration = seconds_since(t0);
    repair(triangles);
    for (int round = 0; round < opt_.subdivisions; ++round) {
      const auto t1 = Clock::now();
      triangles = subdivide(triangles);
      stats_.seconds_migration += seconds_since(t1);
      repair(triangles);
    }
    return build(triangles);
  }

  // --- the starting mesh ---------------------------------------------------------------------

  /// Visits P(c) of a leaf: Spheres(c), the cones of those balls (a cone of two of them
  /// twice), and Cones(c) (the cones meeting the cube through their crease only): every
  /// primitive whose solid meets the cube (leaves inside one ball, which own no M1 face, list
  /// no crease cones).
  template <class Visit>
  void for_each_leaf_primitive(int leaf, Visit&& visit) const {
    const OctreeCell& cell = tree_.cells[leaf];
    for (int a : cell.spheres) {
      visit(a);
      const auto [first, last] = shape_->cones_of_atom(a);
      for (const PrimitiveId* c = first; c != last; ++c) visit(*c);
    }
    const int n = static_cast<int>(shape_->sphere_count());
    for (int k : cell.cones) visit(n + k);
  }

  /// P(c) of a leaf, appended sorted, without repeats.
  void add_leaf_primitives(int leaf, std::vector<PrimitiveId>& out) const {
    for_each_leaf_primitive(leaf, [&](PrimitiveId g) { out.push_back(g); });
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
  }

  /// P for a point (vertices of --no-dual and --refine): the primitives meeting the closed
  /// cube of any leaf that contains it (for an active leaf, its Spheres(c) and Cones(c); a
  /// point of a cone can lie in an inactive leaf, which then contributes its cones). The leaf
  /// size for the travel limit is the smallest such leaf's.
  void point_primitives(const Vec3& p, Locale& locale) const {
    std::vector<PrimitiveId> out;
    double& side = locale.side;
    side = tree_.root_side;
    double cover_side = 0;
    // An M1 vertex is a lattice corner, but it reaches this frame through world coordinates
    // (to_local), a few ulps off: on the boundary of active and inactive leaves it could
    // fall inside an inactive leaf alone and get no primitive. Within this tolerance a leaf
    // counts as containing the point.
    const double tol = 1e-12 * tree_.root_side;
    std::vector<int> stack = {0};
    while (!stack.empty()) {
      const int c = stack.back();
      stack.pop_back();
      const OctreeCell& cell = tree_.cells[c];
      const Eigen::AlignedBox3d cube = tree_.cube(cell);
      if (!(cube.exteriorDistance(p) <= tol)) continue;
      if (!cell.is_leaf()) {
        for (int k = 0; k < 8; ++k) stack.push_back(cell.first_child + k);
        continue;
      }
      shape_->primitives_meeting_box(cube.min(), cube.max(), out);
      const double s = tree_.side(cell.level);
      side = std::min(side, s);
      if (s > cover_side) {  // the largest leaf: every primitive meeting it is listed
        cover_side = s;
        locale.cover = cube;
      }
    }
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    locale.prims = std::make_shared<const std::vector<PrimitiveId>>(std::move(out));
  }

  void start_from_dual() {
    // Vertices: the centres of M1's squares; P from the owning leaf.
    const std::size_t n = m1_.faces.size();
    start_.resize(n);
    locale_.resize(n);
    std::vector<int> owners;
    for (std::size_t f = 0; f < n; ++f) {
      const CoarseFace& face = m1_.faces[f];
      const double side = tree_.side(face.level);
      for (int a = 0; a < 3; ++a)
        start_[f][a] = (static_cast<double>(face.corner[a]) + (a == face.axis ? 0.0 : 0.5)) * side;
      owners.push_back(face.owner);
    }
    std::sort(owners.begin(), owners.end());
    owners.erase(std::unique(owners.begin(), owners.end()), owners.end());
    std::vector<Locale> per_owner(owners.size());
    tbb::parallel_for(std::size_t(0), owners.size(), [&](std::size_t i) {
      const OctreeCell& owner = tree_.cells[owners[i]];
      Locale& l = per_owner[i];
      l.side = tree_.side(owner.level);
      l.cover = tree_.cube(owner);
      std::vector<PrimitiveId> prims;
      add_leaf_primitives(owners[i], prims);
      l.prims = std::make_shared<const std::vector<PrimitiveId>>(std::move(prims));
    });
    for (std::size_t f = 0; f < n; ++f) {
      const auto it = std::lower_bound(owners.begin(), owners.end(), m1_.faces[f].owner);
      locale_[f] = per_owner[it - owners.begin()];
    }
    // Faces: one per M1 vertex, the M1 faces around it in counter-clockwise order.
    const Mesh& mesh = m1_.mesh;
    for (const auto v : mesh.vertices()) {
      std::vector<int> loop;
      for (const auto f : mesh.vf_ccw_range(v)) loop.push_back(f.idx());
      if (loop.size() < 3) {
        ++stats_.collapsed_digons;  // a pinch midpoint: its two faces share an edge instead
        continue;
      }
      // Counter-clockwise around the vertex seen from outside: the dual face points outward.
      polygons_.push_back(std::move(loop));
    }
  }

  void start_from_m1() {
    const Mesh& mesh = m1_.mesh;
    start_.resize(mesh.n_vertices());
    locale_.resize(mesh.n_vertices());
    for (const auto v : mesh.vertices()) {
      const auto& p = mesh.point(v);
      start_[v.idx()] = tree_.to_local(Vec3(p[0], p[1], p[2]));
    }
    tbb::parallel_for(std::size_t(0), start_.size(), [&](std::size_t i) {
      point_primitives(start_[i], locale_[i]);
    });
    for (const auto f : mesh.faces()) {
      std::vector<int> loop;
      for (const auto v : mesh.fv_range(f)) loop.push_back(v.idx());
      polygons_.push_back(std::move(loop));
    }
  }

  // --- migration -----------------------------------------------------------------------------

  /// Moves v along m(v) onto G: outside the union, to where the line first enters it;
  /// inside, back along -m(v) to where it leaves. From outside, first from the octree's lists
  /// (local_entry); when they cannot settle it, one line query over all primitives along a
  /// short segment (1.5 leaf sides each way, where nearly every vertex lands), then the full
  /// max_travel.
  Outcome migrate(const Vec3& v, const Locale& locale, Vec3& out) const {
    const double side = locale.side;
    Vec3 m = Vec3::Zero();
    for (PrimitiveId g : list_of(locale.prims)) m -= shape_->migration_vector(g, v);
    const double norm = m.norm();
    if (!(norm > 1e-12)) {
      out = shape_->closest_point(v);
      return Outcome::zero_direction;
    }
    const Vec3 dir = m / norm;
    double t;
    if (local_entry(v, dir, locale, opt_.max_travel * side, t)) {
      out = v + t * dir;
      return Outcome::ray;
    }
    bool inside;
    for (const double reach : {std::min(1.5, opt_.max_travel), opt_.max_travel}) {
      if (shape_->line_to_boundary(v, dir, reach * side, t, inside)) {
        out = v + t * dir;
        return Outcome::ray;
      }
      if (reach >= opt_.max_travel) break;
    }
    // Only the fallback's kind: from inside, the run containing v ends somewhere (the union is
    // bounded), so G lies beyond the reach; from outside, the line may miss the union.
    const bool anywhere = inside || shape_->first_entry(v, dir, 1e300, t);
    out = shape_->closest_point(v);
    return anywhere ? Outcome::too_far : Outcome::missed;
  }

  /// The first entry at t in (0, t_limit] of the ray v + t dir into the union, from the
  /// octree's lists alone: P over the locale's cover box, then the lists of the leaves the ray
  /// crosses after it, in order. The smallest entry so far is the first into the union once
  /// it lies within the boxes crossed: a primitive entered sooner meets one of them, and each
  /// lists every primitive meeting it (an inactive leaf meets none; a leaf inside one ball,
  /// whose list omits crease cones, is never reached: its ball is entered before it). False,
  /// for the caller's query over all primitives, when v lies in P, no entry comes by t_limit,
  /// or the walk crosses more than a few leaves or cannot follow the ray.
  bool local_entry(const Vec3& v, const Vec3& dir, const Locale& locale, double t_limit, double& t) const {
    if (!opt_.local_queries || !locale.prims || !locale.cover.contains(v)) return false;
    double first = std::numeric_limits<double>::infinity();
    bool inside = false;
    auto enter = [&](PrimitiveId g) {
      if (inside) return;  // settled: the caller's run query (and `first` may be <= 0)
      if (!shape_->is_sphere(g)) {
        // A cone entered by `first` (or holding v) meets the segment [v, v + first dir] inside
        // its bounding ball: a cheap rejection of most (dir is unit; slack for rounding).
        const Cone& k = shape_->cone(g);
        const Vec3 w = k.bound_centre - v;
        const double along = std::clamp(w.dot(dir), 0.0, first);
        if ((w - along * dir).squaredNorm() > k.bound_radius2 * (1 + 1e-9)) return;
      }
      double a, z;
      if (!shape_->ray_interval(g, v, dir, a, z) || z < 0) return;
      if (a <= 0) inside = true;  // only a primitive of P can hold v, which lies in the cover
      first = std::min(first, a);
    };
    for (PrimitiveId g : *locale.prims) enter(g);
    if (inside) return false;
    // Parameters where the line enters and leaves the closed box [lo, hi].
    const Vec3 inv = dir.cwiseInverse();
    auto crossing = [&](const Vec3& lo, const Vec3& hi, double& t0, double& t1) {
      t0 = -std::numeric_limits<double>::infinity();
      t1 = std::numeric_limits<double>::infinity();
      return detail::clip_line_to_box(lo, hi, v, inv, t0, t1);
    };
    double t0, exit;
    if (!crossing(locale.cover.min(), locale.cover.max(), t0, exit)) return false;
    constexpr int kMaxLeaves = 8;
    for (int step = 0;; ++step) {
      if (first <= exit) {
        if (first > t_limit) return false;
        t = first;
        return true;
      }
      if (exit >= t_limit || step == kMaxLeaves) return false;
      const int leaf = leaf_entered(v + exit * dir, dir);
      if (leaf < 0) return false;
      const OctreeCell& cell = tree_.cells[leaf];
      const Eigen::AlignedBox3d cube = tree_.cube(cell);
      const double s = tree_.side(cell.level);
      double next;
      // The leaf must pick the ray up where the last box let it go, and carry it further.
      if (!crossing(cube.min(), cube.max(), t0, next) || t0 > exit + 1e-9 * s || !(next > exit)) return false;
      exit = next;
      for_each_leaf_primitive(leaf, enter);
      if (inside) return false;
    }
  }

  /// The leaf holding the point q that a line with direction dir enters there: on a cell
  /// boundary (to rounding), the cell the direction points into. -1 outside the root.
  int leaf_entered(const Vec3& q, const Vec3& dir) const {
    const double unit = tree_.side(tree_.depth), tol = 1e-12 * tree_.root_side;
    std::array<std::int64_t, 3> ijk;
    for (int k = 0; k < 3; ++k) {
      const double plane = std::round(q[k] / unit);
      ijk[k] = std::abs(q[k] - plane * unit) <= tol ? static_cast<std::int64_t>(plane) - (dir[k] > 0 ? 0 : 1)
                                                    : static_cast<std::int64_t>(std::floor(q[k] / unit));
    }
    return find_cell(tree_, tree_.depth, ijk);
  }

  void count_outcome(Outcome o) {
    switch (o) {
      case Outcome::ray: break;
      case Outcome::zero_direction: ++stats_.fallback_zero_direction; break;
      case Outcome::missed: ++stats_.fallback_missed; break;
      case Outcome::too_far: ++stats_.fallback_too_far; break;
    }
  }

  /// Migrates vertices [first, end) of start_ into position_.
  void migrate_range(std::size_t first) {
    const std::size_t n = start_.size();
    position_.resize(n);
    std::vector<Outcome> outcome(n - first);
    tbb::parallel_for(first, n, [&](std::size_t i) {
      outcome[i - first] = migrate(start_[i], locale_[i], position_[i]);
    });
    for (Outcome o : outcome) count_outcome(o);
    stats_.vertices_migrated += n - first;
  }

  void migrate_all() { migrate_range(0); }

  // --- triangulation and subdivision ---------------------------------------------------------

  /// Triangulates a dual face by least total diagonal length (detail::min_diagonal_triangulation:
  /// keeps the triangles of non-planar faces well shaped). A diagonal that is already an edge
  /// of the mesh, or a diagonal of an earlier polygon (two dual faces can share more than one
  /// vertex pair), is forbidden: it would be shared by more than two faces. When no
  /// triangulation avoids them, the polygon is fanned from a new vertex at its centroid, moved
  /// onto G.
  void triangulate_polygon(const std::vector<int>& poly, detail::EdgeSet& edges,
                           std::vector<std::array<int, 3>>& out) {
    if (detail::min_diagonal_triangulation(poly, position_, edges, out)) return;
    const int n = static_cast<int>(poly.size());
    Vec3 centroid = Vec3::Zero();
    for (int v : poly) centroid += position_[v];
    centroid /= n;
    const int c = static_cast<int>(position_.size());
    start_.push_back(centroid);
    position_.push_back(shape_->closest_point(centroid));
    locale_.emplace_back();
    ++stats_.centroid_fans;
    for (int i = 0; i < n; ++i) out.push_back({poly[i], poly[(i + 1) % n], c});
  }

  std::vector<std::array<int, 3>> triangulate() {
    // Every edge of the mesh so far: the polygons' edges, then each chosen diagonal.
    detail::EdgeSet edges(position_.size());
    for (const auto& poly : polygons_)
      for (std::size_t i = 0; i < poly.size(); ++i) edges.insert(poly[i], poly[(i + 1) % poly.size()]);
    std::vector<std::array<int, 3>> triangles;
    for (const auto& poly : polygons_) triangulate_polygon(poly, edges, triangles);
    return triangles;
  }

  /// 1-to-4 subdivision: a new vertex per edge at its midpoint, migrated onto G with P from
  /// the active leaves whose closed cube contains it.
  std::vector<std::array<int, 3>> subdivide(const std::vector<std::array<int, 3>>& triangles) {
    std::map<std::pair<int, int>, int> midpoint;
    const std::size_t first_new = position_.size();
    auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto [it, inserted] = midpoint.emplace(key, static_cast<int>(start_.size()));
      if (inserted) {
        start_.push_back((position_[a] + position_[b]) / 2);
        locale_.emplace_back();
      }
      return it->second;
    };
    std::vector<std::array<int, 3>> out;
    out.reserve(4 * triangles.size());
    for (const auto& t : triangles) {
      const int ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
      out.push_back({t[0], ab, ca});
      out.push_back({ab, t[1], bc});
      out.push_back({ca, bc, t[2]});
      out.push_back({ab, bc, ca});
    }
    tbb::parallel_for(first_new, start_.size(), [&](std::size_t i) {
      point_primitives(start_[i], locale_[i]);
    });
    migrate_range(first_new);
    return out;
  }

  /// One round of gap splitting (RefineOptions::max_gap): the edges whose midpoint lies
  /// farther than max_gap leaf sides outside G get a vertex there, migrated onto G; each
  /// triangle is split by its split edges (one: 1-to-2 through the opposite corner; two: the
  /// corner triangle and the rest by its shorter diagonal; three: 1-to-4). A split whose new
  /// vertex is involved in an intersecting or degenerate triangle is undone (passes until none
  /// is: this includes one whose triangles meet a fold that was there before), so the
  /// splitting adds no fold. Later rounds test only edges at vertices the round before
  /// added (`fresh` and beyond). False if no edge was split.
  bool split_gaps(std::vector<std::array<int, 3>>& triangles, std::size_t fresh) {
    std::vector<std::pair<int, int>> edges;
    edges.reserve(3 * triangles.size() / 2);
    for (const auto& t : triangles)
      for (int k = 0; k < 3; ++k) {
        const int a = t[k], b = t[(k + 1) % 3];
        if (a < b) edges.emplace_back(a, b);  // each edge once (the mesh is closed, oriented)
      }
    std::sort(edges.begin(), edges.end());
    std::vector<char> far(edges.size(), 0);
    tbb::parallel_for(std::size_t(0), edges.size(), [&](std::size_t e) {
      const auto [a, b] = edges[e];
      if (static_cast<std::size_t>(b) < fresh) return;  // tested in an earlier round (b > a)
      const double tol = opt_.max_gap * std::min(locale_[a].side, locale_[b].side);
      // Both ends lie on G: a midpoint within tol of one cannot be farther from G.
      if ((position_[a] - position_[b]).squaredNorm() <= 4 * tol * tol) return;
      const Vec3 m = (position_[a] + position_[b]) / 2;
      // The balls of a's leaf first (cheap, and nearly always one of them is within tol).
      for (PrimitiveId g : list_of(locale_[a].prims)) {
        if (!shape_->is_sphere(g)) break;  // sorted: the spheres come first
        const double r = shape_->sphere(g).radius + tol;
        if ((m - shape_->sphere(g).centre).squaredNorm() <= r * r) return;
      }
      far[e] = !shape_->within(m, tol);
    });
    std::vector<std::size_t> split;  // edges with a candidate vertex, in edge order
    for (std::size_t e = 0; e < edges.size(); ++e)
      if (far[e]) split.push_back(e);
    if (split.empty()) return false;

    // Candidates after the current vertices: index first_new + j for split[j].
    const std::size_t first_new = start_.size(), count = split.size();
    std::vector<Vec3> from(count), to(count);
    std::vector<Locale> locale(count);
    std::vector<Outcome> outcome(count);
    tbb::parallel_for(std::size_t(0), count, [&](std::size_t j) {
      const auto [a, b] = edges[split[j]];
      from[j] = (position_[a] + position_[b]) / 2;
      point_primitives(from[j], locale[j]);
      outcome[j] = migrate(from[j], locale[j], to[j]);
    });
    std::vector<int> mid(edges.size(), -1);
    for (std::size_t j = 0; j < count; ++j) mid[split[j]] = static_cast<int>(first_new + j);
    std::vector<std::array<std::size_t, 3>> sides(triangles.size());
    tbb::parallel_for(std::size_t(0), triangles.size(), [&](std::size_t f) {
      for (int k = 0; k < 3; ++k) {
        const int a = triangles[f][k], b = triangles[f][(k + 1) % 3];
        const auto key = std::make_pair(std::min(a, b), std::max(a, b));
        const auto it = std::lower_bound(edges.begin(), edges.end(), key);
        if (it == edges.end() || *it != key)  // every edge is listed once from its a < b side
          throw std::logic_error("gap splitting: the triangles are not a closed oriented mesh");
        sides[f][k] = static_cast<std::size_t>(it - edges.begin());
      }
    });
    // The checks need only the triangles near a candidate: those whose box is near the box
    // of a triangle with a split edge grown to hold the candidates on its edges.
    std::vector<Eigen::AlignedBox3d> probes;
    auto box_of = [&](const std::array<int, 3>& t) {
      Eigen::AlignedBox3d b(position_[t[0]]);
      b.extend(position_[t[1]]);
      b.extend(position_[t[2]]);
      return b;
    };
    for (std::size_t f = 0; f < triangles.size(); ++f) {
      bool any = false;
      Eigen::AlignedBox3d b = box_of(triangles[f]);
      for (std::size_t e : sides[f])
        if (mid[e] >= 0) {
          b.extend(to[mid[e] - first_new]);
          any = true;
        }
      if (any) probes.push_back(b);
    }
    const detail::BoxGrid grid(probes);
    std::vector<std::array<int, 3>> local;
    std::vector<std::array<std::size_t, 3>> local_sides;
    for (std::size_t f = 0; f < triangles.size(); ++f)
      if (grid.near(box_of(triangles[f]))) {
        local.push_back(triangles[f]);
        local_sides.push_back(sides[f]);
      }
    PolygonSoup soup;
    soup.points = position_;
    soup.points.insert(soup.points.end(), to.begin(), to.end());
    // Each pass that undoes something undoes at least one candidate: this ends.
    while (true) {
      const std::vector<std::array<int, 3>> out = split_triangles(local, local_sides, mid, soup.points);
      std::vector<int> touched;  // the triangles at candidate vertices
      for (std::size_t f = 0; f < out.size(); ++f)
        if (std::any_of(out[f].begin(), out[f].end(), [&](int v) { return v >= static_cast<int>(first_new); }))
          touched.push_back(static_cast<int>(f));
      soup.faces.clear();
      for (const auto& t : out) soup.faces.push_back({t[0], t[1], t[2]});
      const TriangleDefects d = find_triangle_defects(soup, touched);
      bool undone = false;
      for (int v : involved_vertices(d, out))
        if (v >= static_cast<int>(first_new) && mid[split[v - first_new]] >= 0) {
          mid[split[v - first_new]] = -1;
          ++stats_.gap_undone;
          undone = true;
        }
      if (!undone) break;
    }
    // Keep the accepted candidates, renumbered in edge order.
    std::size_t kept = 0;
    for (std::size_t j = 0; j < count; ++j) {
      const std::size_t e = split[j];
      if (mid[e] < 0) continue;
      const auto [a, b] = edges[e];
      mid[e] = static_cast<int>(first_new + kept++);
      // The repair's last resort returns vertices to their start: for a new vertex, the
      // midpoint of its edge's starts, so the starts stay the fold-free dual of M1, subdivided.
      start_.push_back((start_[a] + start_[b]) / 2);
      position_.push_back(to[j]);
      locale_.push_back(std::move(locale[j]));
      count_outcome(outcome[j]);
    }
    if (kept == 0) return false;
    stats_.vertices_migrated += kept;
    stats_.gap_splits += kept;
    triangles = split_triangles(triangles, sides, mid, position_);
    return true;
  }

  /// The triangles split by the edges with a vertex (mid[edge] >= 0), as split_gaps describes.
  static std::vector<std::array<int, 3>> split_triangles(const std::vector<std::array<int, 3>>& triangles,
                                                         const std::vector<std::array<std::size_t, 3>>& sides,
                                                         const std::vector<int>& mid, const std::vector<Vec3>& points) {
    std::vector<std::array<int, 3>> out;
    out.reserve(triangles.size() + triangles.size() / 8);
    for (std::size_t f = 0; f < triangles.size(); ++f) {
      const auto& t = triangles[f];
      const std::array<int, 3> m = {mid[sides[f][0]], mid[sides[f][1]], mid[sides[f][2]]};
      const int split = (m[0] >= 0) + (m[1] >= 0) + (m[2] >= 0);
      if (split == 0) {
        out.push_back(t);
      } else if (split == 3) {
        out.push_back({t[0], m[0], m[2]});
        out.push_back({m[0], t[1], m[1]});
        out.push_back({m[2], m[1], t[2]});
        out.push_back({m[0], m[1], m[2]});
      } else if (split == 1) {
        const int k = m[0] >= 0 ? 0 : (m[1] >= 0 ? 1 : 2);  // the edge t[k] t[k+1]
        const int a = t[k], b = t[(k + 1) % 3], c = t[(k + 2) % 3];
        out.push_back({a, m[k], c});
        out.push_back({m[k], b, c});
      } else {
        const int k = m[0] < 0 ? 0 : (m[1] < 0 ? 1 : 2);  // the edge kept: t[k] t[k+1]
        const int a = t[k], b = t[(k + 1) % 3], c = t[(k + 2) % 3];
        const int mb = m[(k + 1) % 3], mc = m[(k + 2) % 3];  // on b-c and on c-a
        out.push_back({mb, c, mc});                          // the corner at c
        // The quad a, b, mb, mc by its shorter diagonal.
        if ((points[a] - points[mb]).squaredNorm() <= (points[b] - points[mc]).squaredNorm()) {
          out.push_back({a, b, mb});
          out.push_back({a, mb, mc});
        } else {
          out.push_back({a, b, mc});
          out.push_back({b, mb, mc});
        }
      }
    }
    return out;
  }

  // --- fold-overs ----------------------------------------------------------------------------

  PolygonSoup soup_of(const std::vector<std::array<int, 3>>& triangles) const {
    PolygonSoup soup;
    soup.points = position_;
    soup.faces.reserve(triangles.size());
    for (const auto& t : triangles) soup.faces.push_back({t[0], t[1], t[2]});
    return soup;
  }

  /// Vertices of the intersecting and degenerate triangles, sorted.
  static std::vector<int> involved_vertices(const TriangleDefects& d,
                                            const std::vector<std::array<int, 3>>& triangles) {
    std::vector<int> out;
    for (const auto& p : d.intersecting_pairs)
      for (int f : p) out.insert(out.end(), triangles[f].begin(), triangles[f].end());
    for (int f : d.degenerate_faces) out.insert(out.end(), triangles[f].begin(), triangles[f].end());
    std::sort(out.begin(), out.end());
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
  }

  /// Repairs fold-overs in stages, re-detecting after each round:
  /// 1. on G: the vertices of defective triangles and their neighbours move to the closest
  ///    point of G to the centroid of their neighbours (untangles while staying on G);
  /// 2. off G, as a last resort: the vertices still involved are pulled back along their
  ///    migration path, halving their step each round;
  /// 3. if some are still folded: they (and, round by round, their neighbours) return to their
  ///    starting point, the fold-free dual of M1.
  /// The vertices stages 2-3 moved are off G; they are counted (`left_off_g`).
  void repair(const std::vector<std::array<int, 3>>& triangles) {
    const auto t0 = Clock::now();
    PolygonSoup soup = soup_of(triangles);  // faces fixed; points refreshed before each check
    TriangleDefects d = find_triangle_defects(soup);
    stats_.intersecting_before += d.intersecting_pairs.size();
    stats_.degenerate_before += d.degenerate_faces.size();
    stats_.intersecting_after = d.intersecting_pairs.size();
    stats_.degenerate_after = d.degenerate_faces.size();
    if (d.intersecting_pairs.empty() && d.degenerate_faces.empty()) {
      stats_.seconds_repair += seconds_since(t0);
      return;
    }

    std::vector<std::vector<int>> ring(position_.size());
    for (const auto& t : triangles)
      for (int k = 0; k < 3; ++k) {
        ring[t[k]].push_back(t[(k + 1) % 3]);
        ring[t[k]].push_back(t[(k + 2) % 3]);
      }
    for (auto& r : ring) {
      std::sort(r.begin(), r.end());
      r.erase(std::unique(r.begin(), r.end()), r.end());
    }
    std::vector<std::vector<int>> faces_of(position_.size());
    for (std::size_t f = 0; f < triangles.size(); ++f)
      for (int v : triangles[f]) faces_of[v].push_back(static_cast<int>(f));
    // Defects can only change around moved vertices: re-detect there, keep the rest.
    auto redetect = [&](const std::vector<int>& moved_now) {
      std::vector<int> dirty;
      for (int v : moved_now) dirty.insert(dirty.end(), faces_of[v].begin(), faces_of[v].end());
      std::sort(dirty.begin(), dirty.end());
      dirty.erase(std::unique(dirty.begin(), dirty.end()), dirty.end());
      auto is_dirty = [&](int f) { return std::binary_search(dirty.begin(), dirty.end(), f); };
      soup.points = position_;
      TriangleDefects local = find_triangle_defects(soup, dirty);
      for (const auto& p : d.intersecting_pairs)
        if (!is_dirty(p[0]) && !is_dirty(p[1])) local.intersecting_pairs.push_back(p);
      for (int f : d.degenerate_faces)
        if (!is_dirty(f)) local.degenerate_faces.push_back(f);
      std::sort(local.intersecting_pairs.begin(), local.intersecting_pairs.end());
      std::sort(local.degenerate_faces.begin(), local.degenerate_faces.end());
      d = std::move(local);
    };
    std::vector<char> moved(position_.size(), 0);
    for (int round = 0; round < opt_.repair_rounds; ++round) {
      if (d.intersecting_pairs.empty() && d.degenerate_faces.empty()) break;
      std::vector<int> involved = involved_vertices(d, triangles);
      std::vector<int> grown = involved;
      for (int v : involved) grown.insert(grown.end(), ring[v].begin(), ring[v].end());
      std::sort(grown.begin(), grown.end());
      grown.erase(std::unique(grown.begin(), grown.end()), grown.end());
      std::vector<Vec3> next(grown.size());
      tbb::parallel_for(std::size_t(0), grown.size(), [&](std::size_t i) {
        Vec3 centroid = Vec3::Zero();
        for (int w : ring[grown[i]]) centroid += position_[w];
        next[i] = shape_->closest_point(centroid / static_cast<double>(ring[grown[i]].size()));
      });
      for (std::size_t i = 0; i < grown.size(); ++i) {
        position_[grown[i]] = next[i];
        moved[grown[i]] = 1;
      }
      redetect(grown);
    }
    std::vector<char> off_g(position_.size(), 0);
    const std::vector<Vec3> target = position_;
    std::vector<double> step(position_.size(), 1.0);
    for (int round = 0; round < opt_.repair_rounds; ++round) {
      if (d.intersecting_pairs.empty() && d.degenerate_faces.empty()) break;
      const std::vector<int> involved = involved_vertices(d, triangles);
      for (int v : involved) {
        step[v] /= 2;
        moved[v] = 1;
        off_g[v] = 1;
        position_[v] = start_[v] + step[v] * (target[v] - start_[v]);
        ++stats_.pulled_back;
      }
      redetect(involved);
    }
    // Still folded: put the vertices involved back where they started (the dual of M1 is
    // fold-free), spreading to their neighbours round by round.
    for (int round = 0; round < opt_.repair_rounds; ++round) {
      if (d.intersecting_pairs.empty() && d.degenerate_faces.empty()) break;
      std::vector<int> involved = involved_vertices(d, triangles);
      if (round > 0) {
        const std::size_t n = involved.size();
        for (std::size_t k = 0; k < n; ++k) involved.insert(involved.end(), ring[involved[k]].begin(), ring[involved[k]].end());
        std::sort(involved.begin(), involved.end());
        involved.erase(std::unique(involved.begin(), involved.end()), involved.end());
      }
      for (int v : involved) {
        position_[v] = start_[v];
        moved[v] = 1;
        off_g[v] = 1;
        ++stats_.pulled_back;
      }
      redetect(involved);
    }
    // Tried: moving these back to the closest point of G where that folds nothing; on hand's
    // vertex poles 2 of 3,517 could move (the rest lie in cones whose nearest surface point
    // belongs to another sheet), so they stay where the fold-free stages put them.
    stats_.left_off_g += static_cast<std::size_t>(std::count(off_g.begin(), off_g.end(), 1));
    stats_.intersecting_after = d.intersecting_pairs.size();
    stats_.degenerate_after = d.degenerate_faces.size();
    stats_.repaired_vertices += static_cast<std::size_t>(std::count(moved.begin(), moved.end(), 1));
    stats_.seconds_repair += seconds_since(t0);
  }

  RefinedMesh build(const std::vector<std::array<int, 3>>& triangles) {
    PolygonSoup soup = soup_of(triangles);
    for (auto& p : soup.points) p = tree_.to_world(p);
    RefinedMesh out;
    out.mesh = mesh_from_manifold_soup(soup, "M2");
    out.stats = stats_;
    return out;
  }

  const CoarseMesh& m1_;
  const Octree& tree_;
  const RefineOptions& opt_;
  std::unique_ptr<TargetShape> shape_;
  RefineStats stats_;
  std::vector<Vec3> start_;       // before migration (root frame)
  std::vector<Vec3> position_;    // after migration
  std::vector<Locale> locale_;    // what each vertex migrates with
  std::vector<std::vector<int>> polygons_;
};

}  // namespace

RefinedMesh refine_mesh(const CoarseMesh& m1, const Octree& tree, const MedialSurface& atoms,
                        const RefineOptions& opt) {
  validate(atoms);
  if (opt.subdivisions < 0) throw InvalidInput("refine: subdivisions must be >= 0");
  if (!(opt.max_travel > 0)) throw InvalidInput("refine: max travel must be > 0");
  if (opt.repair_rounds < 0) throw InvalidInput("refine: repair rounds must be >= 0");
  if (!(opt.max_gap >= 0)) throw InvalidInput("refine: max gap must be >= 0");
  if (opt.gap_rounds < 0) throw InvalidInput("refine: gap rounds must be >= 0");
  if (m1.faces.size() != m1.mesh.n_faces()) throw InvalidInput("refine: M1 and its faces disagree");
  return Refiner(m1, tree, atoms, opt).run();
}

}  // namespace mg
