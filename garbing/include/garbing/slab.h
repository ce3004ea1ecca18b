#pragma once
/// \file slab.h
/// The medial slab: the convex hull of three balls (c_i, r_i), the primitive a face of a
/// medial mesh contributes to its envelope (docs/algorithm.md, "Medial meshes"). Its solid is
/// the union of the interpolated balls B(c(l), r(l)), l barycentric over the medial triangle,
/// c and r affine in l; every function of l below is convex.
///
/// Closed forms. In the plane of the medial triangle (unit normal nu) the radius is affine,
/// r(x) = r_0 + g . (x - c_0), g its in-plane gradient. For a point p at height h = nu . (p - c_0)
/// with in-plane foot q, the stationary point of |p - c(x)| - r(x) is x* = q + g |h| / s,
/// s = sqrt(1 - |g|^2) (|g| < 1): the foot on the medial plane of the slab's normal through p,
/// as a cone's foot on its axis. When x* falls outside the triangle (or |g| >= 1)
/// the minimum lies on the triangle's boundary, that is on one of the three edge hulls (a cone,
/// or the larger ball when one holds the other). When |g| < 1 the two planes tangent to all three
/// spheres have normals n+- = -g +- s nu, touching the spheres at c_i + r_i n+-: the tangent
/// triangles. The slab is the union of its three balls, its three edge hulls and the prism
/// between the two tangent triangles (the reflection in the medial plane maps each piece to
/// itself, so each chord normal to that plane lies in the piece that holds its ends; the prism
/// is the one over the tangent triangles' common projection, c_i - r_i g). The tangent
/// triangles are mirror images of each other in the medial plane.

#include "core/medial_surface.h"
#include "garbing/primitives.h"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>

namespace mg::garbing {

/// A slab of three atoms. Built by make_slab, whose precondition rules out collinear centres.
struct Slab {
  std::array<int, 3> atoms = {-1, -1, -1};  ///< atom indices, as given
  std::array<Eigen::Vector3d, 3> c;         ///< centres
  std::array<double, 3> r = {0, 0, 0};      ///< radii (>= 0)
  Eigen::Vector3d normal;                   ///< nu: unit normal of the medial triangle
  Eigen::Vector3d gradient;                 ///< g: in-plane gradient of the radius
  /// Whether the tangent triangles exist (|g| < 1). Without them the slab's boundary is made of
  /// its balls' and edge hulls' patches only.
  bool has_tangent_triangles = false;
  /// tangent[0] on the side of +nu (normal n+), tangent[1] on the side of -nu; each the three
  /// touch points c_i + r_i n, in the order of the atoms.
  std::array<std::array<Eigen::Vector3d, 3>, 2> tangent;
  std::array<Eigen::Vector3d, 2> tangent_normal;  ///< n+, n- (unit, outward)
  /// The prism between the tangent triangles as five half-spaces n . x <= offset (the two
  /// tangent planes, then the three side planes, which hold the direction nu), and its box.
  /// Set only with tangent triangles.
  std::array<Eigen::Vector3d, 5> prism_normal;
  std::array<double, 5> prism_offset = {0, 0, 0, 0, 0};
  Eigen::AlignedBox3d prism_box;
  /// The edge hulls: edge k joins atoms (k, k + 1 mod 3); `edge_is_ball[k]` when one ball holds
  /// the other (the hull is the larger ball, `edge_ball[k]` its local index 0..2), otherwise
  /// `edge[k]` is the cone of the two balls (whether or not they intersect).
  std::array<Cone, 3> edge;
  std::array<bool, 3> edge_is_ball = {false, false, false};
  std::array<int, 3> edge_ball = {0, 0, 0};
  /// Bounds the slope of every convex function of the barycentric coordinates below along any
  /// unit step in parameter space: max edge length + max |r_i - r_j|, times 2.
  double lipschitz = 0;

