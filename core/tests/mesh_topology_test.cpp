#include "core/mesh_topology.h"
#include "core/shapes.h"

#include <gtest/gtest.h>

namespace {

TEST(MeshTopology, ClosedSphereAndTorus) {
  const auto sphere = mg::mesh_topology(mg::make_geodesic_sphere(3));
  EXPECT_TRUE(sphere.closed && sphere.manifold && sphere.oriented);
  EXPECT_EQ(sphere.euler, 2);
  EXPECT_EQ(sphere.genus, 0);
  EXPECT_EQ(sphere.components, 1u);

  const auto torus = mg::mesh_topology(mg::make_torus(12, 8, 1, 0.3));
  EXPECT_TRUE(torus.closed && torus.oriented);
  EXPECT_EQ(torus.euler, 0);
  EXPECT_EQ(torus.genus, 1);
}

TEST(MeshTopology, GenusSumsOverComponents) {
  mg::PolygonSoup two = mg::make_torus(8, 6, 1, 0.3);
  const mg::PolygonSoup box = mg::make_box(Eigen::Vector3d(3, 3, 3), Eigen::Vector3d(4, 4, 4));
  const int offset = static_cast<int>(two.points.size());
  two.points.insert(two.points.end(), box.points.begin(), box.points.end());
  for (auto face : box.faces) {
    for (int& v : face) v += offset;
    two.faces.push_back(face);
  }
  const auto t = mg::mesh_topology(two);
  EXPECT_EQ(t.components, 2u);
  EXPECT_EQ(t.euler, 2);
  EXPECT_EQ(t.genus, 1);
}

TEST(MeshTopology, OpenBoxHasABoundaryAndNoGenus) {
  mg::PolygonSoup box = mg::make_box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones());
  box.faces.pop_back();
  const auto t = mg::mesh_topology(box);
  EXPECT_FALSE(t.closed);
  EXPECT_EQ(t.boundary_edges, 4u);
  EXPECT_EQ(t.genus, -1);
}

TEST(MeshTopology, TwoTetrahedraSharingAVertexAreNonManifold) {
  mg::PolygonSoup s;
  s.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
  s.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3},
             {0, 4, 5}, {0, 6, 4}, {0, 5, 6}, {4, 6, 5}};
  const auto t = mg::mesh_topology(s);
  EXPECT_TRUE(t.closed);
  EXPECT_FALSE(t.manifold);
  EXPECT_EQ(t.nonmanifold_vertices, 1u);
  EXPECT_EQ(t.first_problem, "vertex 0 is non-manifold (its faces form separate fans)");
}

}  // namespace
