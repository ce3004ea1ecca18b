// The slab's meeting tests: boxes, balls, cones and other slabs, by convex searches over its
// medial triangle that err only toward "meets".
#include "garbing/detail/convex_search.h"
#include "garbing/slab.h"

#include <algorithm>
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
  // The box's centre: slab_distance is 1-Lipschitz, so within the inscribed ball it meets, and
  // beyond the circumscribed ball it misses.
  const Vec3 centre = (lo + hi) / 2, half = (hi - lo) / 2;
  const double at_centre = slab_distance(k, centre);
  if (at_centre <= half.minCoeff()) return true;
  if (at_centre > half.norm()) return false;
  return slab_reaches(k, [&](const Vec3& x) { return box_distance(lo, hi, x); });
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

}  // namespace mg::garbing
