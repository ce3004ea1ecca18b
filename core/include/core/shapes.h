#pragma once
/// \file shapes.h
/// Generated reference shapes: closed, consistently oriented triangle meshes (CCW from outside),
/// and analytic medial meshes (atoms, edges and faces, as a `.ma` file holds them).

#include "core/medial_surface.h"
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

/// Capsule along the z axis: a cylinder of `radius` from z = -half_length to half_length closed
/// by two hemispherical caps (a surface of revolution, vertices exactly on it). `ring` samples
/// around the axis, `rows` rings per quarter circle of a cap, the cylinder's rings spaced as the
/// caps' (at least one band). Triangles; the poles are fans.
/// @pre ring >= 3, rows >= 1, half_length > 0, radius > 0   @throws InvalidInput
PolygonSoup make_capsule(int ring, int rows, double half_length, double radius);

/// Axis-aligned box [lo, hi] as 6 quads.   @pre lo < hi componentwise
PolygonSoup make_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi);

/// \name Medial meshes
/// Sparse analytic medial meshes, as Q-MAT and its successors write them: a simplicial complex
/// of atoms, edges and faces in which every side of a face is also listed as an edge and no
/// edge or face is listed twice (so V - E + F is the complex's Euler characteristic). Their
/// shape is the envelope: the union of the balls, of one cone per edge (the hull of its two
/// balls) and of one slab per face (the hull of its three balls). Every radius is > 0, every
/// edge joins two distinct atoms and every face three (validate() passes); the output depends
/// on the arguments only (no randomness). Model units: each fits in [-1.5, 1.5]^3. With the
/// default arguments no two balls are nearly tangent (|d_ij - r_i - r_j| >= 0.015 for every
/// pair), so that the envelope's topology does not hang on rounding.
/// Expected topology is that of the garbed envelope (a closed surface): components, genus.
/// @{

/// Capsule: two disjoint balls of unequal radii (0.4 and 0.2, centres about 1 apart) joined
/// by an edge. V 2, E 1, F 0. Envelope: 1 component, genus 0.
MedialSurface make_medial_capsule();

/// Slab: one face over three pairwise disjoint balls of radii 0.18, 0.12 and 0.08 (centres
/// 1 to 1.1 apart, not in a coordinate plane), its three sides as edges. The slab has two
/// tangent triangles. V 3, E 3, F 1. Envelope: 1 component, genus 0.
MedialSurface make_medial_slab();

/// Ring: `atoms` atoms on a wavy circle of radius 1 about the z axis (angle t_k = 2 pi k /
/// atoms, height 0.1 sin 3 t_k), radius 0.16 + 0.06 cos 2 t_k (0.10 to 0.22), each joined to
/// the next by an edge, no faces. With the default 16 atoms (neighbours 0.39 apart) the
/// neighbouring balls overlap near t = 0 and pi and are disjoint near t = pi / 2 and 3 pi / 2.
/// Every ball and cone keeps over 0.25 from the z axis (over 0.7 from 8 atoms on): the hole is
/// open for any count.
/// V atoms, E atoms, F 0. Envelope: 1 component, genus 1.
/// @pre atoms >= 3   @throws InvalidInput
MedialSurface make_medial_ring(int atoms = 16);

/// Disc: a hexagon of the triangular lattice with `rings` rings of atoms around a centre atom,
/// spacing 1 / rings (corners at distance 1 from the z axis), every lattice triangle a face
/// (CCW seen from +z). Centres on the bowl z = 0.25 rho^2 (rho: distance to the z axis), so
/// neighbouring slabs are not coplanar; radius 0.2 - 0.13 rho, largest at the centre (0.2),
/// shrinking to 0.07 at the corners. With the default 3 rings, neighbouring balls overlap near
/// the centre and are disjoint at the rim. V = 3 R^2 + 3 R + 1, E = 9 R^2 + 3 R, F = 6 R^2
/// (R = rings; R = 3: 37, 90, 54). Envelope: 1 component, genus 0.
/// @pre 1 <= rings <= 100   @throws InvalidInput
MedialSurface make_medial_disc(int rings = 3);

/// Sheets: three quads, each split into two faces, meeting along the one common edge between
/// the spine atoms (0, 0, -0.5) and (0, 0, 0.5) (radii 0.18 and 0.15): a non-manifold medial
/// mesh. Each sheet reaches 0.8 from the z axis, the sheets 120 degrees apart, outer radii 0.1
/// to 0.14. V 8, E 13, F 6. Envelope: 1 component, genus 0.
MedialSurface make_medial_sheets();

/// Hand: a sparse hand in the z = 0 plane, fingers along +y. The palm is a 4 x 4 grid of atoms
/// 0.2 apart (x in [-0.3, 0.3], y in [-0.45, 0.15]), slightly cupped, each grid square split
/// into two faces; radii 0.17 inside, 0.16 on the sides, 0.08 along the top row (the
/// knuckles). Four fingers of 4, 4, 4 and 3 atoms leave the knuckles fanned out (radii 0.072
/// down to 0.045, curling slightly toward +z), and a thumb of 3 atoms leaves the left side
/// (radii 0.085 down to 0.06), rising out of the palm's plane. Each finger is a chain of edges
/// joined to its palm atom by an edge. No two fingers touch: the cones of two different
/// fingers (their edges to the palm included) are at least 0.04 apart, and past its first atom
/// no finger comes within 0.04 of a cone of the palm. V 34, E 51, F 18. Envelope: 1 component,
/// genus 0.
MedialSurface make_medial_hand();

/// @}

}  // namespace mg
