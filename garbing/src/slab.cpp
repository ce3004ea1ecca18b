// The medial slab: closed forms (distance, foot, tangent triangles) and exact line intervals.
#include "garbing/slab.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mg::garbing {
namespace {

using Vec3 = Eigen::Vector3d;

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Barycentric coordinates (s, t) of the in-plane point x: x = c0 + s e1 + t e2.
void plane_coordinates(const Slab& k, const Vec3& x, double& s, double& t) {
  const Vec3 e1 = k.c[1] - k.c[0], e2 = k.c[2] - k.c[0], w = x - k.c[0];
  const double a = e1.dot(e1), b = e1.dot(e2), c = e2.dot(e2);
  const double det = a * c - b * b;
  const double p = w.dot(e1), q = w.dot(e2);
  s = (c * p - b * q) / det;
  t = (a * q - b * p) / det;
}

/// The stationary point x* of |p - c(x)| - r(x) over the medial plane (the foot of p on the
/// slab's axis), as barycentric (s, t); false without tangent triangles.
bool foot(const Slab& k, const Vec3& p, double& s, double& t) {
  if (!k.has_tangent_triangles) return false;
  const double h = k.normal.dot(p - k.c[0]);
  const double root = std::sqrt(std::max(0.0, 1 - k.gradient.squaredNorm()));
  const Vec3 x = p - h * k.normal + (std::abs(h) / root) * k.gradient;
  plane_coordinates(k, x, s, t);
  return s >= 0 && t >= 0 && s + t <= 1;
}

/// The distance from p to edge hull e (its cone, or the ball holding the other).
double edge_distance(const Slab& k, int e, const Vec3& p) {
  if (k.edge_is_ball[e]) {
    const int b = k.edge_ball[e];
    return (p - k.c[b]).norm() - k.r[b];
  }
  return hull_distance(k.edge[e], p);
}

/// The value at n of the support-plane distance h(n) - n . p, h(n) = max_i c_i . n + r_i.
double support_gap(const Slab& k, const Vec3& n, const Vec3& p) {
  double h = -kInf;
  for (int i = 0; i < 3; ++i) h = std::max(h, k.c[i].dot(n) + k.r[i]);
  return h - n.dot(p);
}

}  // namespace

bool collinear_centres(const MedialAtom& a, const MedialAtom& b, const MedialAtom& c) {
  const double longest =
      std::max({(b.centre - a.centre).squaredNorm(), (c.centre - b.centre).squaredNorm(),
                (a.centre - c.centre).squaredNorm()});
  const double area = 0.5 * (b.centre - a.centre).cross(c.centre - a.centre).norm();
  return !(area > 1e-12 * longest);
}

Slab make_slab(const MedialAtom& a, const MedialAtom& b, const MedialAtom& c, int i, int j, int k) {
  Slab s;
  s.atoms = {i, j, k};
  const MedialAtom* balls[3] = {&a, &b, &c};
  for (int x = 0; x < 3; ++x) {
    s.c[x] = balls[x]->centre;
    s.r[x] = balls[x]->radius;
  }
  const Vec3 e1 = s.c[1] - s.c[0], e2 = s.c[2] - s.c[0];
  s.normal = e1.cross(e2).normalized();
  // g = alpha e1 + beta e2 with g . e1 = r1 - r0, g . e2 = r2 - r0.
  const double g11 = e1.dot(e1), g12 = e1.dot(e2), g22 = e2.dot(e2);
  const double det = g11 * g22 - g12 * g12;
  const double d1 = s.r[1] - s.r[0], d2 = s.r[2] - s.r[0];
  const double alpha = (g22 * d1 - g12 * d2) / det, beta = (g11 * d2 - g12 * d1) / det;
  s.gradient = alpha * e1 + beta * e2;
  const double g2 = s.gradient.squaredNorm();
  s.has_tangent_triangles = g2 < 1;
  if (s.has_tangent_triangles) {
    const double root = std::sqrt(1 - g2);
    s.tangent_normal[0] = (-s.gradient + root * s.normal).normalized();
    s.tangent_normal[1] = (-s.gradient - root * s.normal).normalized();
    for (int side = 0; side < 2; ++side)
      for (int x = 0; x < 3; ++x) s.tangent[side][x] = s.c[x] + s.r[x] * s.tangent_normal[side];
    // The prism's faces: the tangent planes, then the side planes through the edges of the
    // tangent triangle (they hold nu), each turned away from the opposite corner.
    for (int side = 0; side < 2; ++side) {
      s.prism_normal[side] = s.tangent_normal[side];
      s.prism_offset[side] = s.tangent_normal[side].dot(s.tangent[side][0]);
    }
    for (int e = 0; e < 3; ++e) {
      const Vec3& from = s.tangent[0][e];
      const Vec3& to = s.tangent[0][(e + 1) % 3];
      const Vec3& third = s.tangent[0][(e + 2) % 3];
      Vec3 m = (to - from).cross(s.normal).normalized();
      if (m.dot(third - from) > 0) m = -m;
      s.prism_normal[2 + e] = m;
      s.prism_offset[2 + e] = m.dot(from);
    }
    for (const auto& triangle : s.tangent)
      for (const Vec3& v : triangle) s.prism_box.extend(v);
  }
  double longest = 0, steepest = 0;
  for (int e = 0; e < 3; ++e) {
    const int x = e, y = (e + 1) % 3;
    const double L = (s.c[y] - s.c[x]).norm(), dr = s.r[y] - s.r[x];
    longest = std::max(longest, L);
    steepest = std::max(steepest, std::abs(dr));
    if (!(L > std::abs(dr) + 1e-12 * (L + s.r[x] + s.r[y]))) {
      s.edge_is_ball[e] = true;
      s.edge_ball[e] = dr > 0 ? y : x;
    } else {
      s.edge[e] = make_cone(*balls[x], *balls[y], s.atoms[x], s.atoms[y]);
    }
  }
  s.lipschitz = 2 * (longest + steepest);
  return s;
}

