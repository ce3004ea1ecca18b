#pragma once
// Generated atom sets for the garbing tests.

#include "core/medial_surface.h"
#include "garbing/octree.h"
#include "garbing/target_shape.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <iterator>
#include <random>

namespace mg_test {

inline mg::MedialSurface atoms(std::initializer_list<mg::MedialAtom> list) {
  mg::MedialSurface s;
  s.atoms = list;
  return s;
}

/// n balls of radius r centred on the circle of radius R in the z = 0 plane.
inline mg::MedialSurface ring(int n, double R, double r) {
  mg::MedialSurface s;
  for (int k = 0; k < n; ++k) {
    const double t = 2 * 3.14159265358979323846 * k / n;
    s.atoms.push_back({Eigen::Vector3d(R * std::cos(t), R * std::sin(t), 0), r});
  }
  return s;
}

/// n balls of radius r evenly spaced from a to b (inclusive), appended to s.
inline void add_chain(mg::MedialSurface& s, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                      int n, double r) {
  for (int k = 0; k < n; ++k) s.atoms.push_back({a + (b - a) * (double(k) / (n - 1)), r});
}

/// A random blob: n balls, centres in [-1, 1]^3, radii in [rmin, rmax]; fixed seed.
inline mg::MedialSurface blob(int n, double rmin, double rmax, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> c(-1, 1), r(rmin, rmax);
  mg::MedialSurface s;
  for (int k = 0; k < n; ++k) {
    const double x = c(gen), y = c(gen), z = c(gen);
    s.atoms.push_back({Eigen::Vector3d(x, y, z), r(gen)});
  }
  return s;
}

/// G of the atoms as the garbing builds it: in their bounding cube frame.
inline mg::garbing::TargetShape shape_of(const mg::MedialSurface& s,
                                         const mg::garbing::ConeOptions& cones = {}) {
  return mg::garbing::make_target_shape(s, cones, mg::garbing::bounding_cube_frame(s));
}

/// Step 1 on the atoms' G (the octree keeps no reference to G).
inline mg::garbing::Octree octree_of(const mg::MedialSurface& s,
                                     const mg::garbing::OctreeOptions& opt = {},
                                     const mg::garbing::ConeOptions& cones = {}) {
  return mg::garbing::build_octree(shape_of(s, cones), opt);
}

/// Whether two cones are the same bit for bit, field by field (doubles compared with ==).
inline ::testing::AssertionResult same_cone(const mg::garbing::Cone& x,
                                            const mg::garbing::Cone& y) {
  const double xs[] = {x.c1.x(),
                       x.c1.y(),
                       x.c1.z(),
                       x.u.x(),
                       x.u.y(),
                       x.u.z(),
                       x.r1,
                       x.length,
                       x.r2,
                       x.sin_phi,
                       x.cos_phi,
                       x.t_lo,
                       x.t_hi,
                       x.rho_lo,
                       x.rho_hi,
                       x.bound_centre.x(),
                       x.bound_centre.y(),
                       x.bound_centre.z(),
                       x.bound_radius2,
                       x.crease.along,
                       x.crease.radius,
                       x.fill_lo[0],
                       x.fill_lo[1],
                       x.fill_hi[0],
                       x.fill_hi[1],
                       x.dr,
                       x.lipschitz};
  const double ys[] = {y.c1.x(),
                       y.c1.y(),
                       y.c1.z(),
                       y.u.x(),
                       y.u.y(),
                       y.u.z(),
                       y.r1,
                       y.length,
                       y.r2,
                       y.sin_phi,
                       y.cos_phi,
                       y.t_lo,
                       y.t_hi,
                       y.rho_lo,
                       y.rho_hi,
                       y.bound_centre.x(),
                       y.bound_centre.y(),
                       y.bound_centre.z(),
                       y.bound_radius2,
                       y.crease.along,
                       y.crease.radius,
                       y.fill_lo[0],
                       y.fill_lo[1],
                       y.fill_hi[0],
                       y.fill_hi[1],
                       y.dr,
                       y.lipschitz};
  if (x.a != y.a || x.b != y.b || x.disjoint != y.disjoint)
    return ::testing::AssertionFailure() << "atoms or disjointness differ";
  for (std::size_t k = 0; k < std::size(xs); ++k)
    if (std::memcmp(&xs[k], &ys[k], sizeof(double)) != 0)
      return ::testing::AssertionFailure() << "field " << k << ": " << xs[k] << " vs " << ys[k];
  return ::testing::AssertionSuccess();
}

}  // namespace mg_test
