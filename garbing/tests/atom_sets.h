#pragma once
// Generated atom sets for the garbing tests.

#include "core/medial_surface.h"
#include "garbing/octree.h"
#include "garbing/target_shape.h"

#include <cmath>
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

}  // namespace mg_test
