// The spherical quadric error metric and the placement of a merged atom.
#include "skeletonize/sphere_quadric.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace mg::skeletonize {
namespace {

using Vec4 = Eigen::Vector4d;

Vec4 to_vec4(const MedialAtom& m) { return {m.centre.x(), m.centre.y(), m.centre.z(), m.radius}; }
MedialAtom to_atom(const Vec4& v) { return {v.head<3>(), v[3]}; }

/// Eigenvalues of A under this fraction of the largest are dropped (A nearly singular).
constexpr double kRelativeEigenvalue = 1e-8;

}  // namespace

void SphereQuadric::add_plane(const Eigen::Vector3d& normal, const Eigen::Vector3d& point,
                              double weight) {
  const Vec4 n(normal.x(), normal.y(), normal.z(), 1.0);
  const double d = normal.dot(point);
  a.noalias() += weight * n * n.transpose();
  b.noalias() += (weight * d) * n;
  c += weight * d * d;
}

double SphereQuadric::error(const MedialAtom& m) const {
  const Vec4 v = to_vec4(m);
  return std::max(0.0, v.dot(a * v) - 2 * b.dot(v) + c);
}

MergedAtom place_merged_atom(const SphereQuadric& quadric, const MedialAtom& p,
                             const MedialAtom& q) {
  const Vec4 mid = 0.5 * (to_vec4(p) + to_vec4(q));
  const double largest = quadric.a.diagonal().maxCoeff();  // >= every eigenvalue / 4
  Vec4 m = mid;
  Placement placement = Placement::minimiser;
  bool solved = false;
  if (largest > 0) {
    // Cheap first: LDLT with pivoting; well conditioned when its pivots are.
    const Eigen::LDLT<Eigen::Matrix4d> ldlt(quadric.a);
    const Vec4 pivots = ldlt.vectorD().cwiseAbs();
    if (ldlt.info() == Eigen::Success && ldlt.isPositive() &&
        pivots.minCoeff() > 1e2 * kRelativeEigenvalue * pivots.maxCoeff()) {
      m = ldlt.solve(quadric.b);
      solved = m.allFinite();
    }
    if (!solved) {
      // The minimiser nearest to the midpoint in the well-determined directions.
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eigen(quadric.a);
      const Vec4& lambda = eigen.eigenvalues();  // increasing
      const double cut = kRelativeEigenvalue * lambda[3];
      const Vec4 residual = quadric.b - quadric.a * mid;
      m = mid;
      for (int k = 0; k < 4; ++k)
        if (lambda[k] > cut) {
          const Vec4 u = eigen.eigenvectors().col(k);
          m += (u.dot(residual) / lambda[k]) * u;
        }
      solved = m.allFinite();
      placement = Placement::nearest_minimiser;
    }
  }
  if (solved && m[3] > 0) {
    const MedialAtom atom = to_atom(m);
    return {atom, quadric.error(atom), placement};
  }
  // Fallback: the larger sphere, the smaller, their midpoint (first of the least error).
  const MedialAtom& large = p.radius >= q.radius ? p : q;
  const MedialAtom& small = p.radius >= q.radius ? q : p;
  MergedAtom best{large, quadric.error(large), Placement::fallback};
  for (const MedialAtom& candidate : {small, to_atom(mid)}) {
    if (!(candidate.radius > 0)) continue;
    const double e = quadric.error(candidate);
    if (e < best.error) best = {candidate, e, Placement::fallback};
  }
  return best;
}

double stability_ratio(const MedialAtom& p, const MedialAtom& q) {
  const double length = (p.centre - q.centre).norm();
  if (!(length > 0)) return 0;
  return std::clamp((length - std::abs(p.radius - q.radius)) / length, 0.0, 1.0);
}

}  // namespace mg::skeletonize
