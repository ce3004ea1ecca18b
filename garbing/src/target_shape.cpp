#include "garbing/target_shape.h"

#include "core/errors.h"
#include "core/random.h"
#include "target_shape_bvh.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <queue>
#include <utility>

namespace mg::garbing {

using Vec3 = Eigen::Vector3d;

ConeSource parse_cone_source(const std::string& name) {
  if (name == "rt") return ConeSource::regular_triangulation;
  if (name == "all") return ConeSource::all_pairs;
  if (name == "edges") return ConeSource::ma_edges;
  if (name == "none") return ConeSource::none;
  throw InvalidInput("unknown cone source '" + name + "' (expected rt, all, edges or none)");
}

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// The 26 directions of a cube's faces, edges and corners, unit length.
const std::vector<Vec3>& probe_directions() {
  static const std::vector<Vec3> dirs = [] {
    std::vector<Vec3> out;
    for (int x = -1; x <= 1; ++x)
      for (int y = -1; y <= 1; ++y)
        for (int z = -1; z <= 1; ++z)
          if (x || y || z) out.push_back(Vec3(x, y, z).normalized());
    return out;
  }();
  return dirs;
}

detail::Box box_of(const Eigen::AlignedBox3d& b) { return {b.min(), b.max()}; }

}  // namespace

namespace {

/// CSR lists atom -> the ids of the primitives having it as a corner.
template <class Corners>
void index_by_atom(std::size_t atom_count, std::size_t count, int first_id, const Corners& corners,
                   std::vector<int>& start, std::vector<int>& ids) {
  start.assign(atom_count + 1, 0);
  for (std::size_t k = 0; k < count; ++k)
    for (int a : corners(k)) ++start[a + 1];
  for (std::size_t i = 0; i < atom_count; ++i) start[i + 1] += start[i];
  ids.resize(start.back());
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (std::size_t k = 0; k < count; ++k)
    for (int a : corners(k)) ids[fill[a]++] = first_id + static_cast<int>(k);
}

}  // namespace

TargetShape::TargetShape(MedialSurface atoms, const std::vector<std::array<int, 2>>& pairs,
                         const Frame& frame)
    : TargetShape(std::move(atoms), pairs, {}, frame) {
  envelope_ = false;
}

TargetShape::TargetShape(MedialSurface atoms, const std::vector<std::array<int, 2>>& pairs,
                         const std::vector<std::array<int, 3>>& triples, const Frame& frame,
                         const EnvelopeCounts& counts)
    : frame_(frame),
      atoms_{std::move(atoms.atoms), {}, {}},
      counts_(counts),
      bvh_(std::make_unique<Bvh>()) {
  atoms = {};  // the connectivity of the copy given is not G's
  // The world frame copies the centres as they are (a transform by the identity could still
  // change the sign of a zero).
  if (!frame_.is_world())
    for (MedialAtom& s : atoms_.atoms) s.centre = frame_.to_local(s.centre);
  cones_.resize(pairs.size());
  tbb::parallel_for(std::size_t(0), pairs.size(), [&](std::size_t k) {
    const auto& p = pairs[k];
    cones_[k] = stored(make_cone(atoms_.atoms[p[0]], atoms_.atoms[p[1]], p[0], p[1]));
  });
  const std::size_t n = atoms_.atoms.size();
  index_by_atom(
      n, cones_.size(), static_cast<int>(n),
      [&](std::size_t k) {
        return std::array<int, 2>{cones_[k].a, cones_[k].b};
      },
      cones_by_atom_start_, cones_by_atom_);
  first_slab_ = static_cast<int>(n + cones_.size());
  slabs_.reserve(triples.size());
  for (const auto& t : triples) {
    slabs_.push_back(
        make_slab(atoms_.atoms[t[0]], atoms_.atoms[t[1]], atoms_.atoms[t[2]], t[0], t[1], t[2]));
    counts_.slabs_without_tangent_triangles += !slabs_.back().has_tangent_triangles;
  }
  index_by_atom(
      n, slabs_.size(), first_slab_, [&](std::size_t k) { return slabs_[k].atoms; },
      slabs_by_atom_start_, slabs_by_atom_);
  // The hierarchy holds each primitive's own piece: a slab's prism (its balls and edge hulls
  // are primitives of G), none for a slab without tangent triangles.
  std::vector<detail::Box> boxes(primitive_count());
  tbb::parallel_for(std::size_t(0), boxes.size(), [&](std::size_t i) {
    const int id = static_cast<int>(i);
    boxes[i] = is_sphere(id) ? box_of(bounding_box(atoms_.atoms[i]))
               : is_cone(id) ? box_of(bounding_box(cone(id)))
                             : box_of(slab(id).prism_box);
  });
  std::vector<int> ids;
  ids.reserve(boxes.size());
  for (int i = 0; i < static_cast<int>(boxes.size()); ++i)
    if (!is_slab(i) || slab(i).has_tangent_triangles) ids.push_back(i);
  bvh_->build(std::move(boxes), std::move(ids));
}

