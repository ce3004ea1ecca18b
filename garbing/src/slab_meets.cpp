// The slab's meeting tests: boxes, balls, cones and other slabs, by convex searches over its
// medial triangle that err only toward "meets".
#include "garbing/detail/convex_search.h"
#include "garbing/slab.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace mg::garbing {
namespace {

using Vec3 = Eigen::Vector3d;

/// Whether f(s, t) = dist(c(s, t)) - r(s, t) reaches <= 0 over the triangle, for a convex,
/// 1-Lipschitz dist (so f is convex with slope bound k.lipschitz): a few exact shortcuts, then
/// the nested search.
template <class Distance>
bool slab_reaches(const Slab& k, const Distance& dist) {
  for (int i = 0; i < 3; ++i)
    if (dist(k.c[i]) <= k.r[i]) return true;
  return detail::convex_reaches_zero_on_triangle(
      [&](double s, double t) { return dist(k.centre(s, t)) - k.radius(s, t); }, k.lipschitz);
}

}  // namespace

bool slab_meets_box(const Slab& k, const Vec3& lo, const Vec3& hi) {
  if (!bounding_box(k).intersects(Eigen::AlignedBox3d(lo, hi))) return false;
  for (int i = 0; i < 3; ++i)
    if (box_distance(lo, hi, k.c[i]) <= k.r[i]) return true;
  // The box's centre: slab_distance is 1-Lipschitz, so within the inscribed ball it meets, and
  // beyond the circumscribed ball it misses. A box inside the slab is met here; any other box
  // meeting it meets its boundary, which lies on its balls, edge cones and tangent triangles.
  const Vec3 centre = (lo + hi) / 2, half = (hi - lo) / 2;
  const double at_centre = slab_distance(k, centre);
  if (at_centre <= half.minCoeff()) return true;
  if (at_centre > half.norm()) return false;
  for (int e = 0; e < 3; ++e)
    if (!k.edge_is_ball[e] && hull_meets_box(k.edge[e], lo, hi)) return true;
  return prism_meets_box(k, lo, hi);
}

bool slab_meets_ball(const Slab& k, const MedialAtom& b) {
  return slab_distance(k, b.centre) <= b.radius;
}

bool slab_meets_cone(const Slab& k, const Cone& cone) {
  return detail::convex_reaches_zero(
      [&](double t) { return slab_distance(k, cone.centre(t)) - cone.radius(t); }, cone.lipschitz);
}

bool slabs_meet(const Slab& a, const Slab& b) {
  return slab_reaches(a, [&](const Vec3& x) { return slab_distance(b, x); });
}

bool prism_meets_box(const Slab& k, const Vec3& lo, const Vec3& hi) {
  if (!k.has_tangent_triangles || !k.prism_box.intersects(Eigen::AlignedBox3d(lo, hi)))
    return false;
  const Vec3 centre = (lo + hi) / 2, half = (hi - lo) / 2;
  std::array<Vec3, 6> v;
  for (int side = 0; side < 2; ++side)
    for (int i = 0; i < 3; ++i) v[3 * side + i] = k.tangent[side][i] - centre;
  auto separates = [&](const Vec3& axis) {
    const double n2 = axis.squaredNorm();
    if (!(n2 > 1e-24 * (1 + v[0].squaredNorm()))) return false;  // degenerate axis
    double a = v[0].dot(axis), b = a;
    for (int i = 1; i < 6; ++i) {
      const double x = v[i].dot(axis);
      a = std::min(a, x);
      b = std::max(b, x);
    }
    const double reach = half.dot(axis.cwiseAbs());
    const double slack = 1e-12 * (std::abs(a) + std::abs(b) + reach);
    return a > reach + slack || b < -reach - slack;
  };
  // The box's own axes: the boxes' test above.
  std::array<Vec3, 7> edges;
  for (int i = 0; i < 3; ++i) {
    edges[i] = v[(i + 1) % 3] - v[i];
    edges[3 + i] = v[3 + (i + 1) % 3] - v[3 + i];
  }
  edges[6] = k.normal;  // the side faces hold the direction nu
  for (const Vec3& n : k.prism_normal)
    if (separates(n)) return false;
  for (const Vec3& d : edges)
    for (int e = 0; e < 3; ++e)
      if (separates(d.cross(Vec3::Unit(e)))) return false;
  return true;
}

}  // namespace mg::garbing
