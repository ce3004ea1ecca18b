#include "evaluate/atoms_distance.h"
#include "core/shapes.h"
#include "garbing/garb.h"

#include <gtest/gtest.h>

namespace {

namespace ev = mg::evaluate;
using Eigen::Vector3d;

TEST(AtomsDistance, SphereMeshAgainstItsAtomIsTheChordalError) {
  const mg::PolygonSoup sphere = mg::make_geodesic_sphere(10, 1.0);
  // Chordal error: the deepest point of a triangle below the sphere, over the triangles.
  double chord = 0;
  for (const auto& f : sphere.faces) {
    const Vector3d a = sphere.points[f[0]], b = sphere.points[f[1]], c = sphere.points[f[2]];
    const Vector3d n = (b - a).cross(c - a).normalized();
    chord = std::max(chord, 1.0 - std::abs(n.dot(a)));  // the plane's distance from the centre
  }
  mg::MedialSurface atom;
  atom.atoms = {{Vector3d::Zero(), 1.0}};
  ev::AtomsDistanceOptions opt;
  opt.samples = 200000;
  const auto r = ev::atoms_distance(sphere, atom, opt, "sphere");
  // Mesh -> G: the sample nearest the plane's foot approaches the chord; G -> mesh too.
  EXPECT_NEAR(r.distance.hausdorff, chord, 0.05 * chord);
  EXPECT_LE(r.distance.hausdorff, chord * (1 + 1e-9));
  EXPECT_GT(r.g_unbiased, 100000u);  // one ball: every sample of its sphere is on G
}

TEST(AtomsDistance, FineGarbingOfTwoBallsIsNearZero) {
  mg::MedialSurface s;
  s.atoms = {{Vector3d(0, 0, 0), 1.0}, {Vector3d(1.2, 0.3, -0.2), 0.7}};
  mg::garbing::GarbOptions gopt;
  gopt.octree.min_depth = 6;
  gopt.cones.min_circle_ratio = 0;  // keep the cone of these two balls
  gopt.cones.max_collar = 0;
  const auto m2 = mg::garbing::garb(s, gopt).m2;
  ev::AtomsDistanceOptions aopt;
  aopt.cones = gopt.cones;
  const auto r = ev::atoms_distance(mg::soup_from_mesh(m2.mesh), s, aopt, "m2");
  EXPECT_LT(r.distance.hausdorff, 2e-3 * r.diagonal);  // chordal error of a leaf-size mesh
  EXPECT_LT(r.distance.rms, 2e-4 * r.diagonal);
  EXPECT_EQ(r.cones, 1u);
}

}  // namespace