TargetShape::~TargetShape() = default;
TargetShape::TargetShape(TargetShape&&) noexcept = default;
TargetShape& TargetShape::operator=(TargetShape&&) noexcept = default;

TargetShape make_target_shape(MedialSurface atoms, const ConeOptions& cones, const Frame& frame) {
  const std::vector<std::array<int, 2>> pairs = cone_pairs(atoms, cones);
  return TargetShape(std::move(atoms), pairs, frame);
}

Vec3 TargetShape::migration_vector(PrimitiveId i, const Vec3& v) const {
  if (is_slab(i)) return garbing::migration_vector(slab(i), v);
  return is_sphere(i) ? garbing::migration_vector(atoms_.atoms[i], v)
                      : garbing::migration_vector(stored_cone(i), v);
}

bool TargetShape::primitive_contains(PrimitiveId i, const Vec3& p, double eps) const {
  if (is_slab(i)) return prism_depth(slab(i), p) > eps;
  return is_sphere(i) ? contains_deeper_than(atoms_.atoms[i], p, eps)
                      : contains_deeper_than(cone(i), p, eps);
}

bool TargetShape::ray_interval(PrimitiveId i, const Vec3& origin, const Vec3& dir, double& t0,
                               double& t1) const {
  if (is_slab(i)) return prism_interval(slab(i), origin, dir, t0, t1);
  return is_sphere(i) ? line_interval(atoms_.atoms[i], origin, dir, t0, t1)
                      : line_interval(cone(i), origin, dir, t0, t1);
}

bool TargetShape::contains(const Vec3& p) const {
  bool inside = false;
  bvh_->visit([&](const detail::StoredBox& b) { return !inside && b.squared_distance(p) == 0; },
              [&](int i) {
                if (inside) return;
                if (is_sphere(i)) {
                  const double r = atoms_.atoms[i].radius;
                  inside = (p - atoms_.atoms[i].centre).squaredNorm() <= r * r;
                } else if (is_cone(i)) {
                  inside = closest_solid_point(cone(i), p) == p;
                } else {
                  inside = prism_depth(slab(i), p) >= 0;
                }
              });
  return inside;
}

bool TargetShape::within(const Vec3& p, double tol) const {
  bool found = false;
  const double tol2 = tol * tol;
  bvh_->visit([&](const detail::StoredBox& b) { return !found && b.squared_distance(p) <= tol2; },
              [&](int i) {
                if (found) return;
                if (is_sphere(i)) {
                  const double r = atoms_.atoms[i].radius + tol;
                  found = (p - atoms_.atoms[i].centre).squaredNorm() <= r * r;
                } else if (is_cone(i)) {
                  found = hull_distance(cone(i), p) <= tol;
                } else {
                  found = slab_distance(slab(i), p) <= tol;
                }
              });
  return found;
}

