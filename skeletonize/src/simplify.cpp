// simplify_medial_mesh(): Q-MAT's edge collapses over a medial mesh (spherical quadric error
// times the stability ratio). The pipeline (docs/algorithm.md "Simplification"): the complex
// (closure, the union's dual complex, isolated atoms joined) -> thinning and pruning (elementary
// collapses) -> the atoms' quadrics -> greedy edge collapses under the tunnel test and the
// hull-excess bound -> sorted output.
#include "skeletonize/simplify.h"

#include "ball_tree.h"
#include "core/errors.h"
#include "core/timer.h"
#include "garbing/primitives.h"
#include "garbing/slab.h"
#include "medial_complex.h"
#include "samples.h"
#include "skeletonize/solid_query.h"
#include "skeletonize/sphere_quadric.h"
#include "skeletonize/union_topology.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>
#include <tbb/parallel_sort.h>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iterator>
#include <numeric>
#include <optional>
#include <queue>
#include <string>
#include <tuple>
#include <type_traits>

namespace mg::skeletonize {
namespace {

using Vec3 = Eigen::Vector3d;
using detail::Pair;
using detail::Quad;
using detail::Triple;

/// Two unit vectors completing u (unit) to an orthonormal basis, chosen from u alone.
std::array<Vec3, 2> perpendiculars(const Vec3& u) {
  int axis = 0;
  u.cwiseAbs().minCoeff(&axis);
  const Vec3 w1 = u.cross(Vec3::Unit(axis)).normalized();
  return {w1, u.cross(w1)};
}

/// Whether the triangle of the three centres lies in the union of the three balls. With
/// p_i(x) = r_i^2 - |x - c_i|^2, f = max_i p_i is -|x|^2 plus a convex piecewise-affine function,
/// concave on each piece (the power cells): its minimum over the triangle lies at a corner of a
/// piece: the triangle's corners (covered), the points of its sides on the radical planes of two
/// balls, and the radical centre of the three when it falls inside. Covered iff f >= 0 there.
bool covered_by_balls(const MedialAtom& a, const MedialAtom& b, const MedialAtom& c) {
  const std::array<const MedialAtom*, 3> s = {&a, &b, &c};
  auto power = [&](int i, const Vec3& x) {
    return s[i]->radius * s[i]->radius - (x - s[i]->centre).squaredNorm();
  };
  auto covered = [&](const Vec3& x) {
    const double f = std::max({power(0, x), power(1, x), power(2, x)});
    const double scale = std::max({a.radius, b.radius, c.radius});
    return f >= -1e-12 * scale * scale;
  };
  // p_i - p_j is affine: (r_i^2 - |c_i|^2) - (r_j^2 - |c_j|^2) + 2 (c_i - c_j) . x.
  auto difference = [&](int i, int j, const Vec3& x) { return power(i, x) - power(j, x); };
  for (int i = 0; i < 3; ++i)
    for (int j = i + 1; j < 3; ++j)
      for (int k = 0; k < 3; ++k) {  // side (k, k + 1)
        const Vec3 &u = s[k]->centre, &v = s[(k + 1) % 3]->centre;
        const double du = difference(i, j, u), dv = difference(i, j, v);
        if ((du < 0) == (dv < 0) || du == dv) continue;
        const double t = du / (du - dv);
        if (!covered(u + t * (v - u))) return false;
      }
  // The radical centre in the plane: x = c_a + s e1 + t e2 with p_a = p_b = p_c.
  const Vec3 e1 = b.centre - a.centre, e2 = c.centre - a.centre;
  Eigen::Matrix2d m;
  Eigen::Vector2d rhs;
  const double d0 = difference(0, 1, a.centre), d1 = difference(0, 2, a.centre);
  // difference(0, j, x) = difference(0, j, c_a) + 2 (c_a - c_j) . (x - c_a)
  m << 2 * (a.centre - b.centre).dot(e1), 2 * (a.centre - b.centre).dot(e2),
      2 * (a.centre - c.centre).dot(e1), 2 * (a.centre - c.centre).dot(e2);
  rhs << -d0, -d1;
  if (std::abs(m.determinant()) > 1e-300) {
    const Eigen::Vector2d st = m.partialPivLu().solve(rhs);
    if (st.allFinite() && st[0] >= 0 && st[1] >= 0 && st[0] + st[1] <= 1 &&
        !covered(a.centre + st[0] * e1 + st[1] * e2))
      return false;
  }
  return true;
}

/// The 26 directions of the cube's faces, edges and corners, normalised (the caps' planes).
std::vector<Vec3> cap_directions() {
  std::vector<Vec3> d;
  for (int x = -1; x <= 1; ++x)
    for (int y = -1; y <= 1; ++y)
      for (int z = -1; z <= 1; ++z)
        if (x || y || z) d.push_back(Vec3(x, y, z).normalized());
  return d;
}

/// The depth of y in the union of the balls B(c1, d1) and B(c2, d2) (the distance from y to the
/// union's boundary; negative outside both: minus the distance to the nearer). Exact: a sphere's
/// nearest point to y is the one in y's direction from its centre; when that point is buried in
/// the other ball, the nearest exposed point of that sphere lies on the crease circle.
double pair_depth(const Vec3& y, const Vec3& c1, double d1, const Vec3& c2, double d2) {
  const double r1 = (y - c1).norm(), r2 = (y - c2).norm();
  const double single = std::max(d1 - r1, d2 - r2);
  const Vec3 axis = c2 - c1;
  const double length = axis.norm();
  if (!(length > std::abs(d1 - d2)) || !(length < d1 + d2) || single <= 0) return single;
  const Vec3 u = axis / length;
  const double h = (length * length + d1 * d1 - d2 * d2) / (2 * length);  // crease plane, from c1
  const double a = std::sqrt(std::max(0.0, d1 * d1 - h * h));             // crease radius
  const double x = (y - c1).dot(u), rho = ((y - c1) - x * u).norm();
  const double crease = std::hypot(x - h, rho - a);
  // Sphere 1's nearest point is exposed when its axial coordinate is at most h, sphere 2's
  // when at least h (from c1); at a centre every direction is nearest: take the crease.
  const double s1 = r1 > 0 && d1 * x / r1 <= h ? std::abs(d1 - r1) : crease;
  const double s2 = r2 > 0 && length + d2 * (y - c2).dot(u) / r2 >= h ? std::abs(d2 - r2) : crease;
  return std::min({s1, s2, crease});
}

/// What the excess estimates know of a vertex: its sphere, the mesh's point closest to its
/// centre and the distance to it.
struct Corner {
  const MedialAtom* sphere;
  const Vec3* anchor;
  double depth;
};

/// The collapses' bounds on the excess and the shortfall rise from 1 / kBoundSteps of
/// SimplifyOptions' to theirs, doubling.
constexpr double kBoundSteps = 8;

/// The collapse loop's batches: at most kBatch candidates checked together, found among at
/// most kBatch + kBatchScan fresh ones (see collapse_edges).
constexpr std::size_t kBatch = 8;
constexpr std::size_t kBatchScan = 16;

struct Candidate {
  double cost;
  int a, b;  // a < b
  std::uint32_t version_a, version_b;
  bool clamped;  // the cost is the clamped merged atom's
};

/// The heap's order: least cost first, ties by the edge's atoms (a total order: the same
/// collapses at any thread count).
struct LaterCandidate {
  bool operator()(const Candidate& x, const Candidate& y) const {
    if (x.cost != y.cost) return x.cost > y.cost;
    if (x.a != y.a) return x.a > y.a;
    return x.b > y.b;
  }
};

class Simplifier {
 public:
  Simplifier(const PolygonSoup& object, const MedialSurface& mesh, const std::vector<Quad>& cells,
             const SimplifyOptions& opt, const std::vector<Vec3>& samples,
             const std::vector<int>& atom_of_sample, const UnionComplex* dual)
      : object_(object),
        mesh_(mesh),
        cells_(cells),
        opt_(opt),
        samples_(samples),
        atom_of_sample_(atom_of_sample),
        dual_(dual) {}

