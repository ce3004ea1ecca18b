#include "garbing/frame.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>

namespace mg::garbing {
namespace {

using Vec3 = Eigen::Vector3d;

Eigen::Matrix3d principal_axes(const MedialSurface& s) {
  Vec3 mean = Vec3::Zero();
  for (const auto& a : s.atoms) mean += a.centre;
  mean /= static_cast<double>(s.atoms.size());
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (const auto& a : s.atoms) cov += (a.centre - mean) * (a.centre - mean).transpose();
  cov /= static_cast<double>(s.atoms.size());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
  const Vec3 l = eig.eigenvalues();  // ascending
  const double tolerance = 1e-9 * std::max(std::abs(l[2]), 1e-300);
  if (!(l[1] - l[0] > tolerance && l[2] - l[1] > tolerance)) return Eigen::Matrix3d::Identity();
  Eigen::Matrix3d axes;
  for (int k = 0; k < 2; ++k) {
    Vec3 e = eig.eigenvectors().col(2 - k);
    Eigen::Index big = 0;
    e.cwiseAbs().maxCoeff(&big);
    if (e[big] < 0) e = -e;
    axes.col(k) = e.normalized();
  }
  axes.col(2) = axes.col(0).cross(axes.col(1)).normalized();
  return axes;
}

}  // namespace

Frame bounding_cube_frame(const MedialSurface& atoms) {
  validate(atoms);
  Frame f;
  f.axes = principal_axes(atoms);
  Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY);
  for (const auto& a : atoms.atoms) {
    const Vec3 p = f.axes.transpose() * a.centre;
    lo = lo.cwiseMin(p - Vec3::Constant(a.radius));
    hi = hi.cwiseMax(p + Vec3::Constant(a.radius));
  }
  f.cube_side = (hi - lo).maxCoeff();
  const Vec3 corner = (lo + hi) / 2 - Vec3::Constant(f.cube_side / 2);
  f.origin = f.axes * corner;
  return f;
}

}  // namespace mg::garbing
