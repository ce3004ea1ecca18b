#pragma once
/// \file shapes.h
/// Generated reference shapes: closed, consistently oriented triangle meshes (CCW from outside).

#include "core/mesh.h"

namespace mg {

/// Icosahedral geodesic sphere centred at the origin: every vertex exactly at `radius`
/// (up to rounding). V = 10 f^2 + 2, F = 20 f^2.
/// @pre frequency >= 1, radius > 0   @throws InvalidInput
PolygonSoup make_geodesic_sphere(int frequency, double radius = 1.0);

/// Torus of revolution about z: `ring` samples around the z axis, `tube` around the tube,
/// vertices exactly on the torus, each grid quad split into two triangles.
/// V = ring * tube, F = 2 * ring * tube.
/// @pre ring >= 3, tube >= 3, 0 < minor < major   @throws InvalidInput
PolygonSoup make_torus(int ring, int tube, double major, double minor);

/// Bumpy torus: the tube radius is modulated,
/// r(u, v) = minor * (1 + amplitude * sin(bumps_ring * u) * sin(bumps_tube * v)),
/// with u the angle around the z axis and v the angle around the tube. Same grid as make_torus.
/// @pre as make_torus; 0 <= amplitude < 1; major > minor * (1 + amplitude)   @throws InvalidInput
PolygonSoup make_bumpy_torus(int ring, int tube, double major, double minor, double amplitude,
                             int bumps_ring, int bumps_tube);

/// Axis-aligned box [lo, hi] as 6 quads.   @pre lo < hi componentwise
PolygonSoup make_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);

}  // namespace mg