  SimplifiedMedialMesh run() {
    Stopwatch t;
    check_input();
    build_complex();
    input_excess();
    out_.stats.seconds_setup = t.restart();
    thin_cells();
    prune();
    out_.stats.seconds_prune = t.restart();
    init_quadrics();
    out_.stats.seconds_quadrics = t.restart();
    collapse_edges();
    out_.stats.seconds_collapse = t.restart();
    write_output();
    out_.stats.seconds_output = t.restart();
    return std::move(out_);
  }

 private:
  // ---- input -------------------------------------------------------------------------------

  void check_input() {
    detail::check_closed_mesh(object_, "the object");
    validate(mesh_);
    const auto& atoms = mesh_.atoms;
    for (std::size_t i = 0; i < atoms.size(); ++i)
      if (!(atoms[i].radius > 0))
        throw InvalidInput("atom " + std::to_string(i) + ": radius must be > 0 to simplify, got " +
                           std::to_string(atoms[i].radius));
    const long n = static_cast<long>(atoms.size());
    for (std::size_t k = 0; k < cells_.size(); ++k) {
      Quad c = cells_[k];
      for (int x : c)
        if (x < 0 || x >= n)
          throw InvalidInput("cell " + std::to_string(k) + ": atom index " + std::to_string(x) +
                             " out of range (" + std::to_string(n) + " atoms)");
      std::sort(c.begin(), c.end());
      const auto twice = std::adjacent_find(c.begin(), c.end());
      if (twice != c.end())
        throw InvalidInput("cell " + std::to_string(k) + ": repeats atom " +
                           std::to_string(*twice));
    }
    if (samples_.size() != atom_of_sample_.size())
      throw InvalidInput(std::to_string(samples_.size()) + " samples but " +
                         std::to_string(atom_of_sample_.size()) + " sample atoms");
    for (std::size_t k = 0; k < atom_of_sample_.size(); ++k)
      if (atom_of_sample_[k] < -1 || atom_of_sample_[k] >= n)
        throw InvalidInput("sample " + std::to_string(k) + ": atom index " +
                           std::to_string(atom_of_sample_[k]) + " out of range (" +
                           std::to_string(n) + " atoms)");
    if (!samples_.empty()) {
      std::vector<char> used(object_.points.size(), 0);
      for (const auto& f : object_.faces)
        for (int v : f) used[v] = 1;
      if (static_cast<std::size_t>(std::count(used.begin(), used.end(), 1)) > samples_.size())
        throw InvalidInput(
            "fewer samples than the object's vertices (the samples begin with them)");
    }
    if (dual_) {
      auto in_range = [&](const auto& simplices) {
        return std::all_of(simplices.begin(), simplices.end(), [&](const auto& s) {
          return std::all_of(s.begin(), s.end(), [&](int x) { return x >= 0 && x < n; });
        });
      };
      if (!in_range(dual_->edges) || !in_range(dual_->triangles) || !in_range(dual_->tetrahedra))
        throw InvalidInput("the union's dual complex names an atom out of range (" +
                           std::to_string(n) + " atoms): not the complex of these atoms");
    }
    if (opt_.target_atoms < 1) throw InvalidInput("target of 0 atoms: must be >= 1");
    if (opt_.target_atoms > atoms.size())
      throw InvalidInput("target of " + std::to_string(opt_.target_atoms) +
                         " atoms exceeds the medial mesh's " + std::to_string(atoms.size()));
    if (!(opt_.stability_weight >= 0 && std::isfinite(opt_.stability_weight)))
      throw InvalidInput("stability weight must be finite and >= 0, got " +
                         std::to_string(opt_.stability_weight));
    if (!(opt_.max_shortfall >= 0 && std::isfinite(opt_.max_shortfall)))
      throw InvalidInput("shortfall bound must be finite and >= 0, got " +
                         std::to_string(opt_.max_shortfall));
    if (!(opt_.max_excess >= 0 && std::isfinite(opt_.max_excess)))
      throw InvalidInput("hull excess bound must be finite and >= 0, got " +
                         std::to_string(opt_.max_excess));
  }

  template <class T>
  static void sort_unique(std::vector<T>& v) {
    tbb::parallel_sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  }

