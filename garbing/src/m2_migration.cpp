// Step 3, migration: each vertex moves along m(v) onto G, its first entry found from the
// octree's lists before the hierarchy over all primitives.
#include "m2.h"

#include "garbing/detail/line_box.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace mg::garbing::refine {
namespace {

/// Visits P(c) of a leaf: Spheres(c), the cones and slabs of those balls (one of two or three
/// of them more than once), Cones(c) and Slabs(c) (those meeting the cube where none of their
/// balls does): every primitive whose solid meets the cube (leaves inside one ball, which own
/// no M1 face, list no cones or slabs of their own).
template <class Visit>
void for_each_leaf_primitive(const Context& ctx, int leaf, Visit&& visit) {
  const OctreeCell& cell = ctx.tree.cells[leaf];
  const bool slabs = ctx.g.slab_count() > 0;
  for (int a : cell.spheres) {
    visit(a);
    const auto [first, last] = ctx.g.cones_of_atom(a);
    for (const PrimitiveId* c = first; c != last; ++c) visit(*c);
    if (!slabs) continue;
    const auto [first_slab, last_slab] = ctx.g.slabs_of_atom(a);
    for (const PrimitiveId* c = first_slab; c != last_slab; ++c) visit(*c);
  }
  const int n = static_cast<int>(ctx.g.sphere_count());
  for (int k : cell.cones) visit(n + k);
  for (int k : cell.slabs) visit(ctx.g.slab_id(k));
}

/// P(c) of a leaf, appended sorted, without repeats: the primitives whose piece meets the cube
/// (a slab of one of its balls only when its prism does).
void add_leaf_primitives(const Context& ctx, int leaf, std::vector<PrimitiveId>& out) {
  const std::size_t start = out.size();
  for_each_leaf_primitive(ctx, leaf, [&](PrimitiveId g) { out.push_back(g); });
  std::sort(out.begin() + static_cast<long>(start), out.end());
  out.erase(std::unique(out.begin() + static_cast<long>(start), out.end()), out.end());
  if (ctx.g.slab_count() == 0) return;
  const Eigen::AlignedBox3d cube = ctx.tree.cube(ctx.tree.cells[leaf]);
  out.erase(std::remove_if(out.begin() + static_cast<long>(start), out.end(),
                           [&](PrimitiveId g) {
                             return ctx.g.is_slab(g) &&
                                    !prism_meets_box(ctx.g.slab(g), cube.min(), cube.max());
                           }),
            out.end());
}

/// The leaf holding the point q that a line with direction dir enters there: on a cell
/// boundary (to rounding), the cell the direction points into. -1 outside the root.
int leaf_entered(const Octree& tree, const Vec3& q, const Vec3& dir) {
  const double unit = tree.side(tree.depth), tol = 1e-12 * tree.root_side;
  std::array<std::int64_t, 3> ijk;
  for (int k = 0; k < 3; ++k) {
    const double plane = std::round(q[k] / unit);
    ijk[k] = std::abs(q[k] - plane * unit) <= tol
                 ? static_cast<std::int64_t>(plane) - (dir[k] > 0 ? 0 : 1)
                 : static_cast<std::int64_t>(std::floor(q[k] / unit));
  }
  return find_cell(tree, tree.depth, ijk);
}

/// For local_entry: the interval [a, z], z >= 0, of the line v + t dir in the cone's solid,
/// when the cone may be entered by `first`. A cone entered by then (or holding v) meets the
/// segment [v, v + first dir] inside its bounding ball: a cheap rejection of most (dir is unit;
/// slack for rounding), before the cone is restored. Out of line: the balls' path stays small.
[[gnu::noinline]] bool cone_interval(const StoredCone& stored, const Vec3& v, const Vec3& dir,
                                     double first, double& a, double& z) {
  Vec3 centre;
  double radius2;
  bounding_ball(stored, centre, radius2);
  const Vec3 w = centre - v;
  const double along = std::clamp(w.dot(dir), 0.0, first);
  if ((w - along * dir).squaredNorm() > radius2 * (1 + 1e-9)) return false;
  return line_interval(restored(stored), v, dir, a, z) && z >= 0;
}

/// The first entry at t in (0, t_limit] of the ray v + t dir into the union, from the
/// octree's lists alone: P over the locale's cover box, then the lists of the leaves the ray
/// crosses after it, in order. The smallest entry so far is the first into the union once
/// it lies within the boxes crossed: G within each box is the union of the primitives it
/// lists (every primitive meeting it, or with pruned lists those that G's boundary there
/// needs), so the union is entered there first (an inactive leaf meets none; a leaf inside one
/// ball, whose list omits crease cones, is never reached: its ball is entered before it). False,
/// for the caller's query over all primitives, when v lies in P, no entry comes by t_limit,
/// or the walk crosses more than a few leaves or cannot follow the ray.
bool local_entry(const Context& ctx, const Vec3& v, const Vec3& dir, const Locale& locale,
                 const std::vector<PrimitiveId>& prims, double t_limit, double& t) {
  if (!ctx.opt.local_queries || !locale.has_list() || !locale.cover.contains(v)) return false;
  double first = std::numeric_limits<double>::infinity();
  bool inside = false;
  auto enter = [&](PrimitiveId g) {
    if (inside) return;  // settled: the caller's run query (and `first` may be <= 0)
    double a, z;
    if (ctx.g.is_cone(g) ? !cone_interval(ctx.g.stored_cone(g), v, dir, first, a, z)
                         : !ctx.g.ray_interval(g, v, dir, a, z) || z < 0)
      return;
    if (a <= 0) inside = true;  // only a primitive of P can hold v, which lies in the cover
    first = std::min(first, a);
  };
  for (PrimitiveId g : prims) enter(g);
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
    const int leaf = leaf_entered(ctx.tree, v + exit * dir, dir);
    if (leaf < 0) return false;
    const OctreeCell& cell = ctx.tree.cells[leaf];
    const Eigen::AlignedBox3d cube = ctx.tree.cube(cell);
    const double s = ctx.tree.side(cell.level);
    double next;
    // The leaf must pick the ray up where the last box let it go, and carry it further.
    if (!crossing(cube.min(), cube.max(), t0, next) || t0 > exit + 1e-9 * s || !(next > exit))
      return false;
    exit = next;
    for_each_leaf_primitive(ctx, leaf, enter);
    if (inside) return false;
  }
}

}  // namespace

