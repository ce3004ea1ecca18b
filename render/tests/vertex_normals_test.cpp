#include "render/vertex_normals.h"

#include "core/errors.h"
#include "core/shapes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using mg::render::NormalOptions;
using mg::render::NormalWeighting;
using mg::render::shading_normals;

/// The box [0,2]x[0,1]x[0,1] as 12 triangles (each quad of make_box split along a diagonal).
mg::PolygonSoup triangulated_box() {
  mg::PolygonSoup quads = mg::make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 1, 1));
  mg::PolygonSoup soup{quads.points, {}};
  for (const auto& q : quads.faces) {
    soup.faces.push_back({q[0], q[1], q[2]});
    soup.faces.push_back({q[0], q[2], q[3]});
  }
  return soup;
}

/// Outward unit normal of a corner of the box (all corners have 3 faces at right angles).
Eigen::Vector3d corner_diagonal(const Eigen::Vector3d& p) {
  return Eigen::Vector3d(p.x() > 1 ? 1 : -1, p.y() > 0.5 ? 1 : -1, p.z() > 0.5 ? 1 : -1) /
         std::sqrt(3.0);
}

TEST(ShadingNormals, SphereVertexNormalsAreRadial) {
  const mg::PolygonSoup sphere = mg::make_geodesic_sphere(/*frequency=*/8, /*radius=*/2.0);
  for (auto weighting : {NormalWeighting::angle, NormalWeighting::area}) {
    NormalOptions opt;
    opt.weighting = weighting;
    const auto n = shading_normals(sphere, opt);
    EXPECT_TRUE(n.per_vertex);
    ASSERT_EQ(n.normals.size(), sphere.points.size());
    for (std::size_t v = 0; v < sphere.points.size(); ++v) {
      EXPECT_NEAR(n.normals[v].norm(), 1.0, 1e-12);
      // Flat facets of a geodesic sphere: the averaged normal is within 1 degree of radial.
      EXPECT_GT(n.normals[v].dot(sphere.points[v].normalized()), std::cos(M_PI / 180));
    }
  }
}

TEST(ShadingNormals, AngleWeightingIgnoresTriangulation) {
  // Every corner of a box sees three right angles: the angle-weighted normal is the diagonal,
  // for quads and for any triangulation of them.
  for (const mg::PolygonSoup& soup :
       {mg::make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 1, 1)), triangulated_box()}) {
    const auto n = shading_normals(soup);
    for (std::size_t v = 0; v < soup.points.size(); ++v)
      EXPECT_LT((n.normals[v] - corner_diagonal(soup.points[v])).norm(), 1e-12) << "vertex " << v;
  }
}

TEST(ShadingNormals, AreaWeightingFollowsFaceAreas) {
  // Box 2 x 1 x 1: the face with normal +-x has area 1, those with +-y and +-z area 2, so the
  // area-weighted corner normal is (1, 2, 2) / 3 up to signs.
  const mg::PolygonSoup soup = mg::make_box(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(2, 1, 1));
  NormalOptions opt;
  opt.weighting = NormalWeighting::area;
  const auto n = shading_normals(soup, opt);
  for (std::size_t v = 0; v < soup.points.size(); ++v) {
    const Eigen::Vector3d s = corner_diagonal(soup.points[v]) * std::sqrt(3.0);
    const Eigen::Vector3d expected = Eigen::Vector3d(s.x(), 2 * s.y(), 2 * s.z()) / 3.0;
    EXPECT_LT((n.normals[v] - expected).norm(), 1e-12) << "vertex " << v;
  }
}

TEST(ShadingNormals, CreaseAngleKeepsBoxEdgesSharp) {
  const mg::PolygonSoup soup = triangulated_box();
  NormalOptions opt;
  opt.crease_angle = 60;
  const auto n = shading_normals(soup, opt);
  EXPECT_FALSE(n.per_vertex);
  ASSERT_EQ(n.corners.size(), soup.faces.size());
  for (std::size_t f = 0; f < soup.faces.size(); ++f) {
    const Eigen::Vector3d face = mg::face_normal(soup, static_cast<int>(f));
    for (int c : n.corners[f]) EXPECT_LT((n.normals[c] - face).norm(), 1e-12) << "face " << f;
  }
  // 8 vertex normals + one normal per (corner, face direction): 8 corners x 3 directions.
  EXPECT_EQ(n.normals.size(), 8u + 24u);

  opt.crease_angle = 180;
  EXPECT_TRUE(shading_normals(soup, opt).per_vertex);
}

TEST(ShadingNormals, NonManifoldAndDegenerateSoupsGetUnitNormals) {
  // Three triangles on one edge (non-manifold), a triangle with its twin reversed (their
  // normals cancel), a collinear triangle and an unused vertex.
  mg::PolygonSoup soup;
  soup.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1},
                 {5, 0, 0}, {6, 0, 0}, {5, 1, 0}, {7, 0, 0},  {9, 9, 9}};
  soup.faces = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}, {5, 6, 7}, {5, 7, 6}, {5, 6, 8}};
  const auto n = shading_normals(soup);
  for (const auto& v : n.normals) EXPECT_NEAR(v.norm(), 1.0, 1e-12);
  EXPECT_FALSE(n.per_vertex);  // the cancelled vertices fall back to face normals
  EXPECT_LT((n.normals[n.corners[3][0]] - Eigen::Vector3d(0, 0, 1)).norm(), 1e-12);
  EXPECT_LT((n.normals[n.corners[4][0]] - Eigen::Vector3d(0, 0, -1)).norm(), 1e-12);
  EXPECT_EQ(mg::face_normal(soup, 5), Eigen::Vector3d::Zero());
}

TEST(ShadingNormals, Preconditions) {
  const mg::PolygonSoup soup = triangulated_box();
  NormalOptions opt;
  opt.crease_angle = 181;
  EXPECT_THROW(shading_normals(soup, opt), mg::InvalidInput);
  opt.crease_angle = std::nan("");
  EXPECT_THROW(shading_normals(soup, opt), mg::InvalidInput);
  mg::PolygonSoup bad = soup;
  bad.faces[3][1] = 8;
  EXPECT_THROW(shading_normals(bad), mg::InvalidInput);
  bad.faces[3] = {0, 1};
  EXPECT_THROW(shading_normals(bad), mg::InvalidInput);
}

}  // namespace