double slab_distance(const Slab& k, const Vec3& p) {
  double s, t;
  if (foot(k, p, s, t)) return (p - k.centre(s, t)).norm() - k.radius(s, t);
  double best = kInf;
  for (int e = 0; e < 3; ++e) best = std::min(best, edge_distance(k, e, p));
  return best;
}

Vec3 closest_solid_point(const Slab& k, const Vec3& p) {
  double s, t;
  if (foot(k, p, s, t)) {
    const Vec3 c = k.centre(s, t);
    const double r = k.radius(s, t), d = (p - c).norm();
    return d <= r ? p : Vec3(c + (r / d) * (p - c));
  }
  int best = 0;
  double distance = kInf;
  for (int e = 0; e < 3; ++e) {
    const double x = edge_distance(k, e, p);
    if (x < distance) {
      distance = x;
      best = e;
    }
  }
  if (distance <= 0) return p;
  // The nearest point of the edge hull's nearest interpolated ball (the cone's frustum alone
  // leaves out the balls' caps).
  Vec3 c;
  double r;
  if (k.edge_is_ball[best]) {
    c = k.c[k.edge_ball[best]];
    r = k.r[k.edge_ball[best]];
  } else {
    const Cone& cone = k.edge[best];
    const double along = hull_parameter(cone, p);
    c = cone.centre(along);
    r = cone.radius(along);
  }
  return c + (r / (p - c).norm()) * (p - c);
}

Vec3 closest_boundary_point(const Slab& k, const Vec3& p) {
  if (slab_distance(k, p) > 0) return closest_solid_point(k, p);
  // min over unit n of h(n) - n . p, over the normals where one ball, one pair or all three
  // balls attain h: each candidate's gap is an upper bound, the least one exact.
  double best = kInf;
  Vec3 normal = k.normal;
  auto consider = [&](const Vec3& n) {
    const double gap = support_gap(k, n, p);
    if (gap < best) {
      best = gap;
      normal = n;
    }
  };
  for (int i = 0; i < 3; ++i) {
    const Vec3 w = p - k.c[i];
    const double len = w.norm();
    if (len > 0) {
      consider(w / len);
    } else {
      consider(k.normal);
      consider(-k.normal);
    }
  }
  for (int e = 0; e < 3; ++e) {
    if (k.edge_is_ball[e]) continue;
    // The cone's outward normals are sin(phi) u + cos(phi) e, e normal to the axis; the best for
    // p is p's own radial direction. On (or within rounding of) the axis every e gives the same
    // value, and the in-plane e pointing away from the third centre is the one where the third
    // ball is lowest: both are candidates.
    const Cone& cone = k.edge[e];
    Vec3 outward = cone.u.cross(k.normal);
    if (outward.dot(k.c[(e + 2) % 3] - cone.c1) > 0) outward = -outward;
    consider(cone.sin_phi * cone.u + cone.cos_phi * outward);
    const Vec3 w = p - cone.c1;
    const Vec3 radial = w - w.dot(cone.u) * cone.u;
    const double len = radial.norm();
    if (len > 0) consider(cone.sin_phi * cone.u + (cone.cos_phi / len) * radial);
  }
  if (k.has_tangent_triangles) {
    consider(k.tangent_normal[0]);
    consider(k.tangent_normal[1]);
  }
  return p + best * normal;
}

