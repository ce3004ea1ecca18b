#include "garbing/primitives.h"

#include "garbing/detail/convex_search.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace mg::garbing {
namespace {

using Vec3 = Eigen::Vector3d;

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Squared distance from the point (x, y) to the segment (ax, ay)-(bx, by).
double segment_distance2(double x, double y, double ax, double ay, double bx, double by) {
  const double ux = bx - ax, uy = by - ay;
  const double len2 = ux * ux + uy * uy;
  double t = len2 > 0 ? ((x - ax) * ux + (y - ay) * uy) / len2 : 0;
  t = std::clamp(t, 0.0, 1.0);
  const double dx = x - ax - t * ux, dy = y - ay - t * uy;
  return dx * dx + dy * dy;
}

/// Where p stands in the cone's profile: axial coordinate x, unit radial direction e (any
/// normal of the axis when p is on it) and distance rho from the axis.
struct Profile {
  double x, rho;
  Vec3 e;
};

Profile profile(const Cone& k, const Vec3& p) {
  const Vec3 w = p - k.c1;
  const double x = w.dot(k.u);
  const Vec3 radial = w - x * k.u;
  const double rho = radial.norm();
  return {x, rho, rho > 0 ? Vec3(radial / rho) : Vec3(k.u.unitOrthogonal())};
}

/// The parameter s in [0, 1] of the point of the generator segment (t_lo, rho_lo)-(t_hi, rho_hi)
/// nearest to (x, rho) in the profile plane.
double generator_parameter(const Cone& k, double x, double rho) {
  const double gt = k.t_hi - k.t_lo, gr = k.rho_hi - k.rho_lo;
  return std::clamp(((x - k.t_lo) * gt + (rho - k.rho_lo) * gr) / (gt * gt + gr * gr), 0.0, 1.0);
}

}  // namespace

Cone make_cone(const MedialAtom& first, const MedialAtom& second, int a, int b) {
  Cone c;
  c.a = a;
  c.b = b;
  c.c1 = first.centre;
  c.r1 = first.radius;
  c.r2 = second.radius;
  const Vec3 axis = second.centre - first.centre;
  c.length = axis.norm();
  c.u = axis / c.length;
  c.sin_phi = (first.radius - second.radius) / c.length;
  c.cos_phi = std::sqrt(std::max(0.0, 1 - c.sin_phi * c.sin_phi));
  if (c.length < c.r1 + c.r2) c.crease = crease(c.length, c.r1, c.r2);
  complete_cone(c);
  return c;
}

StoredCone stored(const Cone& cone) {
  StoredCone s;
  s.a = cone.a;
  s.b = cone.b;
  s.c1 = cone.c1;
  s.u = cone.u;
  s.r1 = cone.r1;
  s.length = cone.length;
  s.r2 = cone.r2;
  s.cos_phi = cone.cos_phi;
  return s;
}

double hull_parameter(const Cone& k, const Vec3& p) {
  const Vec3 q = p - k.c1;
  const double x = q.dot(k.u), y = q.cross(k.u).norm();  // a cross product: accurate near the axis
  const double dr = k.r2 - k.r1;
  // cos(phi) = 0 only when rounding makes one ball hold the other: the hull is the larger.
  const double t =
      k.cos_phi > 0 ? (x - k.sin_phi * y / k.cos_phi) / k.length : (dr > 0 ? 1.0 : 0.0);
  return std::clamp(t, 0.0, 1.0);
}

double hull_distance(const Cone& k, const Vec3& p) {
  const double t = hull_parameter(k, p);
  return (p - (k.c1 + (t * k.length) * k.u)).norm() - (k.r1 + t * (k.r2 - k.r1));
}

Vec3 migration_vector(const MedialAtom& ball, const Vec3& v) {
  const Vec3 d = v - ball.centre;
  const double d2 = d.squaredNorm();
  if (d2 == 0) return Vec3::Zero();
  return ball.radius * d / d2;
}