  /// The closure of the input (faces' sides, cells' faces and edges), restricted to the union's
  /// dual complex, isolated atoms joined; the object's distance queries.
  void build_complex() {
    const auto& atoms = mesh_.atoms;
    const int n = static_cast<int>(atoms.size());
    std::vector<Pair> edges;
    std::vector<Triple> triangles;
    std::vector<Quad> tetrahedra;
    auto add_edge = [&](int i, int j) { edges.push_back({std::min(i, j), std::max(i, j)}); };
    auto add_triangle = [&](Triple t) {
      std::sort(t.begin(), t.end());
      triangles.push_back(t);
      add_edge(t[0], t[1]);
      add_edge(t[0], t[2]);
      add_edge(t[1], t[2]);
    };
    for (const auto& e : mesh_.edges) add_edge(e[0], e[1]);
    for (const auto& f : mesh_.faces) add_triangle(f);
    for (Quad c : cells_) {
      std::sort(c.begin(), c.end());
      tetrahedra.push_back(c);
      add_triangle({c[0], c[1], c[2]});
      add_triangle({c[0], c[1], c[3]});
      add_triangle({c[0], c[2], c[3]});
      add_triangle({c[1], c[2], c[3]});
    }
    tbb::parallel_invoke([&] { sort_unique(edges); }, [&] { sort_unique(triangles); },
                         [&] { sort_unique(tetrahedra); });
    auto& s = out_.stats;
    s.atoms_before = atoms.size();
    s.edges_before = edges.size();
    s.faces_before = triangles.size();
    s.cells_before = tetrahedra.size();
    if (opt_.union_complex) {
      // Only the simplices of the union's dual complex (balls that meet), itself a complex:
      // what is left stays closed under faces.
      std::optional<UnionComplex> computed;
      if (!dual_) computed = union_complex(MedialSurface{atoms, {}, {}});
      const UnionComplex& uc = dual_ ? *dual_ : *computed;
      auto keep_common = [](auto& mine, const auto& theirs) {
        std::decay_t<decltype(mine)> kept;
        std::set_intersection(mine.begin(), mine.end(), theirs.begin(), theirs.end(),
                              std::back_inserter(kept));
        const std::size_t dropped = mine.size() - kept.size();
        mine = std::move(kept);
        return dropped;
      };
      s.dropped_edges = keep_common(edges, uc.edges);
      s.dropped_faces = keep_common(triangles, uc.triangles);
      s.dropped_cells = keep_common(tetrahedra, uc.tetrahedra);
    }

    s.diagonal = bbox_diagonal(object_.points);
    tau_ = opt_.max_excess * s.diagonal;
    delta_ = samples_.empty() ? 0 : opt_.max_shortfall * s.diagonal;
    samples_of_.assign(n, {});
    for (std::size_t k = 0; k < atom_of_sample_.size(); ++k)
      if (atom_of_sample_[k] >= 0) samples_of_[atom_of_sample_[k]].push_back(static_cast<int>(k));
    k_ = opt_.stability_weight * std::pow(s.diagonal, 4);
    solid_ = std::make_unique<SolidQuery>(object_, SolidQuery::Distances::plain);
    anchor_.resize(n);
    depth_.resize(n);
    overshoot_.resize(n);
    tbb::parallel_for(0, n, [&](int i) {
      anchor_[i] = solid_->closest_point(atoms[i].centre);
      depth_[i] = (atoms[i].centre - anchor_[i]).norm();
      overshoot_[i] = std::max(0.0, atoms[i].radius - depth_[i]);
    });

    inscribed_balls_.resize(n);
    for (int i = 0; i < n; ++i) inscribed_balls_[i] = {atoms[i].centre, depth_[i]};
    inscribed_ = std::make_unique<detail::BallTree>(inscribed_balls_);

    // Components of the complex whose balls meet (hidden atoms of the regular triangulation,
    // balls nearly inside another): joined by the edge of deepest overlap between them,
    // Kruskal's way (deepest first, ties by the atoms), until the complex's components are the
    // union's.
    tree_ = std::make_unique<detail::BallTree>(atoms);
    std::vector<int> parent(n);
    std::iota(parent.begin(), parent.end(), 0);
    auto find = [&](int x) {
      while (parent[x] != x) x = parent[x] = parent[parent[x]];
      return x;
    };
    for (const auto& e : edges) parent[find(e[0])] = find(e[1]);
    struct Join {
      double overlap;
      int i, j;
    };
    // The pairs of meeting balls in different components: each has an atom outside the
    // largest component, so only those atoms' balls are searched.
    std::vector<int> size(n, 0);
    for (int i = 0; i < n; ++i) ++size[find(i)];
    const int largest =
        n > 0 ? static_cast<int>(std::max_element(size.begin(), size.end()) - size.begin()) : -1;
    std::vector<Join> joins;
    for (int i = 0; i < n; ++i) {
      if (find(i) == largest) continue;
      tree_->find_meeting(atoms[i].centre, atoms[i].radius, [&](int j) {
        const int root = find(j);
        // A pair of two atoms outside the largest component is met from both: kept once.
        if (root != find(i) && (root == largest || j > i))
          joins.push_back(
              {atoms[i].radius + atoms[j].radius - (atoms[i].centre - atoms[j].centre).norm(),
               std::min(i, j), std::max(i, j)});
        return false;
      });
    }
    std::sort(joins.begin(), joins.end(), [](const Join& x, const Join& y) {
      if (x.overlap != y.overlap) return x.overlap > y.overlap;
      return std::tie(x.i, x.j) < std::tie(y.i, y.j);
    });
    const std::size_t before = edges.size();
    for (const Join& j : joins) {
      if (!(j.overlap > 0) || find(j.i) == find(j.j)) continue;
      parent[find(j.i)] = find(j.j);
      add_edge(j.i, j.j);
    }
    s.joined_isolated = edges.size() - before;
    sort_unique(edges);

    complex_ = std::make_unique<detail::MedialComplex>(n, edges, triangles, tetrahedra);
    s.complex_components_before = complex_->components();
    s.complex_euler_before = complex_->euler();
    spheres_ = atoms;
  }

  // ---- hull excess ---------------------------------------------------------------------------

  Corner corner(int v) const { return {&spheres_[v], &anchor_[v], depth_[v]}; }

  /// How far the interpolated ball (weights w over the corners) sticks out of the object, at
  /// most: its radius - the distance from its centre to the mesh (the ball of that radius lies
  /// inside when the centre does; the centres here interpolate centres inside). Certified
  /// bounds first: the balls B(c_k, depth_k) lie inside the object, so the distance is at least
  /// y's depth in one of them, or in the union of two (pair_depth); when a bound already keeps
  /// the excess at most `over`, it is returned (an upper bound), otherwise the exact distance is
  /// queried.
  ///
  /// With `decide`, only whether the excess passes `over` is needed: when it does not, `over`
  /// itself may be returned, and the exact query is first a test for a point of the mesh closer
  /// than r - over.
  template <std::size_t N>
  double ball_excess(const std::array<Corner, N>& c, const std::array<double, N>& w, double over,
                     bool decide = false) const {
    Vec3 y = Vec3::Zero();
    double r = 0;
    for (std::size_t k = 0; k < N; ++k) {
      y += w[k] * c[k].sphere->centre;
      r += w[k] * c[k].sphere->radius;
    }
    double lower = -INFINITY;
    std::size_t nearest = 0;
    for (std::size_t k = 0; k < N; ++k) {
      const double d = c[k].depth - (y - c[k].sphere->centre).norm();
      if (d > lower) {
        lower = d;
        nearest = k;
      }
    }
    if (r - lower <= over) return r - lower;
    // Tighter: the depth in the union of two corner balls (both inside the object).
    for (std::size_t i = 0; i < N; ++i)
      for (std::size_t j = i + 1; j < N; ++j)
        lower = std::max(
            lower, pair_depth(y, c[i].sphere->centre, c[i].depth, c[j].sphere->centre, c[j].depth));
    if (r - lower <= over) return r - lower;
    // Tighter still: the depth in the union of every input atom's inscribed ball.
    lower = inscribed_->deepest(y, lower);
    if (r - lower <= over) return r - lower;
    // Exact: the centre may have left the object (a new cone or slab's axis crossing its
    // boundary), then the ball sticks out by r + d. The inside test only where it decides:
    // y in an inscribed ball (lower > 0) is inside, and r - d over `over` is refused anyway.
    // (The test compares squared distances, the exact path r - sqrt(d2): they may differ at
    // the last ulp.)
    if (decide && !solid_->within(y, r - over)) {
      // r - d <= over: enough where y is inside (certified, or tested); outside, r + d.
      if (lower > 0 || solid_->contains(y)) return over;
      return r + solid_->distance(y, *c[nearest].anchor);
    }
    const double d = solid_->distance(y, *c[nearest].anchor);
    if (lower > 0 || r - d > over) return r - d;
    return solid_->contains(y) ? r - d : r + d;
  }

  /// Interior samples along a length: spaced by at most half `radius`, 1 to 15.
  static int samples_along(double length, double radius) {
    const double n = std::ceil(length / (0.5 * radius)) - 1;
    return static_cast<int>(std::clamp(n, 1.0, 15.0));
  }

  /// Estimated excess of a cone (the hull of two spheres): at interpolated balls spaced by at
  /// most half the smaller radius (at least the middle one, at most 15). Exact queries only
  /// where the certified bound passes `over` (see ball_excess).
  double cone_excess(const Corner& p, const Corner& q, double over, bool decide = false) const {
    const MedialAtom &a = *p.sphere, &b = *q.sphere;
    const int n = samples_along((a.centre - b.centre).norm(), std::min(a.radius, b.radius));
    double worst = -INFINITY;
    for (int k = 1; k <= n; ++k) {
      const double t = static_cast<double>(k) / (n + 1);
      worst = std::max(worst, ball_excess<2>({p, q}, {1 - t, t}, over, decide));
    }
    return worst;
  }