bool TargetShape::line_to_boundary(const Vec3& v, const Vec3& dir, double t_max, double& t,
                                   bool& inside) const {
  // Outside, only the first entry matters: depth first along [0, t_max], the segment cut at
  // each entry found, nearer boxes first. An interval holding t = 0 (v inside) is never cut
  // off (its box holds v) and ends the walk. Only from inside (rare: M1 lies outside G, within
  // a leaf) is the whole segment [-t_max, t_max] collected.
  inside = false;
  double first = kInf;
  bvh_->visit_segment(
      v, dir, [&] { return std::min(first, t_max); },
      [&](int i) {
        double a, z;
        if (!ray_interval(i, v, dir, a, z) || z < 0) return true;
        if (a <= 0) {
          inside = true;
          return false;
        }
        if (a <= t_max) first = std::min(first, a);
        return true;
      });
  if (!inside) {
    if (first > t_max) return false;
    t = first;
    return true;
  }
  thread_local std::vector<std::pair<double, double>> runs;  // in units of dir from v
  runs.clear();
  bvh_->visit_segment(
      v - t_max * dir, dir, [&] { return 2 * t_max; },
      [&](int i) {
        double a, z;
        if (ray_interval(i, v, dir, a, z) && z >= -t_max && a <= t_max) runs.emplace_back(a, z);
        return true;
      });
  // Leave the union toward negative t: merge the runs containing 0 downward.
  std::sort(runs.begin(), runs.end(),
            [](const auto& x, const auto& y) { return x.second > y.second; });
  const double slack = 1e-12 * (1 + t_max);
  double end = 0;
  for (const auto& [a, z] : runs) {
    if (z < end - slack) break;
    end = std::min(end, a);
  }
  if (end < -t_max) return false;
  t = end;
  return true;
}

bool TargetShape::first_entry(const Vec3& origin, const Vec3& dir, double t_max, double& t) const {
  // Best-first along the ray: nodes entered after the best entry so far cannot improve it.
  double best = kInf;
  bvh_->visit_along_ray(
      origin, dir, t_max, [&](double entry) { return entry < best; },
      [&](int i) {
        double a, z;
        if (ray_interval(i, origin, dir, a, z) && a >= 0 && a < best) best = a;
      });
  if (best > t_max) return false;
  t = best;
  return true;
}

bool TargetShape::run_end(const Vec3& origin, const Vec3& dir, double t_max, double& t) const {
  // Grow the run [.., end] in order of entry: an interval joins when it starts before the end;
  // later ones wait in a heap until the end reaches them. Nodes entered after the end (plus
  // slack) cannot extend it.
  const double slack = 1e-12 * (1 + t_max);
  double end = 0;
  bool started = false;
  using Interval = std::pair<double, double>;
  std::priority_queue<Interval, std::vector<Interval>, std::greater<>> waiting;
  auto absorb = [&](double a, double z) {
    if (a <= end + slack) {
      started = started || a <= slack;
      if (z > end) {
        end = z;
        while (!waiting.empty() && waiting.top().first <= end + slack) {
          end = std::max(end, waiting.top().second);
          waiting.pop();
        }
      }
    } else {
      waiting.push({a, z});
    }
  };
  bvh_->visit_along_ray(
      origin, dir, t_max, [&](double entry) { return entry <= end + slack && end <= t_max; },
      [&](int i) {
        double a, z;
        if (ray_interval(i, origin, dir, a, z) && z >= 0) absorb(a, z);
      });
  if (!started || end > t_max) return false;  // not inside, or the run goes on past t_max
  t = end;
  return true;
}