namespace {

Vec3 cone_migration(const Vec3& c1, const Vec3& u, double length, double r1, double sin_phi,
                    double cos_phi, const Vec3& v) {
  const Vec3 w = v - c1;
  const double x = w.dot(u);
  const double rho = (w - x * u).norm();
  if (rho == 0) return Vec3::Zero();
  const double t = x - rho * sin_phi / cos_phi;  // foot of the normal on the axis
  if (t < 0 || t > length) return Vec3::Zero();
  const Vec3 d = v - (c1 + t * u);
  const double r = r1 - t * sin_phi;  // radius of the ball tangent there
  return r * d / d.squaredNorm();
}

}  // namespace

Vec3 migration_vector(const Cone& cone, const Vec3& v) {
  return cone_migration(cone.c1, cone.u, cone.length, cone.r1, cone.sin_phi, cone.cos_phi, v);
}

Vec3 migration_vector(const StoredCone& cone, const Vec3& v) {
  const double sin_phi = (cone.r1 - cone.r2) / cone.length;  // restored()'s
  return cone_migration(cone.c1, cone.u, cone.length, cone.r1, sin_phi, cone.cos_phi, v);
}

bool line_interval(const MedialAtom& s, const Vec3& o, const Vec3& d, double& t0, double& t1) {
  const Vec3 oc = o - s.centre;
  const double a = d.squaredNorm();
  const double half_b = oc.dot(d);
  const double c = oc.squaredNorm() - s.radius * s.radius;
  const double disc = half_b * half_b - a * c;
  if (disc < 0 || a == 0) return false;
  const double root = std::sqrt(disc);
  // Stable pair of roots.
  const double q = half_b >= 0 ? -(half_b + root) : -(half_b - root);
  double x0 = q / a, x1 = q != 0 ? c / q : -half_b / a;
  if (x0 > x1) std::swap(x0, x1);
  t0 = x0;
  t1 = x1;
  return true;
}

bool line_interval(const Cone& k, const Vec3& o, const Vec3& d, double& t0, double& t1) {
  const Vec3 w = o - k.c1;
  const double ot = w.dot(k.u), dt = d.dot(k.u);
  {
    // Cheap rejection: a line missing the frustum's bounding ball (with slack for rounding)
    // misses the frustum.
    const Vec3 wm = o - k.bound_centre;
    const double wd = wm.dot(d);
    if (wm.squaredNorm() - wd * wd / d.squaredNorm() > k.bound_radius2 * (1 + 1e-9)) return false;
  }
  const Vec3 op = w - ot * k.u, dp = d - dt * k.u;
  // Slab t_lo <= axial <= t_hi.
  double lo = -kInf, hi = kInf;
  if (dt != 0) {
    double a = (k.t_lo - ot) / dt, b = (k.t_hi - ot) / dt;
    if (a > b) std::swap(a, b);
    lo = a;
    hi = b;
  } else if (ot < k.t_lo || ot > k.t_hi) {
    return false;
  }
  // rho(t)^2 <= R(t)^2 with R(axial) = (r1 - axial sin) / cos, linear in t: alpha + beta t.
  const double alpha = (k.r1 - ot * k.sin_phi) / k.cos_phi;
  const double beta = -dt * k.sin_phi / k.cos_phi;
  const double A = dp.squaredNorm() - beta * beta;
  const double B = 2 * (op.dot(dp) - alpha * beta);
  const double C = op.squaredNorm() - alpha * alpha;
  const double scale = d.squaredNorm();
  double qlo = -kInf, qhi = kInf;
  if (std::abs(A) <= 1e-14 * scale) {  // parallel to a generator: linear
    if (B > 0)
      qhi = -C / B;
    else if (B < 0)
      qlo = -C / B;
    else if (C > 0)
      return false;
  } else {
    const double disc = B * B - 4 * A * C;
    if (A > 0) {
      if (disc < 0) return false;
      const double root = std::sqrt(disc);
      qlo = (-B - root) / (2 * A);
      qhi = (-B + root) / (2 * A);
    } else if (disc >= 0) {
      // q <= 0 outside the roots: two rays, one per nappe; keep the one where R >= 0.
      const double root = std::sqrt(disc);
      const double s0 = (-B + root) / (2 * A), s1 = (-B - root) / (2 * A);  // s0 <= s1
      const double ra = std::max(lo, -kInf), rb = std::min(hi, s0);
      const double sa = std::max(lo, s1), sb = std::min(hi, kInf);
      auto radius_ok = [&](double x0, double x1) {
        if (!(x0 <= x1)) return false;
        const double mid = std::isfinite(x0) && std::isfinite(x1) ? (x0 + x1) / 2
                           : std::isfinite(x0)                    ? x0
                                                                  : x1;
        return alpha + beta * mid >= 0;
      };
      if (radius_ok(ra, rb)) {
        qhi = s0;
      } else if (radius_ok(sa, sb)) {
        qlo = s1;
      } else {
        return false;
      }
    }  // disc < 0 with A < 0: q < 0 everywhere
  }
  t0 = std::max(lo, qlo);
  t1 = std::min(hi, qhi);
  return t0 <= t1;
}