const std::vector<PrimitiveId>& primitives_of(const Context& ctx, const Locale& locale,
                                              std::vector<PrimitiveId>& scratch) {
  scratch.clear();
  if (locale.prims) return *locale.prims;
  if (locale.leaf >= 0) add_leaf_primitives(ctx, locale.leaf, scratch);
  return scratch;
}

bool ball_within(const Context& ctx, const Locale& locale, const Vec3& p, double tol) {
  auto near = [&](PrimitiveId g) {
    const double r = ctx.g.sphere(g).radius + tol;
    return (p - ctx.g.sphere(g).centre).squaredNorm() <= r * r;
  };
  if (locale.leaf >= 0)
    return std::any_of(ctx.tree.cells[locale.leaf].spheres.begin(),
                       ctx.tree.cells[locale.leaf].spheres.end(), near);
  if (!locale.prims) return false;
  for (PrimitiveId g : *locale.prims) {
    if (!ctx.g.is_sphere(g)) break;  // sorted: the spheres come first
    if (near(g)) return true;
  }
  return false;
}

Locale leaf_locale(const Context& ctx, int leaf) {
  Locale l;
  const OctreeCell& owner = ctx.tree.cells[leaf];
  l.side = ctx.tree.side(owner.level);
  l.cover = ctx.tree.cube(owner);
  l.leaf = leaf;
  return l;
}