Vec3 TargetShape::closest_point(const Vec3& p) const {
  if (!contains(p)) {
    // Outside: the nearest point of any primitive's solid, by branch and bound; of equally near
    // ones, the lowest primitive id's (so that the hierarchy's order does not decide).
    double best = kInf;
    int best_id = -1;
    Vec3 out = p;
    std::priority_queue<std::pair<double, int>, std::vector<std::pair<double, int>>, std::greater<>>
        queue;
    if (!bvh_->nodes.empty()) queue.push({bvh_->nodes[0].box.squared_distance(p), 0});
    while (!queue.empty()) {
      const auto [d2, id] = queue.top();
      queue.pop();
      if (d2 > best) break;
      const auto& n = bvh_->nodes[id];
      if (n.right >= 0) {
        queue.push({bvh_->nodes[id + 1].box.squared_distance(p), id + 1});
        queue.push({bvh_->nodes[n.right].box.squared_distance(p), n.right});
        continue;
      }
      for (int k = n.first; k < n.first + n.count; ++k) {
        const int i = bvh_->order[k];
        Vec3 q;
        if (is_sphere(i)) {
          const Vec3 d = p - atoms_.atoms[i].centre;
          q = atoms_.atoms[i].centre + atoms_.atoms[i].radius * d / d.norm();
        } else if (is_cone(i)) {
          q = closest_solid_point(cone(i), p);
        } else {
          q = closest_solid_point(slab(i), p);
        }
        const double e2 = (q - p).squaredNorm();
        if (e2 < best || (e2 == best && i < best_id)) {
          best = e2;
          best_id = i;
          out = q;
        }
      }
    }
    return out;
  }
  // Inside: the nearest exposed candidate. Candidates: each containing primitive's nearest
  // surface point, tried nearest first (the first exposed one bounds the rest); the circles of
  // pairs of those spheres, which lie no nearer than either sphere's own point; and, only if
  // nothing was found, the exits along 26 directions.
  struct Candidate {
    double distance;
    int id;
    Vec3 point;
  };
  std::vector<Candidate> around;
  const double on_surface = -1e-12 * (1 + p.norm());  // p on a surface counts as inside it
  bvh_->visit([&](const detail::StoredBox& b) { return b.squared_distance(p) == 0; },
              [&](int i) {
                if (!primitive_contains(i, p, on_surface)) return;
                Vec3 q;
                if (is_sphere(i)) {
                  const Vec3 d = p - atoms_.atoms[i].centre;
                  q = atoms_.atoms[i].centre +
                      atoms_.atoms[i].radius *
                          (d.squaredNorm() > 0 ? Vec3(d.normalized()) : Vec3(Vec3::UnitX()));
                } else if (is_cone(i)) {
                  q = closest_lateral_point(cone(i), p);
                } else {
                  q = prism_boundary_point(slab(i), p);
                }
                around.push_back({(q - p).norm(), i, q});
              });
  std::sort(around.begin(), around.end(), [](const Candidate& a, const Candidate& b) {
    return a.distance < b.distance || (a.distance == b.distance && a.id < b.id);
  });
  auto exposed = [&](const Vec3& q, int i, int j) {
    const double eps = 1e-12 * (1 + q.norm());
    bool free = true;
    bvh_->visit(
        [&](const detail::StoredBox& bb) { return free && bb.squared_distance(q) == 0; },
        [&](int k) { free = free && (k == i || k == j || !primitive_contains(k, q, eps)); });
    return free;
  };
  double best = kInf;
  Vec3 out = p;
  for (const Candidate& c : around) {
    if (c.distance >= best) break;
    if (exposed(c.point, c.id, c.id)) {
      best = c.distance;
      out = c.point;
      break;
    }
  }
  for (std::size_t x = 0; x < around.size() && around[x].distance < best; ++x) {
    if (!is_sphere(around[x].id)) continue;
    for (std::size_t y = x + 1; y < around.size() && around[y].distance < best; ++y) {
      if (!is_sphere(around[y].id)) continue;
      const MedialAtom& a = atoms_.atoms[around[x].id];
      const MedialAtom& b = atoms_.atoms[around[y].id];
      const Vec3 axis = b.centre - a.centre;
      const double L = axis.norm();
      if (!(L < a.radius + b.radius) || !(L > std::abs(a.radius - b.radius))) continue;
      const Vec3 n = axis / L;
      const Crease c = crease(L, a.radius, b.radius);
      const double along = c.along, radius = c.radius;
      const Vec3 centre = a.centre + along * n;
      Vec3 radial = (p - centre) - (p - centre).dot(n) * n;
      if (radial.squaredNorm() == 0) radial = n.unitOrthogonal();
      const Vec3 q = centre + radius * radial.normalized();
      const double d = (q - p).norm();
      if (d < best && exposed(q, around[x].id, around[y].id)) {
        best = d;
        out = q;
      }
    }
  }
  if (std::isfinite(best)) return out;
  // Exits along probe directions, the nearest candidate's direction first: its exit bounds the
  // others, which then stop as soon as their run passes it.
  auto probe = [&](const Vec3& d) {
    double t;
    if (run_end(p, d, std::isfinite(best) ? best : 1e300, t) && t < best) {
      best = t;
      out = p + t * d;
    }
  };
  if (!around.empty() && around.front().distance > 0)
    probe((around.front().point - p).normalized());
  for (const Vec3& d : probe_directions()) probe(d);
  return out;
}

