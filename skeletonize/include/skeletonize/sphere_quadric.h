#pragma once
/// \file sphere_quadric.h
/// The spherical quadric error of Q-MAT (Li et al., ACM TOG 2015): a sphere m = (c, r) is a
/// point of R^4, and its signed gap to a plane with unit normal n (pointing out of the solid)
/// through the point p is e(m) = n . (p - c) - r, zero when the sphere touches the plane from
/// inside. With n~ = (n, 1) and d = n . p, e(m)^2 = m^T (n~ n~^T) m - 2 d n~^T m + d^2: a quadric
/// in m. A sum of weighted planes is one quadric Q(m) = m^T A m - 2 b^T m + c. See
/// docs/algorithm.md "Simplification".

#include "core/medial_surface.h"

#include <Eigen/Core>

namespace mg::skeletonize {

/// Q(m) = m^T A m - 2 b^T m + c over spheres m = (cx, cy, cz, r). Model units: A is unitless
/// times the weights, b and c carry lengths (c: length^2) times the weights.
struct SphereQuadric {
  Eigen::Matrix4d a = Eigen::Matrix4d::Zero();
  Eigen::Vector4d b = Eigen::Vector4d::Zero();
  double c = 0;

  /// Adds weight * e(m)^2 for the plane through `point` with unit `normal` (out of the solid).
  /// @pre normal has unit length; weight >= 0
  void add_plane(const Eigen::Vector3d& normal, const Eigen::Vector3d& point, double weight);

  SphereQuadric& operator+=(const SphereQuadric& o) {
    a += o.a;
    b += o.b;
    c += o.c;
    return *this;
  }

  /// Q(m), clamped at 0 (a sum of squares; rounding can take it a little below).
  double error(const MedialAtom& m) const;
};

/// How place_merged_atom() placed the merged sphere.
enum class Placement {
  minimiser,  ///< Q's unique minimiser (A well conditioned)
  /// A nearly singular: the minimiser nearest to the midpoint of the two spheres (eigenvalues of
  /// A under 1e-8 of the largest dropped), e.g. a flat sheet, whose planes leave the in-plane
  /// position free
  nearest_minimiser,
  /// the minimiser's radius would be <= 0 (or A is zero): the best of the two spheres and their
  /// midpoint, by Q (ties: the larger sphere, then the smaller, then the midpoint)
  fallback
};

struct MergedAtom {
  MedialAtom atom;
  double error = 0;  ///< Q(atom)
  Placement placement = Placement::minimiser;
};

/// The sphere an edge collapse of spheres `p` and `q` becomes: the minimiser of `quadric` (their
/// quadrics' sum), with the fallbacks of Placement. The result's radius is > 0 when p's or q's is.
/// @pre p, q finite with radii >= 0; quadric finite
MergedAtom place_merged_atom(const SphereQuadric& quadric, const MedialAtom& p,
                             const MedialAtom& q);

/// Q-MAT's stability ratio of the edge joining two spheres: (L - |r_p - r_q|) / L, L the distance
/// of the centres, in [0, 1]: 1 for equal radii, 0 when one ball holds the other (or L = 0).
/// Small ratios mark the unstable spikes of a medial axis (a ball nearly inside its neighbour).
double stability_ratio(const MedialAtom& p, const MedialAtom& q);

}  // namespace mg::skeletonize
