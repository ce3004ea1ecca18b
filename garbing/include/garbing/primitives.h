#pragma once
/// \file primitives.h
/// The primitives of the target shape G (docs/algorithm.md, "Step 3"): balls (the atoms) and
/// cones, the convex hull of two intersecting balls. Everything the stages ask of one primitive
/// lives here, exact up to rounding: the crease where two spheres meet, the distance to a
/// cone's solid, the paper's migration vector m_g, where a line enters and leaves a primitive,
/// closest points, and whether a primitive meets an axis-aligned box.
///
/// A cone's solid is the union of the balls B(c(t), r(t)), c and r linear from (c1, r1) at
/// t = 0 to (c2, r2) at t = 1; every function of t below is convex in t.

#include "core/medial_surface.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace mg::garbing {

/// The crease of two intersecting spheres: the circle where they meet. It lies in the plane
/// normal to the axis at `along` from the first centre, and has radius `radius`.
struct Crease {
  double along = 0;
  double radius = 0;
};

/// @param length |c2 - c1|, model units   @pre |r1 - r2| < length < r1 + r2
inline Crease crease(double length, double r1, double r2) {
  Crease c;
  c.along = (length * length + r1 * r1 - r2 * r2) / (2 * length);
  c.radius = std::sqrt(std::max(0.0, r1 * r1 - c.along * c.along));
  return c;
}

/// The solid cone tangent to two balls (c1, r1), (c2, r2) neither of which holds the other,
/// L > |r1 - r2|, whether or not they intersect (a medial mesh's edge joins balls that may not):
/// the truncated cone between the two tangent circles. Axial coordinate x from c1 along u.
struct Cone {
  int a = -1, b = -1;               ///< atom indices
  Eigen::Vector3d c1, u;            ///< first centre, unit axis toward the second
  double r1 = 0, length = 0;        ///< first radius, L = |c2 - c1|
  double r2 = 0;                    ///< second radius
  double sin_phi = 0, cos_phi = 1;  ///< sin(phi) = (r1 - r2) / L
  double t_lo = 0, t_hi = 0;        ///< axial range of the lateral surface
  double rho_lo = 0, rho_hi = 0;    ///< its radius at t_lo and t_hi
  /// A ball holding the frustum: centred on the axis midway between t_lo and t_hi, through
  /// its rims (squared radius); a cheap rejection for line tests.
  Eigen::Vector3d bound_centre = Eigen::Vector3d::Zero();
  double bound_radius2 = 0;
  /// Whether the balls are disjoint (L >= r1 + r2): no crease, and the part of the solid outside
  /// both balls is a whole waist.
  bool disjoint = false;
  /// The crease of the two spheres (when they intersect). In the profile half-plane (axial x,
  /// distance from the axis), the part of the solid outside both balls (the crease fill) lies
  /// inside the triangle of the crease point and the two rims; fill_lo, fill_hi are that
  /// triangle's box (x, radius). For disjoint balls, the frustum's profile box.
  Crease crease;
  double fill_lo[2] = {0, 0}, fill_hi[2] = {0, 0};
  double dr = 0;         ///< r2 - r1
  double lipschitz = 0;  ///< L + |dr|: bounds the slope in t of every convex function below

  /// The interpolated ball of parameter t in [0, 1].
  Eigen::Vector3d centre(double t) const { return c1 + (t * length) * u; }
  double radius(double t) const { return r1 + t * dr; }
};

/// Builds the cone of atoms a and b. @pre neither ball holds the other: |c2 - c1| > |r2 - r1|
Cone make_cone(const MedialAtom& first, const MedialAtom& second, int a, int b);

/// Fills the fields of `c` that follow from a, b, c1, u, r1, length, r2, sin_phi, cos_phi and
/// crease by products, sums and comparisons (make_cone's last step).
inline void complete_cone(Cone& c) {
  c.t_lo = c.r1 * c.sin_phi;
  c.rho_lo = c.r1 * c.cos_phi;
  c.t_hi = c.length + c.r2 * c.sin_phi;
  c.rho_hi = c.r2 * c.cos_phi;
  const double half = (c.t_hi - c.t_lo) / 2, rim = std::max(c.rho_lo, c.rho_hi);
  c.bound_centre = c.c1 + (c.t_lo + half) * c.u;
  c.bound_radius2 = half * half + rim * rim;
  c.dr = c.r2 - c.r1;
  c.lipschitz = c.length + std::abs(c.dr);
  c.disjoint = !(c.length < c.r1 + c.r2);
  if (c.disjoint) {
    c.fill_lo[0] = c.t_lo;
    c.fill_lo[1] = 0;
    c.fill_hi[0] = c.t_hi;
    c.fill_hi[1] = rim;
    return;
  }
  const double x0 = c.crease.along, rho0 = c.crease.radius;
  c.fill_lo[0] = std::min({x0, c.t_lo, c.t_hi});
  c.fill_lo[1] = std::min({rho0, c.rho_lo, c.rho_hi});
  c.fill_hi[0] = std::max({x0, c.t_lo, c.t_hi});
  c.fill_hi[1] = std::max({rho0, c.rho_lo, c.rho_hi});
}

/// What G stores of a cone (88 bytes instead of Cone's 232: at a million atoms G holds 3.3
/// million cones): its atoms, axis and radii, and cos(phi) (a square root).
struct StoredCone {
  int a = -1, b = -1;
  Eigen::Vector3d c1, u;
  double r1 = 0, length = 0, r2 = 0;
  double cos_phi = 1;
};

/// The stored fields of a cone.
StoredCone stored(const Cone& cone);