bool contains_deeper_than(const MedialAtom& ball, const Vec3& p, double eps) {
  const double r = ball.radius - eps;
  return r > 0 && (p - ball.centre).squaredNorm() < r * r;
}

bool contains_deeper_than(const Cone& k, const Vec3& p, double eps) {
  const Vec3 w = p - k.c1;
  const double x = w.dot(k.u);
  if (x < k.t_lo + eps || x > k.t_hi - eps) return false;
  const double rho = (w - x * k.u).norm();
  // Distance to the lateral surface in the (axial, radial) plane: (R(x) - rho) cos(phi).
  return ((k.r1 - x * k.sin_phi) / k.cos_phi - rho) * k.cos_phi > eps;
}

Vec3 closest_solid_point(const Cone& k, const Vec3& p) {
  const Profile q = profile(k, p);
  const double x = q.x, rho = q.rho;
  // In the (axial, radial) half-plane the solid is the quadrilateral
  // (t_lo, 0) (t_hi, 0) (t_hi, rho_hi) (t_lo, rho_lo).
  const double R = (k.r1 - x * k.sin_phi) / k.cos_phi;
  if (x >= k.t_lo && x <= k.t_hi && rho <= R) return p;
  // Candidates: clamp to caps, to the generator segment.
  double best = kInf;
  Vec3 out = p;
  auto consider = [&](double t, double r) {
    const double d2 = (t - x) * (t - x) + (r - rho) * (r - rho);
    if (d2 < best) {
      best = d2;
      out = k.c1 + t * k.u + r * q.e;
    }
  };
  consider(k.t_lo, std::min(rho, k.rho_lo));
  consider(k.t_hi, std::min(rho, k.rho_hi));
  const double s = generator_parameter(k, x, rho);
  consider(k.t_lo + s * (k.t_hi - k.t_lo), k.rho_lo + s * (k.rho_hi - k.rho_lo));
  return out;
}

Vec3 closest_lateral_point(const Cone& k, const Vec3& p) {
  const Profile q = profile(k, p);
  const double s = generator_parameter(k, q.x, q.rho);
  return k.c1 + (k.t_lo + s * (k.t_hi - k.t_lo)) * k.u +
         (k.rho_lo + s * (k.rho_hi - k.rho_lo)) * q.e;
}

double lateral_area(const Cone& k) {
  const double slant = std::hypot(k.t_hi - k.t_lo, k.rho_hi - k.rho_lo);
  return M_PI * (k.rho_lo + k.rho_hi) * slant;
}

Eigen::AlignedBox3d bounding_box(const MedialAtom& s) {
  return {Vec3(s.centre - Vec3::Constant(s.radius)), Vec3(s.centre + Vec3::Constant(s.radius))};
}

Eigen::AlignedBox3d bounding_box(const Cone& c) {
  // A disk of radius rho and unit normal u spans rho * sqrt(1 - u_k^2) along axis k.
  const Vec3 half =
      c.u.cwiseAbs2().unaryExpr([](double x) { return std::sqrt(std::max(0.0, 1 - x)); });
  Vec3 lo = Vec3::Constant(kInf), hi = Vec3::Constant(-kInf);
  for (const auto& [t, rho] :
       {std::make_pair(c.t_lo, c.rho_lo), std::make_pair(c.t_hi, c.rho_hi)}) {
    const Vec3 o = c.c1 + t * c.u;
    lo = lo.cwiseMin(o - rho * half);
    hi = hi.cwiseMax(o + rho * half);
  }
  return {lo, hi};
}

