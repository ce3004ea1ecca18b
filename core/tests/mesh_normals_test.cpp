// Face and vertex normals of polygon soups (mesh_normals.h), on shapes solvable by hand.
#include "core/mesh_normals.h"
#include "core/errors.h"
#include "core/shapes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

TEST(MeshNormals, FaceNormalsOfABoxPointOutward) {
  const mg::PolygonSoup box = mg::make_box(Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 2, 3));
  const Eigen::Vector3d centre(0.5, 1, 1.5);
  for (int f = 0; f < 6; ++f) {
    const Eigen::Vector3d n = mg::face_normal(box, f);
    EXPECT_NEAR(n.norm(), 1.0, 1e-15);
    EXPECT_NEAR(n.cwiseAbs().maxCoeff(), 1.0, 1e-15);  // axis-aligned
    EXPECT_GT(n.dot(box.points[box.faces[f][0]] - centre), 0) << f;
    EXPECT_NEAR(0.5 * mg::newell_vector(box, f).norm(),
                std::abs(n.x()) * 6 + std::abs(n.y()) * 3 + std::abs(n.z()) * 2, 1e-12);  // area
  }
}

TEST(MeshNormals, DegenerateFacesHaveNoNormalAndNoWeight) {
  mg::PolygonSoup soup;
  soup.points = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 1, 0}};
  soup.faces = {{0, 1, 2}, {0, 1, 3}};
  EXPECT_TRUE(mg::face_normal(soup, 0).isZero(0));
  EXPECT_EQ(mg::corner_weight(soup, 0, 1, mg::face_normal(soup, 0), mg::NormalWeighting::angle),
            0.0);
  EXPECT_NEAR(mg::corner_weight(soup, 1, 0, mg::face_normal(soup, 1), mg::NormalWeighting::angle),
              M_PI / 2, 1e-15);
  EXPECT_NEAR(mg::corner_weight(soup, 1, 0, mg::face_normal(soup, 1), mg::NormalWeighting::area),
              0.5, 1e-15);
  const auto n = mg::vertex_normals(soup);
  EXPECT_TRUE(n[2].isZero(0));  // only on the degenerate face
  EXPECT_NEAR((n[3] - Eigen::Vector3d::UnitZ()).norm(), 0.0, 1e-15);
}

TEST(MeshNormals, AngleWeightedNormalsOfABoxCornerAreItsDiagonal) {
  // Every corner of a box sees three right angles, whatever the box's proportions; by area the
  // normal leans toward the largest faces.
  const mg::PolygonSoup box = mg::make_box(Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 2, 4));
  const auto by_angle = mg::vertex_normals(box, mg::NormalWeighting::angle);
  const auto by_area = mg::vertex_normals(box, mg::NormalWeighting::area);
  const Eigen::Vector3d outward = (box.points[7] - Eigen::Vector3d(0.5, 1, 2)).cwiseSign();
  EXPECT_NEAR((by_angle[7] - outward.normalized()).norm(), 0.0, 1e-15);
  const Eigen::Vector3d areas(8, 4, 2);  // faces normal to x, y, z: 2 x 4, 1 x 4, 1 x 2
  EXPECT_NEAR((by_area[7] - areas.cwiseProduct(outward).normalized()).norm(), 0.0, 1e-15);
}

TEST(MeshNormals, SphereVertexNormalsFollowTheRadius) {
  const mg::PolygonSoup sphere = mg::make_geodesic_sphere(8, 2.0);
  const auto n = mg::vertex_normals(sphere);
  for (std::size_t v = 0; v < sphere.points.size(); ++v)
    EXPECT_LT(std::acos(std::min(1.0, n[v].dot(sphere.points[v].normalized()))), 0.01) << v;
}

TEST(MeshNormals, OppositeFacesCancel) {
  mg::PolygonSoup soup;
  soup.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  soup.faces = {{0, 1, 2}, {0, 2, 1}};
  for (const auto& n : mg::vertex_normals(soup)) EXPECT_TRUE(n.isZero(0));
}

TEST(MeshNormals, InvalidSoupsAreRefused) {
  mg::PolygonSoup soup;
  soup.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  soup.faces = {{0, 1, 3}};
  EXPECT_THROW(mg::vertex_normals(soup), mg::InvalidInput);
  soup.faces = {{0, 1}};
  EXPECT_THROW(mg::vertex_normals(soup), mg::InvalidInput);
}

}  // namespace