/// The cone back from its stored fields: bit for bit the Cone make_cone built (the same
/// expressions, in the same order, as make_cone's own).
inline Cone restored(const StoredCone& s) {
  Cone c;
  c.a = s.a;
  c.b = s.b;
  c.c1 = s.c1;
  c.u = s.u;
  c.r1 = s.r1;
  c.length = s.length;
  c.r2 = s.r2;
  c.sin_phi = (s.r1 - s.r2) / s.length;
  c.cos_phi = s.cos_phi;
  if (c.length < c.r1 + c.r2) c.crease = crease(c.length, c.r1, c.r2);
  complete_cone(c);
  return c;
}

/// restored(s).bound_centre and bound_radius2 alone (the same expressions), without the rest
/// of the cone: a cheap rejection before restoring it.
inline void bounding_ball(const StoredCone& s, Eigen::Vector3d& centre, double& radius2) {
  const double sin_phi = (s.r1 - s.r2) / s.length;
  const double t_lo = s.r1 * sin_phi, t_hi = s.length + s.r2 * sin_phi;
  const double half = (t_hi - t_lo) / 2, rim = std::max(s.r1 * s.cos_phi, s.r2 * s.cos_phi);
  centre = s.c1 + (t_lo + half) * s.u;
  radius2 = half * half + rim * rim;
}

/// min over t in [0, 1] of |p - c(t)| - r(t): the distance from p to the cone's solid when p
/// is outside it; when inside, minus the depth of p in the deepest ball B(c(t), r(t)), a lower
/// bound on its depth in the solid. Closed form: the stationary t has the foot of p on the axis
/// ahead of c(t) by tan(phi) times p's distance from the axis.
double hull_distance(const Cone& k, const Eigen::Vector3d& p);

/// The t in [0, 1] where hull_distance's minimum is attained: the ball B(c(t), r(t)) nearest p.
double hull_parameter(const Cone& k, const Eigen::Vector3d& p);

/// The per-primitive migration vector of the paper: with p the foot on the primitive's axis of
/// the surface normal through v and r the radius there, m_g(v) = r (v - p) / |v - p|^2. Zero
/// when v is on the axis, and for a cone when the foot falls outside [0, L].
Eigen::Vector3d migration_vector(const MedialAtom& ball, const Eigen::Vector3d& v);
Eigen::Vector3d migration_vector(const Cone& cone, const Eigen::Vector3d& v);
/// The same as migration_vector(restored(cone), v), from the stored fields alone.
Eigen::Vector3d migration_vector(const StoredCone& cone, const Eigen::Vector3d& v);

/// The parameter interval [t0, t1] of the line o + t d inside the closed ball (resp. the
/// cone's solid); false if the line misses it. @param d need not be unit; t in units of |d|
bool line_interval(const MedialAtom& ball, const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                   double& t0, double& t1);
bool line_interval(const Cone& cone, const Eigen::Vector3d& o, const Eigen::Vector3d& d, double& t0,
                   double& t1);

/// Whether p lies strictly deeper than `eps` inside the ball (resp. the cone's solid), model
/// units; a negative eps grows the primitive.
bool contains_deeper_than(const MedialAtom& ball, const Eigen::Vector3d& p, double eps);
bool contains_deeper_than(const Cone& cone, const Eigen::Vector3d& p, double eps);

/// The closest point of the cone's solid to p (p itself when p is inside, compared exactly).
Eigen::Vector3d closest_solid_point(const Cone& cone, const Eigen::Vector3d& p);
/// The closest point of the cone's lateral surface to p (p may be inside).
Eigen::Vector3d closest_lateral_point(const Cone& cone, const Eigen::Vector3d& p);

/// The area of the cone's lateral surface, model units squared.
double lateral_area(const Cone& cone);

/// The axis-aligned bounding box of the ball; of the cone's frustum (the boxes of its two rim
/// disks: much tighter than its balls' boxes).
Eigen::AlignedBox3d bounding_box(const MedialAtom& ball);
Eigen::AlignedBox3d bounding_box(const Cone& cone);

/// Distance from p to the closed box [lo, hi] (0 inside).
double box_distance(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, const Eigen::Vector3d& p);

/// Whether the closed ball meets the closed box [lo, hi] (exact).
bool meets_box(const MedialAtom& ball, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);

/// Whether the cone's solid reaches the closed box [lo, hi]: min over t of
/// box_distance(c(t)) - r(t) <= 0, by golden-section search that errs only toward "meets"
/// (within 1e-9 of the parameter range).
bool hull_meets_box(const Cone& cone, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);

/// False when the cube [lo, lo + side] is too far from the cone's crease fill to meet it
/// (conservative: the fill, revolved about the axis, lies in the profile triangle of the
/// crease point and the two rims; the cube's centre is compared with that triangle in its own
/// meridian half-plane; for disjoint balls, with the frustum's bounding ball). Monotone: a cube
/// is near whenever one of its sub-cubes is.
bool near_crease_fill(const Cone& cone, const Eigen::Vector3d& lo, double side);

/// Whether the closed cube [lo, lo + side], which meets neither of the cone's two balls, meets
/// the cone's solid (that is: its crease fill), up to 1e-9 of the slope bound, counted as
/// meeting.
bool fill_meets_cube(const Cone& cone, const Eigen::Vector3d& lo, double side);

/// Whether the solids of two cones meet: min over (s, t) of |c(s) - c'(t)| - r(s) - r'(t) <= 0,
/// jointly convex, its inner minimum in closed form (hull_distance); errs only toward "meet".
bool hulls_meet(const Cone& a, const Cone& b);

}  // namespace mg::garbing