/// P for a point (vertices of --no-dual, --refine and gap splitting): the primitives meeting the
/// closed cube of any leaf that contains it (for an active leaf, its Spheres(c) and Cones(c); a
/// point of a cone can lie in an inactive leaf, which then contributes its cones). The leaf
/// size for the travel limit is the smallest such leaf's.
Locale point_locale(const Context& ctx, const Vec3& p) {
  Locale locale;
  std::vector<PrimitiveId> out;
  double& side = locale.side;
  side = ctx.tree.root_side;
  double cover_side = 0;
  // An M1 vertex is a lattice corner, but it reaches this frame through world coordinates
  // (to_local), a few ulps off: on the boundary of active and inactive leaves it could
  // fall inside an inactive leaf alone and get no primitive. Within this tolerance a leaf
  // counts as containing the point.
  const double tol = 1e-12 * ctx.tree.root_side;
  std::vector<int> stack = {0};
  while (!stack.empty()) {
    const int c = stack.back();
    stack.pop_back();
    const OctreeCell& cell = ctx.tree.cells[c];
    const Eigen::AlignedBox3d cube = ctx.tree.cube(cell);
    if (!(cube.exteriorDistance(p) <= tol)) continue;
    if (!cell.is_leaf()) {
      for (int k = 0; k < 8; ++k) stack.push_back(cell.first_child + k);
      continue;
    }
    ctx.g.primitives_meeting_box(cube.min(), cube.max(), out);
    const double s = ctx.tree.side(cell.level);
    side = std::min(side, s);
    if (s > cover_side) {  // the largest leaf: every primitive meeting it is listed
      cover_side = s;
      locale.cover = cube;
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  locale.prims = std::make_shared<const std::vector<PrimitiveId>>(std::move(out));
  return locale;
}

/// Moves v along m(v) onto G: outside the union, to where the line first enters it;
/// inside, back along -m(v) to where it leaves. From outside, first from the octree's lists
/// (local_entry); when they cannot settle it, one line query over all primitives along a
/// short segment (1.5 leaf sides each way, where nearly every vertex lands), then the full
/// max_travel.
Outcome migrate(const Context& ctx, const Vec3& v, const Locale& locale, Vec3& out) {
  thread_local std::vector<PrimitiveId> scratch;
  return migrate(ctx, v, locale, primitives_of(ctx, locale, scratch), out);
}

Outcome migrate(const Context& ctx, const Vec3& v, const Locale& locale,
                const std::vector<PrimitiveId>& prims, Vec3& out) {
  const double side = locale.side;
  Vec3 m = Vec3::Zero();
  for (PrimitiveId g : prims) m -= ctx.g.migration_vector(g, v);
  const double norm = m.norm();
  if (!(norm > 1e-12)) {
    out = ctx.g.closest_point(v);
    return Outcome::zero_direction;
  }
  const Vec3 dir = m / norm;
  double t;
  if (local_entry(ctx, v, dir, locale, prims, ctx.opt.max_travel * side, t)) {
    out = v + t * dir;
    return Outcome::ray;
  }
  bool inside;
  for (const double reach : {std::min(1.5, ctx.opt.max_travel), ctx.opt.max_travel}) {
    if (ctx.g.line_to_boundary(v, dir, reach * side, t, inside)) {
      out = v + t * dir;
      return Outcome::ray;
    }
    if (reach >= ctx.opt.max_travel) break;
  }
  // Only the fallback's kind: from inside, the run containing v ends somewhere (the union is
  // bounded), so G lies beyond the reach; from outside, the line may miss the union.
  const bool anywhere = inside || ctx.g.first_entry(v, dir, 1e300, t);
  out = ctx.g.closest_point(v);
  return anywhere ? Outcome::too_far : Outcome::missed;
}

void count_outcome(Outcome o, RefineStats& stats) {
  switch (o) {
    case Outcome::ray:
      break;
    case Outcome::zero_direction:
      ++stats.fallback_zero_direction;
      break;
    case Outcome::missed:
      ++stats.fallback_missed;
      break;
    case Outcome::too_far:
      ++stats.fallback_too_far;
      break;
  }
}

/// Migrates vertices [first, end) of m2.start into m2.position.
void migrate_range(const Context& ctx, Vertices& m2, std::size_t first, RefineStats& stats) {
  const std::size_t n = m2.start.size();
  m2.position.resize(n);
  std::vector<Outcome> outcome(n - first);
  // Runs of vertices with the same leaf's P (the dual's vertices come in M1's face order,
  // leaf by leaf: 1.7 per leaf on the bumpy torus): gathered once per run.
  // A vertex joins the run before it when both take P from the same leaf alone.
  auto leaf_only = [&](std::size_t i) { return !m2.locale[i].prims && m2.locale[i].leaf >= 0; };
  std::vector<std::size_t> runs;
  for (std::size_t i = first; i < n; ++i)
    if (i == first || !leaf_only(i) || !leaf_only(i - 1) ||
        m2.locale[i].leaf != m2.locale[i - 1].leaf)
      runs.push_back(i);
  runs.push_back(n);
  tbb::parallel_for(std::size_t(0), runs.size() - 1, [&](std::size_t r) {
    thread_local std::vector<PrimitiveId> scratch;  // cleared by primitives_of
    const std::vector<PrimitiveId>& prims = primitives_of(ctx, m2.locale[runs[r]], scratch);
    for (std::size_t i = runs[r]; i < runs[r + 1]; ++i)
      outcome[i - first] = migrate(ctx, m2.start[i], m2.locale[i], prims, m2.position[i]);
  });
  for (Outcome o : outcome) count_outcome(o, stats);
  stats.vertices_migrated += n - first;
}

}  // namespace mg::garbing::refine