namespace {

/// Draw j (0..3) of sample k: a counter-based stream, so sample k depends only on (seed, k).
double uniform(std::uint64_t seed, std::uint64_t k, int j) {
  return unit_interval(
      splitmix64(seed * 0x632be59bd9b4e019ULL + 4 * k + static_cast<std::uint64_t>(j)));
}

}  // namespace

std::vector<Vec3> TargetShape::sample_boundary(std::size_t count, std::uint64_t seed) const {
  const std::size_t n = primitive_count();
  std::vector<double> cumulative(n);
  double total = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const int id = static_cast<int>(i);
    if (is_sphere(id)) {
      total += 4 * M_PI * atoms_.atoms[i].radius * atoms_.atoms[i].radius;
    } else if (is_cone(id)) {
      total += lateral_area(cone(id));
    } else {
      total += tangent_area(slab(id));
    }
    cumulative[i] = total;
  }
  std::vector<Vec3> points(count);
  std::vector<char> keep(count, 0);
  tbb::parallel_for(std::size_t(0), count, [&](std::size_t k) {
    const double pick = uniform(seed, k, 0) * total;
    const int i = static_cast<int>(std::min<std::size_t>(
        std::upper_bound(cumulative.begin(), cumulative.end(), pick) - cumulative.begin(), n - 1));
    const double u = uniform(seed, k, 1), v = uniform(seed, k, 2);
    Vec3 q;
    if (is_slab(i)) {
      q = tangent_point(slab(i), u, v, uniform(seed, k, 3));
    } else if (is_sphere(i)) {
      const double z = 2 * u - 1, phi = 2 * M_PI * v, s = std::sqrt(std::max(0.0, 1 - z * z));
      q = atoms_.atoms[i].centre +
          atoms_.atoms[i].radius * Vec3(s * std::cos(phi), s * std::sin(phi), z);
    } else {
      // Lateral area element ~ rho(s): invert the cumulative of a linear density on [0, 1].
      const Cone c = cone(i);
      const double a = c.rho_lo, b = c.rho_hi;
      const double s = std::abs(b - a) < 1e-15 * (a + b)
                           ? u
                           : (std::sqrt(a * a + u * (b * b - a * a)) - a) / (b - a);
      const Vec3 e1 = c.u.unitOrthogonal(), e2 = c.u.cross(e1);
      const double phi = 2 * M_PI * v;
      q = c.c1 + (c.t_lo + s * (c.t_hi - c.t_lo)) * c.u +
          (a + s * (b - a)) * (std::cos(phi) * e1 + std::sin(phi) * e2);
    }
    const double eps = 1e-12 * (1 + q.norm());
    bool exposed = true;
    bvh_->visit([&](const detail::StoredBox& bb) { return exposed && bb.squared_distance(q) == 0; },
                [&](int j) { exposed = exposed && (j == i || !primitive_contains(j, q, eps)); });
    points[k] = q;
    keep[k] = exposed;
  });
  std::vector<Vec3> out;
  for (std::size_t k = 0; k < count; ++k)
    if (keep[k]) out.push_back(points[k]);
  return out;
}

void TargetShape::primitives_meeting_box(const Vec3& lo, const Vec3& hi,
                                         std::vector<PrimitiveId>& out) const {
  const std::size_t start = out.size();
  bvh_->visit([&](const detail::StoredBox& b) { return b.overlaps(lo, hi); },
              [&](int i) {
                if (is_sphere(i)) {
                  if (meets_box(atoms_.atoms[i], lo, hi)) out.push_back(i);
                  return;
                }
                if (is_slab(i)) {
                  if (prism_meets_box(slab(i), lo, hi)) out.push_back(i);
                  return;
                }
                const Cone k = cone(i);
                if (meets_box(atoms_.atoms[k.a], lo, hi) || meets_box(atoms_.atoms[k.b], lo, hi) ||
                    hull_meets_box(k, lo, hi))
                  out.push_back(i);
              });
  std::sort(out.begin() + static_cast<long>(start), out.end());
}

}  // namespace mg::garbing