  /// Estimated excess of a slab (the hull of three spheres) away from its edges: at the
  /// centroid and the interior points of a barycentric grid spaced as the cones'.
  double slab_excess(const Corner& p, const Corner& q, const Corner& r, double over,
                     bool decide = false) const {
    const MedialAtom &a = *p.sphere, &b = *q.sphere, &c = *r.sphere;
    const double longest = std::max(
        {(a.centre - b.centre).norm(), (b.centre - c.centre).norm(), (c.centre - a.centre).norm()});
    const int n = samples_along(longest, std::min({a.radius, b.radius, c.radius})) + 1;
    double worst = ball_excess<3>({p, q, r}, {1.0 / 3, 1.0 / 3, 1.0 / 3}, over, decide);
    for (int i = 1; i < n; ++i)
      for (int j = 1; i + j < n; ++j) {
        const double u = static_cast<double>(i) / n, v = static_cast<double>(j) / n;
        worst = std::max(worst, ball_excess<3>({p, q, r}, {1 - u - v, u, v}, over, decide));
      }
    return worst;
  }

  /// The estimated excess of every simplex of the input complex, made monotone (a simplex's at
  /// least its faces'; a cell's is its faces' maximum: its hull's boundary lies on their hulls).
  /// Values under tau are certified upper bounds, not exact.
  void input_excess() {
    edges0_ = complex_->edge_list();
    triangles0_ = complex_->triangle_list();
    edge_excess_.assign(edges0_.size(), 0);
    triangle_excess_.assign(triangles0_.size(), 0);
    if (!(tau_ > 0)) return;
    tbb::parallel_for(std::size_t(0), edges0_.size(), [&](std::size_t i) {
      const auto& e = edges0_[i];
      edge_excess_[i] = cone_excess(corner(e[0]), corner(e[1]), tau_);
    });
    tbb::parallel_for(std::size_t(0), triangles0_.size(), [&](std::size_t i) {
      const auto& t = triangles0_[i];
      triangle_excess_[i] =
          std::max({slab_excess(corner(t[0]), corner(t[1]), corner(t[2]), tau_),
                    excess_of({t[0], t[1]}), excess_of({t[0], t[2]}), excess_of({t[1], t[2]})});
    });
  }

  /// The input excess of an edge, triangle or cell (sorted atoms) of the input complex.
  double excess_of(const std::vector<int>& s) const {
    if (s.size() == 2) {
      const auto it = std::lower_bound(edges0_.begin(), edges0_.end(), Pair{s[0], s[1]});
      return edge_excess_[it - edges0_.begin()];
    }
    if (s.size() == 3) {
      const auto it =
          std::lower_bound(triangles0_.begin(), triangles0_.end(), Triple{s[0], s[1], s[2]});
      return triangle_excess_[it - triangles0_.begin()];
    }
    double worst = -INFINITY;
    for (const auto& f : facets(s)) worst = std::max(worst, excess_of(f));
    return worst;
  }

  // ---- thinning and pruning ------------------------------------------------------------------

  static std::vector<std::vector<int>> facets(const std::vector<int>& s) {
    std::vector<std::vector<int>> out;
    for (std::size_t k = 0; k < s.size(); ++k) {
      std::vector<int> f;
      for (std::size_t j = 0; j < s.size(); ++j)
        if (j != k) f.push_back(s[j]);
      out.push_back(std::move(f));
    }
    return out;
  }

  bool present(const std::vector<int>& s) const {
    if (s.size() == 2) return complex_->has_edge(s[0], s[1]);
    if (s.size() == 3) return complex_->has_triangle({s[0], s[1], s[2]});
    return complex_->has_tetrahedron({s[0], s[1], s[2], s[3]});
  }

  /// The simplices one dimension up containing s (an edge or a triangle).
  int cofaces(const std::vector<int>& s) const {
    if (s.size() == 2) return complex_->triangles_on_edge(s[0], s[1]);
    if (s.size() == 3) return complex_->tetrahedra_on_triangle({s[0], s[1], s[2]});
    return 0;
  }

  /// The free face of s (a facet whose one coface is s) of the largest input excess (ties: the
  /// first in order); empty when none.
  std::vector<int> free_face(const std::vector<int>& s) const {
    std::vector<int> best;
    double best_excess = -INFINITY;
    for (const auto& f : facets(s)) {
      if (cofaces(f) != 1) continue;
      const double e = excess_of(f);
      if (best.empty() || e > best_excess) {
        best = f;
        best_excess = e;
      }
    }
    return best;
  }

  /// Thinning: in rounds (layers), every cell with a free face at the start of a round goes
  /// with its free face of the largest excess, until none has one. The envelope has no cells;
  /// what is left is a complex of triangles and edges, as Q-MAT's.
  void thin_cells() {
    auto& st = out_.stats;
    std::vector<Quad> cells = complex_->tetrahedron_list();
    while (!cells.empty()) {
      std::vector<Quad> kept;
      std::vector<std::vector<int>> removable;
      for (const Quad& c : cells) {
        const std::vector<int> cell(c.begin(), c.end());
        if (free_face(cell).empty())
          kept.push_back(c);
        else
          removable.push_back(cell);
      }
      if (removable.empty()) break;
      for (const auto& cell : removable) {
        const std::vector<int> face = free_face(cell);
        if (face.empty()) {  // its free face went with another cell: next round
          kept.push_back({cell[0], cell[1], cell[2], cell[3]});
          continue;
        }
        complex_->remove_maximal(cell);
        complex_->remove_maximal(face);
        ++st.thinned_cells;
        ++st.thinned_faces;
      }
      std::sort(kept.begin(), kept.end());
      cells = std::move(kept);
    }
  }

  /// Whether removing the maximal simplex s alone opens or closes only a loop covered by balls:
  /// a triangle whose three balls cover it; an edge ab with a common neighbour c whose triangle
  /// abc the three balls cover (the loop a-b-c).
  bool covered_removal(const std::vector<int>& s) const {
    const auto& a = spheres_;
    if (s.size() == 3) return covered_by_balls(a[s[0]], a[s[1]], a[s[2]]);
    const auto& n0 = complex_->neighbours(s[0]);
    const auto& n1 = complex_->neighbours(s[1]);
    std::vector<int> common;
    std::set_intersection(n0.begin(), n0.end(), n1.begin(), n1.end(), std::back_inserter(common));
    return std::any_of(common.begin(), common.end(),
                       [&](int c) { return covered_by_balls(a[s[0]], a[s[1]], a[c]); });
  }

  /// Pruning, in rounds, worst excess first, of the edges and triangles sticking out by more
  /// than tau: one free in its one coface goes with it (an elementary collapse); a maximal one
  /// goes alone when covered_removal() allows. Those left are counted.
  void prune() {
    if (!(tau_ > 0)) return;
    auto& st = out_.stats;
    std::vector<std::pair<double, std::vector<int>>> items;
    for (std::size_t i = 0; i < triangles0_.size(); ++i)
      if (triangle_excess_[i] > tau_)
        items.push_back({triangle_excess_[i], {triangles0_[i].begin(), triangles0_[i].end()}});
    for (std::size_t i = 0; i < edges0_.size(); ++i)
      if (edge_excess_[i] > tau_)
        items.push_back({edge_excess_[i], {edges0_[i].begin(), edges0_[i].end()}});
    std::sort(items.begin(), items.end(), [](const auto& x, const auto& y) {
      if (x.first != y.first) return x.first > y.first;
      return x.second < y.second;
    });
    std::vector<char> done(items.size(), 0);
    for (bool progress = true; progress;) {
      progress = false;
      for (std::size_t i = 0; i < items.size(); ++i) {
        if (done[i]) continue;
        const std::vector<int>& face = items[i].second;
        if (!present(face)) {
          done[i] = 1;
          continue;
        }
        const int n = cofaces(face);
        if (n == 0 && covered_removal(face)) {
          complex_->remove_maximal(face);
          (face.size() == 3 ? st.removed_faces : st.removed_edges) += 1;
        } else if (n == 1) {
          // Its one coface: a triangle on the edge, or a cell on the triangle; maximal.
          std::vector<int> coface;
          if (face.size() == 2) {
            for (const auto& p : complex_->triangle_links(face[0]))
              if (p[0] == face[1] || p[1] == face[1])
                coface = {face[0], p[0] == face[1] ? p[1] : p[0], face[1]};
          } else {
            for (const auto& q : complex_->tetrahedron_links(face[0]))
              if (std::find(q.begin(), q.end(), face[1]) != q.end() &&
                  std::find(q.begin(), q.end(), face[2]) != q.end())
                coface = {face[0], q[0], q[1], q[2]};
          }
          std::sort(coface.begin(), coface.end());
          if (cofaces(coface) != 0) continue;  // a cell on the triangle: later
          complex_->remove_maximal(coface);
          complex_->remove_maximal(face);
          (coface.size() == 4 ? st.pruned_cells : st.pruned_faces) += 1;
          (face.size() == 3 ? st.pruned_faces : st.pruned_edges) += 1;
        } else {
          continue;
        }
        done[i] = 1;
        progress = true;
      }
    }
    for (std::size_t i = 0; i < items.size(); ++i)
      if (!done[i] && present(items[i].second)) ++st.kept_excess;
  }

