#pragma once
// Internal to mg::skeletonize: robust circumcentres of Delaunay cells (the Voronoi vertices).

#include <Eigen/Core>

#include <array>

namespace mg::skeletonize::detail {

/// Circumcentre of the cell (p[0], p[1], p[2], p[3]) in interval arithmetic (a guaranteed
/// enclosure, unlike a residual check: a wrong centre on the axis of 4 nearly cocircular points
/// passes equal-distance checks). False when the interval is wider than 1e-10 of the centre's
/// offset from p[0] or of the cell's size: the caller then computes it exactly.
/// @pre FPU rounding upward (CGAL::Protect_FPU_rounding<true>)
bool interval_circumcentre(const std::array<Eigen::Vector3d, 4>& p, Eigen::Vector3d& out);

/// The exact circumcentre, rounded to doubles. False when it is not a finite double.
bool exact_circumcentre(const std::array<Eigen::Vector3d, 4>& p, Eigen::Vector3d& out);

}  // namespace mg::skeletonize::detail
