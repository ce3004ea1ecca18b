#pragma once
/// \file detail/cgal_conversions.h
/// Internal: conversions between the project's types and CGAL's, for .cpp files only (never
/// include this from a public header: CGAL stays out of every module's interface).
/// The one place where an atom becomes a CGAL weighted point: CGAL's weight is the SQUARED
/// radius (regular triangulations, skin surfaces, unions of balls).

#include "core/medial_surface.h"

#include <CGAL/number_utils.h>

namespace mg::detail {

template <class Kernel>
typename Kernel::Point_3 to_cgal_point(const Eigen::Vector3d& p) {
  return typename Kernel::Point_3(p.x(), p.y(), p.z());
}

template <class Point>
Eigen::Vector3d to_eigen(const Point& p) {
  return Eigen::Vector3d(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z()));
}

/// Weighted point of an atom: weight = radius^2.
template <class Kernel>
typename Kernel::Weighted_point_3 to_weighted_point(const MedialAtom& a) {
  return typename Kernel::Weighted_point_3(to_cgal_point<Kernel>(a.centre), a.radius * a.radius);
}

}  // namespace mg::detail