  /// The interpolated ball at barycentric coordinates (1 - s - t, s, t).
  Eigen::Vector3d centre(double s, double t) const {
    return c[0] + s * (c[1] - c[0]) + t * (c[2] - c[0]);
  }
  double radius(double s, double t) const { return r[0] + s * (r[1] - r[0]) + t * (r[2] - r[0]); }
};

/// Whether three centres are too close to collinear to make a slab: the triangle's area is at
/// most 1e-12 of its longest edge squared. Such a face's hull is covered by its edge hulls.
bool collinear_centres(const MedialAtom& a, const MedialAtom& b, const MedialAtom& c);

/// Builds the slab of atoms i, j, k. @pre !collinear_centres(a, b, c); radii >= 0
Slab make_slab(const MedialAtom& a, const MedialAtom& b, const MedialAtom& c, int i, int j, int k);

/// min over the triangle of |p - c(l)| - r(l): the distance from p to the slab's solid when p is
/// outside; when inside, minus the depth of p in the deepest interpolated ball (a lower bound on
/// its depth in the solid). Exact up to rounding (closed form above).
double slab_distance(const Slab& s, const Eigen::Vector3d& p);

/// The closest point of the solid to p (p itself when p is inside).
Eigen::Vector3d closest_solid_point(const Slab& s, const Eigen::Vector3d& p);

/// The closest point of the slab's boundary to p, for p inside the solid (exact: the distance to
/// the boundary of a convex body is min over unit n of h(n) - n . p, h(n) = max_i c_i . n + r_i;
/// candidates are one ball, one pair on its cone, and the two tangent planes, each kept when it
/// attains the maximum). For p outside, closest_solid_point.
Eigen::Vector3d closest_boundary_point(const Slab& s, const Eigen::Vector3d& p);

/// Whether p lies strictly deeper than `eps` inside the solid (model units; a negative eps grows
/// the slab): the distance to the boundary exceeds eps (eps < 0: slab_distance(p) < -eps).
bool contains_deeper_than(const Slab& s, const Eigen::Vector3d& p, double eps);

/// The parameter interval [t0, t1] of the line o + t d inside the solid (convex: the least entry
/// and the greatest exit over its balls, edge cones and prism); false if the line misses it.
/// @param d need not be unit; t in units of |d|
bool line_interval(const Slab& s, const Eigen::Vector3d& o, const Eigen::Vector3d& d, double& t0,
                   double& t1);

/// The slab's own piece of G: the prism between its tangent triangles. The rest of its solid
/// is its balls and edge hulls, which G holds as primitives of their own (a ball, or a cone), so
/// G's union is the same with each slab replaced by its prism; and the prism is a convex
/// polytope of five faces, cheap to clip and to test. A slab without tangent triangles has no
/// prism (its solid is its edge hulls'): the tests below are false for it.

/// The parameter interval [t0, t1] of the line o + t d inside the prism; false if the line
/// misses it. @param d need not be unit; t in units of |d|
bool prism_interval(const Slab& s, const Eigen::Vector3d& o, const Eigen::Vector3d& d, double& t0,
                    double& t1);

/// min over the prism's five faces of offset - n . p: inside the closed prism (>= 0), the exact
/// distance from p to its boundary; outside (< 0), minus at most the distance to the prism.
/// -infinity without tangent triangles.
double prism_depth(const Slab& s, const Eigen::Vector3d& p);

/// The closest point of the prism's boundary to p, for p in the prism: its foot on the nearest
/// face plane. @pre s.has_tangent_triangles
Eigen::Vector3d prism_boundary_point(const Slab& s, const Eigen::Vector3d& p);

/// Whether the closed prism meets the closed box [lo, hi]: separating axes of two convex
/// polytopes (the box's 3 axes, the prism's 5 face normals, the cross products of their edge
/// directions), with a relative 1e-12 slack counted as meeting.
bool prism_meets_box(const Slab& s, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);

/// The migration vector of the slab at v: with p the foot of v on the medial triangle (x* above,
/// p = c(x*)) and r = r(x*), m_g(v) = r (v - p) / |v - p|^2; zero when x* falls outside the
/// triangle, when there are no tangent triangles, and when v lies in the medial plane.
Eigen::Vector3d migration_vector(const Slab& s, const Eigen::Vector3d& v);

/// The axis-aligned box of the solid (the union of its three balls' boxes).
Eigen::AlignedBox3d bounding_box(const Slab& s);

/// The area of the two tangent triangles (0 without them): the slab's own share of G's surface
/// (its balls and edge cones are primitives of their own).
double tangent_area(const Slab& s);

/// A point of the tangent triangles, uniform in area, from three numbers in [0, 1): w < 1/2
/// picks tangent[0] (the two have the same area), u and v place the point in it.
/// @pre s.has_tangent_triangles
Eigen::Vector3d tangent_point(const Slab& s, double u, double v, double w);

/// Whether the solid reaches the closed box [lo, hi]: its balls, the box's centre against
/// slab_distance (inscribed and circumscribed balls), its edge cones (hull_meets_box), then the
/// prism between the tangent triangles by separating axes. Exact up to rounding and the cone
/// searches' 1e-9, counted as meeting.
bool slab_meets_box(const Slab& s, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);

/// Whether the solids meet (closed): a ball, a cone, another slab. The ball test is exact
/// (slab_distance(b.centre) <= b.radius); the others are convex searches (over the cone's t, over
/// one slab's triangle, nested) exact up to their 1e-9 tolerance, counted as meeting.
bool slab_meets_ball(const Slab& s, const MedialAtom& b);
bool slab_meets_cone(const Slab& s, const Cone& k);
bool slabs_meet(const Slab& a, const Slab& b);

}  // namespace mg::garbing
