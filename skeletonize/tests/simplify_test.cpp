// The simplification of medial meshes: the spherical quadric against hand-computed values, and
// simplify_medial_mesh() on analytic shapes (sphere, capsule, torus) and bad input.
#include "skeletonize/simplify.h"
#include "core/errors.h"
#include "core/shapes.h"
#include "skeletonize/poles.h"
#include "skeletonize/sphere_quadric.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>

namespace {

using Eigen::Vector3d;
namespace sk = mg::skeletonize;

TEST(SphereQuadric, ZeroForATangentSphereAndTheSquaredGapOtherwise) {
  sk::SphereQuadric q;
  q.add_plane(Vector3d::UnitX(), Vector3d(2, 5, -1), 3.0);  // the plane x = 2, outward +x
  // A sphere touching x = 2 from inside: centre x + r = 2.
  EXPECT_NEAR(q.error({Vector3d(1.5, 0, 0), 0.5}), 0, 1e-15);
  // Gap n.(p - c) - r = 2 - 1 - 0.5 = 0.5: weight 3 times 0.25.
  EXPECT_NEAR(q.error({Vector3d(1, 7, 3), 0.5}), 0.75, 1e-14);
  // Sticking out by 0.25: the same square.
  EXPECT_NEAR(q.error({Vector3d(1.5, 0, 0), 0.75}), 3 * 0.0625, 1e-14);
}

TEST(SphereQuadric, MinimiserOfACubesFacesIsItsInscribedBall) {
  sk::SphereQuadric q;
  for (int axis = 0; axis < 3; ++axis)
    for (double sign : {-1.0, 1.0}) {
      Vector3d n = Vector3d::Zero();
      n[axis] = sign;
      // The box [0, 2] x [0, 4] x [0, 6] would not do: its faces' planes have no common
      // tangent sphere. A cube [1, 3]^3 has: centre (2, 2, 2), radius 1.
      q.add_plane(n, Vector3d(2, 2, 2) + n, 1.0);
    }
  const sk::MergedAtom m =
      sk::place_merged_atom(q, {Vector3d(0, 0, 0), 0.1}, {Vector3d(3, 3, 3), 0.2});
  EXPECT_EQ(m.placement, sk::Placement::minimiser);
  EXPECT_NEAR((m.atom.centre - Vector3d(2, 2, 2)).norm(), 0, 1e-12);
  EXPECT_NEAR(m.atom.radius, 1, 1e-12);
  EXPECT_NEAR(m.error, 0, 1e-12);
}

TEST(SphereQuadric, SlabPlanesLeaveTheInPlanePositionFree) {
  // Two parallel planes z = +-1: every sphere of radius 1 centred on z = 0 fits. The placement
  // is the fitting sphere nearest to the two spheres' midpoint.
  sk::SphereQuadric q;
  q.add_plane(Vector3d::UnitZ(), Vector3d(0, 0, 1), 1.0);
  q.add_plane(-Vector3d::UnitZ(), Vector3d(0, 0, -1), 1.0);
  const sk::MergedAtom m =
      sk::place_merged_atom(q, {Vector3d(0, 0, 0.2), 0.8}, {Vector3d(4, 2, -0.2), 0.9});
  EXPECT_EQ(m.placement, sk::Placement::nearest_minimiser);
  EXPECT_NEAR((m.atom.centre - Vector3d(2, 1, 0)).norm(), 0, 1e-9);
  EXPECT_NEAR(m.atom.radius, 1, 1e-9);
}

TEST(SphereQuadric, NonPositiveRadiusFallsBackToAnInputSphere) {
  // Planes facing inward (normals toward the centre) put the minimiser's radius below zero.
  sk::SphereQuadric q;
  for (int axis = 0; axis < 3; ++axis)
    for (double sign : {-1.0, 1.0}) {
      Vector3d n = Vector3d::Zero();
      n[axis] = sign;
      q.add_plane(-n, n, 1.0);
    }
  const mg::MedialAtom p{Vector3d(0, 0, 0), 0.5}, r{Vector3d(1, 0, 0), 0.25};
  const sk::MergedAtom m = sk::place_merged_atom(q, p, r);
  EXPECT_EQ(m.placement, sk::Placement::fallback);
  EXPECT_GT(m.atom.radius, 0);
}

TEST(SphereQuadric, StabilityRatio) {
  EXPECT_DOUBLE_EQ(sk::stability_ratio({Vector3d(0, 0, 0), 1}, {Vector3d(2, 0, 0), 1}), 1);
  EXPECT_DOUBLE_EQ(sk::stability_ratio({Vector3d(0, 0, 0), 1}, {Vector3d(2, 0, 0), 0.5}), 0.75);
  EXPECT_DOUBLE_EQ(sk::stability_ratio({Vector3d(0, 0, 0), 1}, {Vector3d(0.5, 0, 0), 0.2}), 0);
  EXPECT_DOUBLE_EQ(sk::stability_ratio({Vector3d(1, 1, 1), 1}, {Vector3d(1, 1, 1), 1}), 0);
}

/// The poles of `mesh` with their connectivity, simplified to `target` atoms.
sk::SimplifiedMedialMesh simplify(const mg::PolygonSoup& mesh, std::size_t target,
                                  sk::SkeletonOptions sopt = {}, sk::SimplifyOptions opt = {}) {
  sopt.connectivity = true;
  const sk::Skeleton s = sk::skeletonize(mesh, sopt, "test mesh");
  opt.target_atoms = target;
  return sk::simplify_medial_mesh(mesh, s.atoms, s.cells, opt, s.samples, s.atom_of_sample);
}

/// The output is a simplicial complex as Q-MAT writes it: edges i < j, faces i < j < k, sorted,
/// none repeated, every side of a face an edge, radii > 0.
void expect_valid_complex(const sk::SimplifiedMedialMesh& r) {
  const mg::MedialSurface& s = r.surface;
  for (const auto& a : s.atoms) EXPECT_GT(a.radius, 0);
  const int n = static_cast<int>(s.atoms.size());
  std::set<std::array<int, 2>> edges;
  for (const auto& e : s.edges) {
    EXPECT_LT(e[0], e[1]);
    EXPECT_GE(e[0], 0);
    EXPECT_LT(e[1], n);
    EXPECT_TRUE(edges.insert(e).second) << "edge listed twice";
  }
  EXPECT_TRUE(std::is_sorted(s.edges.begin(), s.edges.end()));
  EXPECT_TRUE(std::is_sorted(s.faces.begin(), s.faces.end()));
  EXPECT_EQ(std::adjacent_find(s.faces.begin(), s.faces.end()), s.faces.end());
  for (const auto& f : s.faces) {
    EXPECT_LT(f[0], f[1]);
    EXPECT_LT(f[1], f[2]);
    EXPECT_TRUE(edges.count({f[0], f[1]}) && edges.count({f[0], f[2]}) && edges.count({f[1], f[2]}))
        << "a side of a face is not an edge";
  }
}

TEST(Simplify, SphereBecomesOneAtomAtItsCentre) {
  // The reference sphere (f = 18, 3,242 vertices); without merging it has many poles near its
  // centre. Its faces lie 0.9991 to 0.9995 from the centre: the ball tangent to their planes
  // is 1e-3 inside the unit sphere.
  sk::SkeletonOptions sopt;
  sopt.merge_tol = 0;
  const sk::SimplifiedMedialMesh r = simplify(mg::make_geodesic_sphere(18, 1.0), 1, sopt);
  EXPECT_GT(r.stats.atoms_before, 1u);
  ASSERT_EQ(r.surface.atoms.size(), 1u);
  EXPECT_TRUE(r.stats.target_reached);
  EXPECT_LT(r.surface.atoms[0].centre.norm(), 1e-3);
  EXPECT_NEAR(r.surface.atoms[0].radius, 1.0, 1e-3);
}

TEST(Simplify, CapsuleBecomesAChainAlongItsAxis) {
  // Cylinder of radius 0.5 from z = -1 to 1 with hemispherical caps: its medial axis is the
  // segment, a chain of balls of radius 0.5.
  sk::SkeletonOptions sopt;
  sopt.clamp_radius = true;
  for (std::size_t target : {2u, 4u}) {
    const sk::SimplifiedMedialMesh r = simplify(mg::make_capsule(32, 8, 1.0, 0.5), target, sopt);
    expect_valid_complex(r);
    ASSERT_EQ(r.surface.atoms.size(), target);
    EXPECT_EQ(r.surface.edges.size(), target - 1);  // a chain
    EXPECT_TRUE(r.surface.faces.empty());
    for (const auto& a : r.surface.atoms) {
      EXPECT_LT(a.centre.head<2>().norm(), 0.01) << "off the axis";
      EXPECT_LT(std::abs(a.centre.z()), 1.0 + 0.01);
      EXPECT_NEAR(a.radius, 0.5, 0.01);
    }
  }
}

TEST(Simplify, TorusKeepsItsLoop) {
  // The 60 x 20 torus: its 60 poles form a ring; every target down to the smallest the
  // collapses reach keeps the loop (the complex's Euler characteristic 0, one component).
  const mg::PolygonSoup torus = mg::make_torus(60, 20, 1.0, 0.3);
  sk::SkeletonOptions sopt;
  sopt.clamp_radius = true;
  const sk::SimplifiedMedialMesh smallest = simplify(torus, 1, sopt);
  EXPECT_FALSE(smallest.stats.target_reached);
  EXPECT_GE(smallest.surface.atoms.size(), 3u);
  for (std::size_t target = smallest.surface.atoms.size(); target <= 60; target += 3) {
    const sk::SimplifiedMedialMesh r = simplify(torus, target, sopt);
    SCOPED_TRACE(target);
    expect_valid_complex(r);
    EXPECT_EQ(r.surface.atoms.size(), target);
    EXPECT_EQ(r.stats.complex_components_after, 1);
    const long euler =
        static_cast<long>(r.surface.atoms.size()) - static_cast<long>(r.surface.edges.size()) +
        static_cast<long>(r.surface.faces.size()) - static_cast<long>(r.cells.size());
    EXPECT_EQ(euler, 0);
    EXPECT_EQ(r.stats.complex_euler_after, 0);
  }
}

TEST(Simplify, RefusesATargetOfZeroOrAboveTheAtomCount) {
  const mg::PolygonSoup torus = mg::make_torus(60, 20, 1.0, 0.3);
  EXPECT_THROW(simplify(torus, 0), mg::InvalidInput);
  EXPECT_THROW(simplify(torus, 61), mg::InvalidInput);
  sk::SimplifyOptions opt;
  opt.stability_weight = -1;
  EXPECT_THROW(simplify(torus, 10, {}, opt), mg::InvalidInput);
}

TEST(Simplify, TheSkeletonsUnionComplexIsUnionComplexAndGivesTheSameOutput) {
  // skeletonize builds the union's dual complex from the regular triangulation of its
  // connectivity; simplify_medial_mesh takes it instead of triangulating again.
  const mg::PolygonSoup torus = mg::make_bumpy_torus(48, 24, 1.0, 0.35, 0.1, 12, 6);
  sk::SkeletonOptions sopt;
  sopt.connectivity = true;
  sopt.clamp_radius = true;
  const sk::Skeleton s = sk::skeletonize(torus, sopt, "torus");
  ASSERT_TRUE(s.union_complex.has_value());
  const sk::UnionComplex direct = sk::union_complex(s.atoms);
  EXPECT_EQ(s.union_complex->edges, direct.edges);
  EXPECT_EQ(s.union_complex->triangles, direct.triangles);
  EXPECT_EQ(s.union_complex->tetrahedra, direct.tetrahedra);
  EXPECT_EQ(s.union_complex->topology.euler, direct.topology.euler);
  EXPECT_EQ(s.union_complex->topology.components, direct.topology.components);
  EXPECT_FALSE(direct.triangles.empty());

  sk::SimplifyOptions opt;
  opt.target_atoms = 40;
  const auto own =
      sk::simplify_medial_mesh(torus, s.atoms, s.cells, opt, s.samples, s.atom_of_sample);
  const auto given = sk::simplify_medial_mesh(torus, s.atoms, s.cells, opt, s.samples,
                                              s.atom_of_sample, &*s.union_complex);
  EXPECT_EQ(own.surface.edges, given.surface.edges);
  EXPECT_EQ(own.surface.faces, given.surface.faces);
  ASSERT_EQ(own.surface.atoms.size(), given.surface.atoms.size());
  for (std::size_t i = 0; i < own.surface.atoms.size(); ++i) {
    EXPECT_EQ(own.surface.atoms[i].centre, given.surface.atoms[i].centre);
    EXPECT_EQ(own.surface.atoms[i].radius, given.surface.atoms[i].radius);
  }

  // A complex naming atoms these do not have is refused.
  sk::UnionComplex wrong = direct;
  wrong.edges.push_back({0, static_cast<int>(s.atoms.atoms.size())});
  EXPECT_THROW(
      sk::simplify_medial_mesh(torus, s.atoms, s.cells, opt, s.samples, s.atom_of_sample, &wrong),
      mg::InvalidInput);
  // Without connectivity there is none.
  EXPECT_FALSE(sk::skeletonize(torus, {}, "torus").union_complex.has_value());
}

}  // namespace
