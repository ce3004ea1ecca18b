#pragma once
/// \file detail/plain_distance_traits.h
/// Internal, for .cpp files only (CGAL stays out of every module's interface): CGAL's AABB
/// traits over triangles of CGAL::Epick with the two functors of the closest-point traversal
/// done in plain doubles. CGAL's own run filtered predicates (sphere against box, which fall
/// back to exact rationals on ties: flat meshes have many) and its general triangle
/// projection: 60 % of a query's time (measured with perf, evaluate's distances). A distance
/// needs no exact predicate: the result is exact up to the rounding of the final projection
/// either way. Intersection and side-of queries keep CGAL's functors.

#include <CGAL/AABB_traits.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <Eigen/Core>

#include <algorithm>
#include <cmath>

namespace mg::detail {

/// Closest point of triangle abc to p in plain double arithmetic (Ericson, Real-Time Collision
/// Detection, 5.1.5): Voronoi regions of the vertices, then of the edges, then the face. A
/// degenerate (collinear) triangle's answer lies on its edges (checked before the face).
inline CGAL::Epick::Point_3 closest_on_triangle(const CGAL::Epick::Point_3& p,
                                                const CGAL::Epick::Triangle_3& t) {
  using V = Eigen::Vector3d;
  using Point = CGAL::Epick::Point_3;
  const V P(p.x(), p.y(), p.z()), A(t[0].x(), t[0].y(), t[0].z()), B(t[1].x(), t[1].y(), t[1].z()),
      C(t[2].x(), t[2].y(), t[2].z());
  auto out = [](const V& q) { return Point(q.x(), q.y(), q.z()); };
  const V ab = B - A, ac = C - A, ap = P - A;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return t[0];
  const V bp = P - B;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return t[1];
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return out(A + (d1 / (d1 - d3)) * ab);
  const V cp = P - C;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return t[2];
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return out(A + (d2 / (d2 - d6)) * ac);
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return out(B + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (C - B));
  const double sum = va + vb + vc;
  if (!(sum > 0)) {  // degenerate: the nearest of the three edges' closest points
    auto on_segment = [&](const V& a, const V& b) {
      const V ab2 = b - a;
      const double len = ab2.squaredNorm();
      const double s = len > 0 ? std::clamp((P - a).dot(ab2) / len, 0.0, 1.0) : 0.0;
      return V(a + s * ab2);
    };
    V best = on_segment(A, B);
    for (const V& q : {on_segment(B, C), on_segment(C, A)})
      if ((q - P).squaredNorm() < (best - P).squaredNorm()) best = q;
    return out(best);
  }
  const double denom = 1 / sum;
  return out(A + ab * (vb * denom) + ac * (vc * denom));
}

inline double squared_plain(const CGAL::Epick::Point_3& a, const CGAL::Epick::Point_3& b) {
  const double x = a.x() - b.x(), y = a.y() - b.y(), z = a.z() - b.z();
  return x * x + y * y + z * z;
}

/// Squared distance from p to a closed box (0 inside), plain doubles.
inline double box_squared_distance(const CGAL::Epick::Point_3& p, const CGAL::Bbox_3& box) {
  double d = 0;
  for (int k = 0; k < 3; ++k) {
    const double c = p[k];
    if (c < box.min(k))
      d += (box.min(k) - c) * (box.min(k) - c);
    else if (c > box.max(k))
      d += (c - box.max(k)) * (c - box.max(k));
  }
  return d;
}

/// CGAL::AABB_traits<Epick, Primitive> (Primitive's datum a Triangle_3) with plain-double
/// Compare_distance and Closest_point.
template <class Primitive>
class PlainDistanceTraits : public CGAL::AABB_traits<CGAL::Epick, Primitive> {
 public:
  using Point = CGAL::Epick::Point_3;
  class Compare_distance {
   public:
    /// SMALLER when the closed box meets the ball around p through `bound`.
    CGAL::Comparison_result operator()(const Point& p, const CGAL::Bbox_3& box,
                                       const Point& bound) const {
      return box_squared_distance(p, box) <= squared_plain(p, bound) ? CGAL::SMALLER : CGAL::LARGER;
    }
  };
  class Closest_point {
   public:
    explicit Closest_point(const PlainDistanceTraits& traits) : traits_(&traits) {}
    Point operator()(const Point& p, const Primitive& primitive, const Point& bound) const {
      // The datum through the traits: a face-graph primitive's needs the traits' shared data.
      const Point q = closest_on_triangle(
          p, CGAL::internal::Primitive_helper<PlainDistanceTraits>::get_datum(primitive, *traits_));
      return squared_plain(p, q) < squared_plain(p, bound) ? q : bound;
    }

   private:
    const PlainDistanceTraits* traits_;
  };
  Compare_distance compare_distance_object() const { return {}; }
  Closest_point closest_point_object() const { return Closest_point(*this); }
};

}  // namespace mg::detail