  // ---- quadrics ------------------------------------------------------------------------------

  /// Each atom's quadric: the tangent planes of its slabs (Q-MAT), weighted by a third of the
  /// tangent triangle's area; for an edge on no face, or a side of a face without tangent
  /// planes, the cone's tangent planes along four generatrices, weighted by an eighth of its
  /// lateral area each end; and the cap: the planes tangent to the atom's own ball in the 26
  /// directions where that point lies in no other input ball, each weighted by 1/26 of the
  /// sphere's area.
  void init_quadrics() {
    const auto& a = spheres_;
    quadric_.assign(a.size(), SphereQuadric{});
    if (opt_.surface_planes && !samples_.empty()) {
      surface_quadrics();
      return;
    }
    std::vector<Pair> cone_edges;
    for (const Triple& t : complex_->triangle_list()) {
      // The slab's two tangent triangles (garbing's slab.h), or its edges' cones without them.
      const MedialAtom &x = a[t[0]], &y = a[t[1]], &z = a[t[2]];
      const bool flat = garbing::collinear_centres(x, y, z);
      const garbing::Slab slab = flat ? garbing::Slab{} : garbing::make_slab(x, y, z, 0, 1, 2);
      if (flat || !slab.has_tangent_triangles) {
        cone_edges.push_back({t[0], t[1]});
        cone_edges.push_back({t[0], t[2]});
        cone_edges.push_back({t[1], t[2]});
        continue;
      }
      const auto& tri = slab.tangent[0];
      const double area = 0.5 * (tri[1] - tri[0]).cross(tri[2] - tri[0]).norm();
      for (int side = 0; side < 2; ++side)
        for (int v : t)
          quadric_[v].add_plane(slab.tangent_normal[side], slab.tangent[side][0], area / 3);
    }
    for (const Pair& e : complex_->edge_list())
      if (complex_->triangles_on_edge(e[0], e[1]) == 0) cone_edges.push_back(e);
    sort_unique(cone_edges);
    for (const Pair& e : cone_edges) {
      const MedialAtom &p = a[e[0]], &q = a[e[1]];
      const Vec3 axis = q.centre - p.centre;
      const double length = axis.norm();
      if (!(length > std::abs(p.radius - q.radius))) continue;  // one ball holds the other
      const Vec3 u = axis / length;
      const double sigma = (p.radius - q.radius) / length, cosine = std::sqrt(1 - sigma * sigma);
      const double lateral = M_PI * (p.radius + q.radius) * cosine * length * cosine;
      const auto w = perpendiculars(u);
      for (const Vec3& dir : {Vec3(w[0]), Vec3(-w[0]), Vec3(w[1]), Vec3(-w[1])}) {
        const Vec3 n = sigma * u + cosine * dir;
        quadric_[e[0]].add_plane(n, p.centre + p.radius * n, lateral / 8);
        quadric_[e[1]].add_plane(n, q.centre + q.radius * n, lateral / 8);
      }
    }
    // Caps, in parallel per atom (each writes its own quadric).
    const std::vector<Vec3> dirs = cap_directions();
    tbb::parallel_for(std::size_t(0), a.size(), [&](std::size_t i) {
      const double weight = 4 * M_PI * a[i].radius * a[i].radius / static_cast<double>(dirs.size());
      for (const Vec3& d : dirs) {
        const Vec3 t = a[i].centre + a[i].radius * d;
        const bool hidden = tree_->find_meeting(t, 0.0, [&](int j) {
          return j != static_cast<int>(i) && (t - a[j].centre).norm() < a[j].radius * (1 - 1e-9);
        });
        if (!hidden) quadric_[i].add_plane(d, t, weight);
      }
    });
  }

  /// Each face's plane, weighted by its area, shared equally among the atoms of the samples on
  /// it: its corners (the first samples are the used vertices, in order) and the other samples
  /// whose closest triangle it is.
  void surface_quadrics() {
    const auto tris = fan_triangles(object_).corners;
    std::vector<int> rank(object_.points.size(), -1);
    int used = 0;
    for (const auto& f : object_.faces)
      for (int v : f) rank[v] = 0;
    for (std::size_t v = 0; v < rank.size(); ++v)
      if (rank[v] == 0) rank[v] = used++;
    std::vector<int> face_of(samples_.size(), -1);
    tbb::parallel_for(std::size_t(used), samples_.size(),
                      [&](std::size_t s) { face_of[s] = solid_->closest_triangle(samples_[s]); });
    // The faces' normals point out of the solid when the fan triangles enclose a positive
    // volume (the mesh is consistently oriented; reversed, every normal is flipped).
    double volume = 0;
    for (const auto& t : tris)
      volume += object_.points[t[0]].dot(object_.points[t[1]].cross(object_.points[t[2]]));
    const double outward = volume < 0 ? -1.0 : 1.0;
    std::vector<std::vector<int>> on(tris.size());
    for (std::size_t f = 0; f < tris.size(); ++f)
      for (int v : tris[f]) on[f].push_back(atom_of_sample_[rank[v]]);
    for (std::size_t s = used; s < samples_.size(); ++s)
      if (face_of[s] >= 0) on[face_of[s]].push_back(atom_of_sample_[s]);
    for (std::size_t f = 0; f < tris.size(); ++f) {
      const Vec3 &p0 = object_.points[tris[f][0]], &p1 = object_.points[tris[f][1]],
                 &p2 = object_.points[tris[f][2]];
      const Vec3 cross = (p1 - p0).cross(p2 - p0);
      const double norm = cross.norm();
      if (!(norm > 0)) continue;
      std::size_t count = 0;
      for (int x : on[f]) count += x >= 0;
      if (count == 0) continue;
      const double weight = norm / 2 / static_cast<double>(count);
      for (int x : on[f])
        if (x >= 0) quadric_[x].add_plane(outward * cross / norm, p0, weight);
    }
  }

  // ---- collapses -----------------------------------------------------------------------------

