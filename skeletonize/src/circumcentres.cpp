// Circumcentres in interval arithmetic, with an exact rational fallback (CGAL).
#include "circumcentres.h"

#include <CGAL/Exact_rational.h>
#include <CGAL/Interval_nt.h>
#include <CGAL/constructions/kernel_ftC3.h>

#include <algorithm>
#include <cmath>

namespace mg::skeletonize::detail {

using Vec3 = Eigen::Vector3d;

bool interval_circumcentre(const std::array<Vec3, 4>& p, Vec3& out) {
  using I = CGAL::Interval_nt<false>;
  I nx, ny, nz, den;
  CGAL::determinants_for_circumcenterC3(
      I(p[0].x()), I(p[0].y()), I(p[0].z()), I(p[1].x()), I(p[1].y()), I(p[1].z()), I(p[2].x()),
      I(p[2].y()), I(p[2].z()), I(p[3].x()), I(p[3].y()), I(p[3].z()), nx, ny, nz, den);
  if (!(den.inf() > 0 || den.sup() < 0)) return false;
  const I inv = I(1) / (I(2) * den);
  const I off[3] = {nx * inv, -(ny * inv), nz * inv};
  double width = 0, size = 0;
  for (int k = 0; k < 3; ++k) {
    if (!std::isfinite(off[k].inf()) || !std::isfinite(off[k].sup())) return false;
    width = std::max(width, off[k].sup() - off[k].inf());
    size = std::max(size, std::abs(CGAL::to_double(off[k])));
    for (int j = 1; j < 4; ++j) size = std::max(size, std::abs(p[j][k] - p[0][k]));
  }
  if (!(width <= 1e-10 * size)) return false;
  out = p[0] + Vec3(CGAL::to_double(off[0]), CGAL::to_double(off[1]), CGAL::to_double(off[2]));
  return true;
}

bool exact_circumcentre(const std::array<Vec3, 4>& p, Vec3& out) {
  using Q = CGAL::Exact_rational;
  Q nx, ny, nz, den;
  CGAL::determinants_for_circumcenterC3(
      Q(p[0].x()), Q(p[0].y()), Q(p[0].z()), Q(p[1].x()), Q(p[1].y()), Q(p[1].z()), Q(p[2].x()),
      Q(p[2].y()), Q(p[2].z()), Q(p[3].x()), Q(p[3].y()), Q(p[3].z()), nx, ny, nz, den);
  if (CGAL::is_zero(den)) return false;  // cannot happen for a Delaunay cell (exact orientation)
  const Q inv = Q(1) / (Q(2) * den);
  out = Vec3(CGAL::to_double(Q(p[0].x()) + nx * inv), CGAL::to_double(Q(p[0].y()) - ny * inv),
             CGAL::to_double(Q(p[0].z()) + nz * inv));
  return out.allFinite();
}

}  // namespace mg::skeletonize::detail