bool contains_deeper_than(const Slab& k, const Vec3& p, double eps) {
  const double d = slab_distance(k, p);
  if (eps < 0) return d < -eps;
  if (d >= 0) return false;
  if (-d > eps) return true;  // the deepest ball alone holds p that deep
  return (closest_boundary_point(k, p) - p).norm() > eps;
}

bool line_interval(const Slab& k, const Vec3& o, const Vec3& d, double& t0, double& t1) {
  double lo = kInf, hi = -kInf;
  double a = 0, b = 0;
  auto take = [&](bool hit) {  // after the call that set a and b
    if (!hit) return;
    lo = std::min(lo, a);
    hi = std::max(hi, b);
  };
  for (int i = 0; i < 3; ++i) {
    const MedialAtom ball{k.c[i], k.r[i]};
    take(line_interval(ball, o, d, a, b));
  }
  for (int e = 0; e < 3; ++e)
    if (!k.edge_is_ball[e]) take(line_interval(k.edge[e], o, d, a, b));
  if (k.has_tangent_triangles) take(prism_interval(k, o, d, a, b));
  if (!(lo <= hi)) return false;
  t0 = lo;
  t1 = hi;
  return true;
}

bool prism_interval(const Slab& k, const Vec3& o, const Vec3& d, double& t0, double& t1) {
  if (!k.has_tangent_triangles) return false;
  double lo = -kInf, hi = kInf;
  for (int f = 0; f < 5; ++f) {  // keep n . x <= offset
    const double dn = k.prism_normal[f].dot(d), gap = k.prism_offset[f] - k.prism_normal[f].dot(o);
    if (dn == 0) {
      if (gap < 0) return false;
      continue;
    }
    const double t = gap / dn;
    if (dn > 0)
      hi = std::min(hi, t);
    else
      lo = std::max(lo, t);
    if (!(lo <= hi)) return false;
  }
  t0 = lo;
  t1 = hi;
  return true;
}

double prism_depth(const Slab& k, const Vec3& p) {
  if (!k.has_tangent_triangles) return -kInf;
  double depth = kInf;
  for (int f = 0; f < 5; ++f) depth = std::min(depth, k.prism_offset[f] - k.prism_normal[f].dot(p));
  return depth;
}

Vec3 prism_boundary_point(const Slab& k, const Vec3& p) {
  int nearest = 0;
  double depth = kInf;
  for (int f = 0; f < 5; ++f) {
    const double gap = k.prism_offset[f] - k.prism_normal[f].dot(p);
    if (gap < depth) {
      depth = gap;
      nearest = f;
    }
  }
  return p + depth * k.prism_normal[nearest];
}

Vec3 migration_vector(const Slab& k, const Vec3& v) {
  double s, t;
  if (!foot(k, v, s, t)) return Vec3::Zero();
  const Vec3 d = v - k.centre(s, t);
  const double d2 = d.squaredNorm();
  if (d2 == 0 || k.normal.dot(v - k.c[0]) == 0) return Vec3::Zero();
  return k.radius(s, t) * d / d2;
}

Eigen::AlignedBox3d bounding_box(const Slab& k) {
  Eigen::AlignedBox3d box;
  for (int i = 0; i < 3; ++i) {
    box.extend(Vec3(k.c[i] - Vec3::Constant(k.r[i])));
    box.extend(Vec3(k.c[i] + Vec3::Constant(k.r[i])));
  }
  return box;
}

double tangent_area(const Slab& k) {
  if (!k.has_tangent_triangles) return 0;
  double area = 0;
  for (int side = 0; side < 2; ++side) {
    const auto& t = k.tangent[side];
    area += 0.5 * (t[1] - t[0]).cross(t[2] - t[0]).norm();
  }
  return area;
}

Vec3 tangent_point(const Slab& k, double u, double v, double w) {
  const auto& t = k.tangent[w < 0.5 ? 0 : 1];  // the two triangles are mirror images
  const double a = std::sqrt(u);
  return (1 - a) * t[0] + (a * (1 - v)) * t[1] + (a * v) * t[2];
}

}  // namespace mg::garbing
