#pragma once
// Generated atom sets for the garbing tests.

#include "core/medial_surface.h"
#include "garbing/octree.h"
#include "garbing/target_shape.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
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

/// A cone's fields, in one order (for same_cone).
inline std::array<double, 27> cone_fields(const mg::garbing::Cone& k) {
  return {k.c1.x(),
          k.c1.y(),
          k.c1.z(),
          k.u.x(),
          k.u.y(),
          k.u.z(),
          k.r1,
          k.length,
          k.r2,
          k.sin_phi,
          k.cos_phi,
          k.t_lo,
          k.t_hi,
          k.rho_lo,
          k.rho_hi,
          k.bound_centre.x(),
          k.bound_centre.y(),
          k.bound_centre.z(),
          k.bound_radius2,
          k.crease.along,
          k.crease.radius,
          k.fill_lo[0],
          k.fill_lo[1],
          k.fill_hi[0],
          k.fill_hi[1],
          k.dr,
          k.lipschitz};
}

/// Whether two cones are the same bit for bit, field by field.
inline ::testing::AssertionResult same_cone(const mg::garbing::Cone& x,
                                            const mg::garbing::Cone& y) {
  if (x.a != y.a || x.b != y.b || x.disjoint != y.disjoint)
    return ::testing::AssertionFailure() << "atoms or disjointness differ";
  const auto xs = cone_fields(x), ys = cone_fields(y);
  for (std::size_t k = 0; k < xs.size(); ++k)
    if (std::memcmp(&xs[k], &ys[k], sizeof(double)) != 0)
      return ::testing::AssertionFailure() << "field " << k << ": " << xs[k] << " vs " << ys[k];
  return ::testing::AssertionSuccess();
}

}  // namespace mg_test