double box_distance(const Vec3& lo, const Vec3& hi, const Vec3& p) {
  return (lo - p).cwiseMax(p - hi).cwiseMax(0.0).norm();
}

bool meets_box(const MedialAtom& ball, const Vec3& lo, const Vec3& hi) {
  return box_distance(lo, hi, ball.centre) <= ball.radius;
}

bool hull_meets_box(const Cone& k, const Vec3& lo, const Vec3& hi) {
  return detail::convex_reaches_zero(
      [&](double t) { return box_distance(lo, hi, k.centre(t)) - k.radius(t); }, k.lipschitz);
}

bool near_crease_fill(const Cone& k, const Vec3& lo, double side) {
  const double half_diagonal = side * (std::sqrt(3.0) / 2);
  if (k.disjoint) {  // the whole waist: the frustum's bounding ball grown by the half diagonal
    const double reach = std::sqrt(k.bound_radius2) + half_diagonal;
    return (lo + Vec3::Constant(side / 2) - k.bound_centre).squaredNorm() <=
           reach * reach * (1 + 1e-12);
  }
  const Vec3 q = lo + Vec3::Constant(side / 2) - k.c1;
  const double x = q.dot(k.u);
  if (x < k.fill_lo[0] - half_diagonal || x > k.fill_hi[0] + half_diagonal) return false;
  // The distance from the axis, squared first: a looser test (by a relative 1e-12, more than
  // the rounding of the squares) spares most square roots and rejects nothing kept below.
  const double y2 = q.cross(k.u).squaredNorm();
  const double y_hi = k.fill_hi[1] + half_diagonal, y_lo = k.fill_lo[1] - half_diagonal;
  if (y2 > y_hi * y_hi * (1 + 1e-12) || (y_lo > 0 && y2 < y_lo * y_lo * (1 - 1e-12))) return false;
  const double y = std::sqrt(y2);
  if (y < y_lo || y > y_hi) return false;    // off the triangle's box
  const double bound2 = 0.75 * side * side;  // (half diagonal)^2
  // Inside the triangle: the same side of its three edges.
  const double x0 = k.crease.along, rho0 = k.crease.radius;
  auto cross = [&](double ax, double ay, double bx, double by) {
    return (bx - ax) * (y - ay) - (by - ay) * (x - ax);
  };
  const double c1 = cross(x0, rho0, k.t_lo, k.rho_lo);
  const double c2 = cross(k.t_lo, k.rho_lo, k.t_hi, k.rho_hi);
  const double c3 = cross(k.t_hi, k.rho_hi, x0, rho0);
  if ((c1 >= 0 && c2 >= 0 && c3 >= 0) || (c1 <= 0 && c2 <= 0 && c3 <= 0)) return true;
  return segment_distance2(x, y, x0, rho0, k.t_lo, k.rho_lo) <= bound2 ||
         segment_distance2(x, y, k.t_lo, k.rho_lo, k.t_hi, k.rho_hi) <= bound2 ||
         segment_distance2(x, y, k.t_hi, k.rho_hi, x0, rho0) <= bound2;
}

bool fill_meets_cube(const Cone& k, const Vec3& lo, double side) {
  if (!near_crease_fill(k, lo, side)) return false;
  const Vec3 centre = lo + Vec3::Constant(side / 2);
  const double from_centre = hull_distance(k, centre);
  if (from_centre <= side / 2) return true;                     // inscribed ball
  if (from_centre > side * (std::sqrt(3.0) / 2)) return false;  // circumscribed ball
  return hull_meets_box(k, lo, Vec3(lo + Vec3::Constant(side)));
}

bool hulls_meet(const Cone& a, const Cone& b) {
  return detail::convex_reaches_zero(
      [&](double s) { return hull_distance(b, a.centre(s)) - a.radius(s); }, a.lipschitz);
}

}  // namespace mg::garbing