  /// The merged atom of {a, b} and the collapse's cost. With `clamp`, the radius is clamped so
  /// that the ball sticks out of the object no further than the input atoms merged into a or b
  /// did (0 for clamped poles): r <= distance(centre, mesh) + their overshoot, and the error
  /// re-evaluated. (The queue's costs are first computed without it, see collapse_edges.)
  /// With `nearest`, the mesh's point closest to the merged centre is kept there when the
  /// clamp queried it.
  Candidate evaluate(int a, int b, bool clamp, MergedAtom* merged = nullptr,
                     bool* clamped = nullptr, std::optional<Vec3>* nearest = nullptr) const {
    SphereQuadric q = quadric_[a];
    q += quadric_[b];
    MergedAtom m = place_merged_atom(q, spheres_[a], spheres_[b]);
    bool was_clamped = false;
    if (clamp) {
      const double allowed = std::max(overshoot_[a], overshoot_[b]);
      const double lower = std::max(depth_[a] - (m.atom.centre - spheres_[a].centre).norm(),
                                    depth_[b] - (m.atom.centre - spheres_[b].centre).norm());
      if (m.atom.radius > lower + allowed) {
        const Vec3 p = solid_->closest_point(m.atom.centre, anchor_[a]);
        if (nearest) *nearest = p;
        const double d = (m.atom.centre - p).norm() + allowed;
        if (m.atom.radius > d && d > 0) {
          m.atom.radius = d;
          m.error = q.error(m.atom);
          was_clamped = true;
        }
      }
    }
    if (merged) *merged = m;
    if (clamped) *clamped = was_clamped;
    double cost = m.error;
    if (opt_.stability) {
      const double gamma = stability_ratio(spheres_[a], spheres_[b]);
      cost = (m.error + k_) * gamma * gamma;
    }
    return {cost, a, b, version_[a], version_[b], clamp};
  }

  /// The estimated excess of the star the collapse of {a, b} into m would leave: m's ball, its
  /// cones and its slabs; stops once over `over`.
  double star_excess(int a, int b, const Corner& m, double over) const {
    double worst = m.sphere->radius - m.depth;
    if (worst > over) return worst;
    for (int side : {a, b}) {
      const int other = side == a ? b : a;
      for (int u : complex_->neighbours(side)) {
        if (u == other || (side == b && complex_->has_edge(a, u))) continue;
        worst = std::max(worst, cone_excess(m, corner(u), over, true));
        if (worst > over) return worst;
      }
      for (const Pair& p : complex_->triangle_links(side)) {
        if (p[0] == other || p[1] == other) continue;
        Triple t = {a, p[0], p[1]};
        std::sort(t.begin(), t.end());
        if (side == b && complex_->has_triangle(t)) continue;
        worst = std::max(worst, slab_excess(m, corner(p[0]), corner(p[1]), over, true));
        if (worst > over) return worst;
      }
    }
    return worst;
  }

  /// The largest distance from the samples of a and b to the solid of the star the collapse of
  /// {a, b} into m would leave (m's ball, its cones and slabs) and the neighbours' balls; stops
  /// once over `over`. An upper bound on each sample's distance to the whole envelope; a sample
  /// inside counts 0. With `record`, every sample's distance is written there instead. Unlike
  /// the excess bound, nothing is allowed for what the poles already lacked: a sample farther
  /// than delta outside its pole's star blocks every collapse of that atom (measured: allowing
  /// it, hand's 2 % went from 2.76 to 3.77 %).
  ///
  /// A refusal's sample (the one found over `over`) is written to `culprit` as {atom, position
  /// in its list}: the caller moves it to the front, where the next try of that atom meets it
  /// first (an atom whose samples block one collapse mostly blocks its other ones for the same
  /// samples).
  double star_shortfall(int a, int b, const MedialAtom& m, double over,
                        std::vector<double>* record = nullptr,
                        std::pair<int, std::size_t>* culprit = nullptr) const {
    if (samples_of_[a].empty() && samples_of_[b].empty()) return 0;
    std::vector<MedialAtom> balls = {m};
    std::vector<garbing::Cone> cones;
    std::vector<garbing::Slab> slabs;
    auto add_hull = [&](const MedialAtom& u) {
      const double length = (u.centre - m.centre).norm();
      if (length > std::abs(u.radius - m.radius))
        cones.push_back(garbing::make_cone(m, u, 0, 1));
      else if (u.radius > m.radius)
        balls.push_back(u);
    };
    std::vector<int> seen;
    for (int side : {a, b})
      for (int u : complex_->neighbours(side)) {
        if (u == a || u == b || std::find(seen.begin(), seen.end(), u) != seen.end()) continue;
        seen.push_back(u);
        balls.push_back(spheres_[u]);
        add_hull(spheres_[u]);
      }
    for (int side : {a, b})
      for (const Pair& p : complex_->triangle_links(side)) {
        if (p[0] == a || p[0] == b || p[1] == a || p[1] == b) continue;
        const MedialAtom &u = spheres_[p[0]], &w = spheres_[p[1]];
        if (!garbing::collinear_centres(m, u, w))
          slabs.push_back(garbing::make_slab(m, u, w, 0, 1, 2));
      }
    double worst = 0;
    // Both lists' fronts first (each the sample that blocked its atom's last refused collapse),
    // then the rest of a's, then of b's.
    const std::size_t na = samples_of_[a].size(), nb = a == b ? 0 : samples_of_[b].size();
    auto at = [&](std::size_t j) -> std::pair<int, std::size_t> {
      if (na == 0 || nb == 0) return {na > 0 ? a : b, j};
      if (j < 2) return {j == 0 ? a : b, 0};
      return j - 1 < na ? std::pair<int, std::size_t>{a, j - 1}
                        : std::pair<int, std::size_t>{b, j - na};
    };
    for (std::size_t j = 0; j < na + nb; ++j) {
      const auto [side, i] = at(j);
      const int k = samples_of_[side][i];
      const Vec3& s = samples_[k];
      double d = INFINITY;
      for (const MedialAtom& ball : balls) {
        if (!record && d <= worst) break;
        d = std::min(d, (s - ball.centre).norm() - ball.radius);
      }
      for (const garbing::Cone& cone : cones) {
        if (!record && d <= worst) break;
        d = std::min(d, garbing::hull_distance(cone, s));
      }
      for (const garbing::Slab& slab : slabs) {
        if (!record && d <= worst) break;
        d = std::min(d, garbing::slab_distance(slab, s));
      }
      if (record) {
        (*record)[k] = d;
        continue;
      }
      worst = std::max(worst, d);
      if (worst > over) {
        if (culprit) *culprit = {side, i};
        return worst;
      }
    }
    return worst;
  }

  /// Whether the point lies inside the object: certified by a vertex's ball of radius depth
  /// (inside the object) holding it, else CGAL's inside test.
  bool inside(const Vec3& p, int a, int b) const {
    for (int v : {a, b})
      if ((p - spheres_[v].centre).norm() < depth_[v]) return true;
    return solid_->contains(p);
  }

  /// What the checks of a collapse found, in the order the collapse loop applies them (the
  /// first refusal ends them). Computed from the state alone, without side effects: the
  /// candidates of a batch are checked in parallel.
  struct Check {
    enum class Stage { topology, back, outside, shortfall, excess, passed };
    Stage stage = Stage::passed;  // the refusal, or passed
    std::size_t loops = 0;        // the loops the collapse contracts
    MergedAtom m;                 // the merged atom, clamped
    bool clamped = false;
    Candidate exact{};  // the candidate at the clamped atom's cost
    double shortfall = 0;
    std::pair<int, std::size_t> culprit{-1, 0};  // the sample that refused it (shortfall)
    Vec3 anchor = Vec3::Zero();                  // the mesh's point closest to m's centre
    double depth = 0, overshoot = 0, excess = 0;
  };

  /// Checks the collapse of candidate c at the bounds' `scale`. It reads the data of c's atoms,
  /// of their neighbours and the complex's simplices on them, nothing else that collapses
  /// change: a collapse of {x, y} changes the data of x and y and the stars of N[x] and N[y].
  /// (has_triangle may read a neighbour's lists, which a collapse of {x, y} relabels when that
  /// neighbour is in N[y]; its answer for a triangle of c's atom and two vertices other than x
  /// and y does not change.)
  ///
  /// `next`: the candidate after c (none: the last). When clamping raises c's cost past it, c
  /// goes back in line with its clamped cost (stage back).
  Check check(const Candidate& c, double scale, const Candidate* next) const {
    Check r;
    // The loops the collapse contracts: each must be covered by its three balls (then it is
    // no tunnel of the envelope).
    const auto loops = complex_->free_link_components(c.a, c.b);
    const bool keeps_tunnels = std::all_of(loops.begin(), loops.end(), [&](const auto& comp) {
      return std::any_of(comp.begin(), comp.end(), [&](int x) {
        return covered_by_balls(spheres_[c.a], spheres_[c.b], spheres_[x]);
      });
    });
    if (!keeps_tunnels) {
      r.stage = Check::Stage::topology;
      return r;
    }
    r.loops = loops.size();
    std::optional<Vec3> nearest;
    r.exact = evaluate(c.a, c.b, true, &r.m, &r.clamped, &nearest);
    if (!c.clamped && r.exact.cost > c.cost && next && LaterCandidate{}(r.exact, *next)) {
      r.stage = Check::Stage::back;
      return r;
    }
    if (!inside(r.m.atom.centre, c.a, c.b)) {
      r.stage = Check::Stage::outside;
      return r;
    }
    if (delta_ > 0) {
      const double allowed = scale * delta_;
      r.shortfall = star_shortfall(c.a, c.b, r.m.atom, allowed, nullptr, &r.culprit);
      if (r.shortfall > allowed) {
        r.stage = Check::Stage::shortfall;
        return r;
      }
    }
    r.anchor = nearest ? *nearest : solid_->closest_point(r.m.atom.centre, anchor_[c.a]);
    r.depth = (r.m.atom.centre - r.anchor).norm();
    r.overshoot = std::max(overshoot_[c.a], overshoot_[c.b]);
    if (tau_ > 0) {
      const double allowed = std::max(scale * tau_, r.overshoot);
      r.excess = star_excess(c.a, c.b, {&r.m.atom, &r.anchor, r.depth}, allowed);
      if (r.excess > allowed) {
        r.stage = Check::Stage::excess;
        return r;
      }
    }
    return r;
  }

  void collapse_edges() {
    auto& st = out_.stats;
    version_.assign(spheres_.size(), 0);
    std::priority_queue<Candidate, std::vector<Candidate>, LaterCandidate> queue;
    auto push_all = [&] {
      const std::vector<Pair> edges = complex_->edge_list();
      std::vector<Candidate> c(edges.size());
      tbb::parallel_for(std::size_t(0), edges.size(),
                        [&](std::size_t i) { c[i] = evaluate(edges[i][0], edges[i][1], false); });
      queue = decltype(queue)(LaterCandidate{}, std::move(c));
    };
    const long target = static_cast<long>(opt_.target_atoms);
    long round_collapses = 0;
    // What the samples already lack (their distance outside their atom's star before any
    // collapse), for the statistics.
    std::vector<double> initial(samples_.size(), 0);
    if (delta_ > 0)
      tbb::parallel_for(std::size_t(0), spheres_.size(), [&](std::size_t i) {
        const int a = static_cast<int>(i);
        if (complex_->alive(a)) star_shortfall(a, a, spheres_[a], INFINITY, &initial);
      });
    for (double d : initial) st.input_shortfall = std::max(st.input_shortfall, d);
    push_all();
    st.rounds = 1;
    // The bounds start at 1 / kBoundSteps of tau and delta and double whenever a pass over
    // the queue collapses nothing: the collapses that keep the envelope closest go first. A
    // refused edge waits, with the scale its measured excess or shortfall needs, until a pass
    // reaches that scale (a topology or outside refusal: the next pass); an edge whose atoms
    // change meanwhile is pushed afresh.
    double scale = 1.0 / kBoundSteps;
    struct Refused {
      Candidate candidate;
      double needs;  // the scale at which to try again
    };
    std::vector<Refused> refused;
    auto refuse = [&](const Candidate& c, double needs) { refused.push_back({c, needs}); };
    auto stale = [&](const Candidate& c) {
      return !complex_->alive(c.a) || !complex_->alive(c.b) || c.version_a != version_[c.a] ||
             c.version_b != version_[c.b];
    };
    // The candidates are taken a batch at a time: the first kBatch fresh ones in queue order
    // whose atoms are not neighbours of (nor equal to) an earlier one's (the others wait in
    // the queue), checked in parallel and applied in order. Such a candidate's check reads
    // nothing an earlier one's collapse or refusal changes (see check()), so it finds what it
    // would find after them; what the batch changes is the order (the edges a collapse pushes
    // wait for the next batch). The batch depends on the queue alone: the same result at any
    // thread count.
    std::vector<Candidate> batch, skipped, popped;  // popped: the fresh ones, in order
    std::vector<std::size_t> position;              // each batched one's in popped
    std::vector<Check> checks;
    std::vector<char> near(complex_->vertex_slots(), 0);  // N[a] u N[b] of the batch's edges
    std::vector<int> near_list;
    auto mark = [&](int v) {
      for (int u : complex_->neighbours(v))
        if (!near[u]) {
          near[u] = 1;
          near_list.push_back(u);
        }
      if (!near[v]) {
        near[v] = 1;
        near_list.push_back(v);
      }
    };
    while (complex_->vertices() > target) {
      if (queue.empty()) {
        if (round_collapses == 0) {
          if (scale >= 1) break;
          scale = std::min(1.0, 2 * scale);
        }
        round_collapses = 0;
        ++st.rounds;
        std::vector<Refused> waiting;
        for (const Refused& r : refused) {
          const Candidate& c = r.candidate;
          if (stale(c)) continue;
          if (r.needs <= scale)
            queue.push(evaluate(c.a, c.b, false));
          else
            waiting.push_back(r);
        }
        refused = std::move(waiting);
        continue;
      }
      batch.clear();
      skipped.clear();
      popped.clear();
      position.clear();
      const long room = complex_->vertices() - target;  // collapses left
      while (batch.size() < kBatch && static_cast<long>(batch.size()) < room &&
             skipped.size() < kBatchScan && !queue.empty()) {
        const Candidate c = queue.top();
        queue.pop();
        if (stale(c)) continue;
        popped.push_back(c);
        if (near[c.a] || near[c.b]) {
          skipped.push_back(c);
          continue;
        }
        position.push_back(popped.size() - 1);
        batch.push_back(c);
        mark(c.a);
        mark(c.b);
      }
      for (int v : near_list) near[v] = 0;
      near_list.clear();
      // The candidate after each one in queue order (for the clamp's back-in-line test): the
      // next one popped, batched or passed over, else what the queue holds first.
      std::optional<Candidate> rest;
      if (!queue.empty()) rest = queue.top();
      for (const Candidate& c : skipped) queue.push(c);
      std::vector<const Candidate*> next(batch.size(), nullptr);
      for (std::size_t k = 0; k < batch.size(); ++k)
        next[k] = position[k] + 1 < popped.size() ? &popped[position[k] + 1]
                  : rest                          ? &*rest
                                                  : nullptr;
      checks.resize(batch.size());
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, batch.size(), 1),
                        [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t i = range.begin(); i != range.end(); ++i)
                            checks[i] = check(batch[i], scale, next[i]);
                        });
      std::vector<Candidate> later;  // what the batch pushes back in line
      std::vector<Pair> pushes;      // the edges its collapses leave
      for (std::size_t k = 0; k < batch.size(); ++k) {
        const Candidate& c = batch[k];
        const Check& r = checks[k];
        switch (r.stage) {
          case Check::Stage::topology:
            ++st.refused_topology;
            refuse(c, 0);
            continue;
          case Check::Stage::back:
            // Clamping raised its cost past the next candidate's: back in line.
            later.push_back(r.exact);
            continue;
          case Check::Stage::outside:
            ++st.refused_outside;  // the same atoms give the same centre: not retried
            continue;
          case Check::Stage::shortfall:
            if (r.culprit.first >= 0) {
              auto& list = samples_of_[r.culprit.first];
              std::swap(list[0], list[r.culprit.second]);
            }
            ++st.refused_shortfall;
            refuse(c, r.shortfall / delta_);
            continue;
          case Check::Stage::excess:
            ++st.refused_excess;
            refuse(c, r.excess / tau_);
            continue;
          case Check::Stage::passed:
            break;
        }
        complex_->collapse(c.a, c.b);
        ++st.collapses;
        ++round_collapses;
        st.contracted_loops += r.loops;
        st.clamped_radii += r.clamped;
        const MergedAtom& m = r.m;
        st.max_error = std::max(st.max_error, m.error);
        (m.placement == Placement::minimiser           ? st.placed_minimiser
         : m.placement == Placement::nearest_minimiser ? st.placed_nearest_minimiser
                                                       : st.placed_fallback) += 1;
        spheres_[c.a] = m.atom;
        quadric_[c.a] += quadric_[c.b];
        samples_of_[c.a].insert(samples_of_[c.a].end(), samples_of_[c.b].begin(),
                                samples_of_[c.b].end());
        samples_of_[c.b] = {};
        anchor_[c.a] = r.anchor;
        depth_[c.a] = r.depth;
        overshoot_[c.a] = r.overshoot;
        ++version_[c.a];
        for (int u : complex_->neighbours(c.a))
          pushes.push_back({std::min(u, c.a), std::max(u, c.a)});
      }
      // The new edges' costs: a later collapse of the batch changes none of their atoms.
      const std::size_t first = later.size();
      later.resize(first + pushes.size());
      tbb::parallel_for(std::size_t(0), pushes.size(), [&](std::size_t i) {
        later[first + i] = evaluate(pushes[i][0], pushes[i][1], false);
      });
      for (const Candidate& c : later) queue.push(c);
    }
    st.target_reached = complex_->vertices() <= target;
  }

  // ---- output --------------------------------------------------------------------------------

  void write_output() {
    auto& st = out_.stats;
    st.complex_components_after = complex_->components();
    st.complex_euler_after = complex_->euler();
    if (st.complex_components_after != st.complex_components_before)
      throw TopologyError("simplify: the complex's components changed from " +
                          std::to_string(st.complex_components_before) + " to " +
                          std::to_string(st.complex_components_after));
    // Atoms by decreasing radius, ties by centre, then by index.
    std::vector<int> order;
    for (int v = 0; v < complex_->vertex_slots(); ++v)
      if (complex_->alive(v)) order.push_back(v);
    std::sort(order.begin(), order.end(), [&](int x, int y) {
      const MedialAtom &p = spheres_[x], &q = spheres_[y];
      if (p.radius != q.radius) return p.radius > q.radius;
      if (p.centre != q.centre)
        return std::lexicographical_compare(p.centre.data(), p.centre.data() + 3, q.centre.data(),
                                            q.centre.data() + 3);
      return x < y;
    });
    std::vector<int> index(complex_->vertex_slots(), -1);
    MedialSurface& s = out_.surface;
    for (int v : order) {
      index[v] = static_cast<int>(s.atoms.size());
      s.atoms.push_back(spheres_[v]);
    }
    auto remap = [&](auto simplices) {
      for (auto& x : simplices) {
        for (int& v : x) v = index[v];
        std::sort(x.begin(), x.end());
      }
      std::sort(simplices.begin(), simplices.end());
      return simplices;
    };
    s.edges = remap(complex_->edge_list());
    s.faces = remap(complex_->triangle_list());
    out_.cells = remap(complex_->tetrahedron_list());
    st.atoms_after = s.atoms.size();
    st.edges_after = s.edges.size();
    st.faces_after = s.faces.size();
    st.cells_after = out_.cells.size();

    // The output's worst hull excess: the same samples as the bound's, all exact.
    std::vector<Corner> c(order.size());
    for (std::size_t i = 0; i < order.size(); ++i)
      c[i] = {&s.atoms[i], &anchor_[order[i]], depth_[order[i]]};
    const std::size_t na = s.atoms.size(), ne = s.edges.size();
    std::vector<double> worst(na + ne + s.faces.size(), 0);
    tbb::parallel_for(std::size_t(0), worst.size(), [&](std::size_t i) {
      if (i < na) {
        worst[i] = s.atoms[i].radius - c[i].depth;
      } else if (i < na + ne) {
        const auto& e = s.edges[i - na];
        worst[i] = cone_excess(c[e[0]], c[e[1]], -INFINITY);
      } else {
        const auto& f = s.faces[i - na - ne];
        worst[i] = slab_excess(c[f[0]], c[f[1]], c[f[2]], -INFINITY);
      }
    });
    st.worst_excess = std::max(0.0, *std::max_element(worst.begin(), worst.end()));
  }

  const PolygonSoup& object_;
  const MedialSurface& mesh_;
  const std::vector<Quad>& cells_;
  const SimplifyOptions& opt_;
  const std::vector<Vec3>& samples_;
  const std::vector<int>& atom_of_sample_;
  const UnionComplex* dual_;  // the union's dual complex, when the caller has it
  SimplifiedMedialMesh out_;
  double tau_ = 0, k_ = 0, delta_ = 0;
  std::unique_ptr<SolidQuery> solid_;       // the object
  std::unique_ptr<detail::BallTree> tree_;  // over the input atoms
  // The input atoms' inscribed balls (centre, distance to the object): inside the object.
  std::vector<MedialAtom> inscribed_balls_;
  std::unique_ptr<detail::BallTree> inscribed_;
  std::unique_ptr<detail::MedialComplex> complex_;
  // Per vertex (atom slot):
  std::vector<MedialAtom> spheres_;           // its current sphere
  std::vector<SphereQuadric> quadric_;        // its quadric
  std::vector<std::vector<int>> samples_of_;  // the samples whose poles merged into it
  std::vector<std::uint32_t> version_;        // bumped when its sphere changes
  std::vector<Vec3> anchor_;                  // the mesh's point closest to its centre
  std::vector<double> depth_;                 // the distance from its centre to the mesh
  std::vector<double> overshoot_;  // the largest r - depth of the input atoms merged into it

  // The input complex's edges and triangles (sorted) and their estimated excesses.
  std::vector<Pair> edges0_;
  std::vector<Triple> triangles0_;
  std::vector<double> edge_excess_, triangle_excess_;
};

}  // namespace

SimplifiedMedialMesh simplify_medial_mesh(const PolygonSoup& object, const MedialSurface& mesh,
                                          const std::vector<std::array<int, 4>>& cells,
                                          const SimplifyOptions& opt,
                                          const std::vector<Eigen::Vector3d>& samples,
                                          const std::vector<int>& atom_of_sample,
                                          const UnionComplex* dual) {
  return Simplifier(object, mesh, cells, opt, samples, atom_of_sample, dual).run();
}

}  // namespace mg::skeletonize
