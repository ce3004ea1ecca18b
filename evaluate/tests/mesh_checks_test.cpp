// Mesh checks (mesh_checks.h): topology, intersections and degenerate triangles apart.
#include "evaluate/mesh_checks.h"
#include "core/shapes.h"

#include <gtest/gtest.h>

#include <map>
#include <set>

namespace ev = mg::evaluate;

namespace {

/// The boundary of a set of unit voxels (x, y, z), as quads CCW from outside.
mg::PolygonSoup voxel_surface(const std::set<std::array<int, 3>>& voxels) {
  mg::PolygonSoup soup;
  std::map<std::array<int, 3>, int> index;
  auto vertex = [&](int x, int y, int z) {
    const auto [it, added] = index.emplace(std::array<int, 3>{x, y, z}, 0);
    if (added) {
      it->second = static_cast<int>(soup.points.size());
      soup.points.emplace_back(x, y, z);
    }
    return it->second;
  };
  for (const auto& v : voxels)
    for (int axis = 0; axis < 3; ++axis)
      for (int side = 0; side < 2; ++side) {
        std::array<int, 3> n = v;
        n[axis] += side ? 1 : -1;
        if (voxels.count(n)) continue;
        const int u = (axis + 1) % 3, w = (axis + 2) % 3;
        std::array<int, 3> c = v;
        c[axis] += side;
        std::vector<int> face;
        for (auto [du, dw] : {std::pair{0, 0}, {1, 0}, {1, 1}, {0, 1}}) {
          std::array<int, 3> p = c;
          p[u] += du;
          p[w] += dw;
          face.push_back(vertex(p[0], p[1], p[2]));
        }
        if (!side) std::reverse(face.begin(), face.end());
        soup.faces.push_back(face);
      }
  return soup;
}

mg::PolygonSoup tetrahedron(const Eigen::Vector3d& o, double s) {
  mg::PolygonSoup t;
  t.points = {o, o + Eigen::Vector3d(s, 0, 0), o + Eigen::Vector3d(0, s, 0),
              o + Eigen::Vector3d(0, 0, s)};
  t.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  return t;
}

void append(mg::PolygonSoup& a, const mg::PolygonSoup& b, int shared_first = -1) {
  // shared_first >= 0: b's vertex 0 is a's vertex shared_first.
  std::vector<int> map(b.points.size());
  for (std::size_t i = 0; i < b.points.size(); ++i) {
    if (i == 0 && shared_first >= 0) {
      map[i] = shared_first;
      continue;
    }
    map[i] = static_cast<int>(a.points.size());
    a.points.push_back(b.points[i]);
  }
  for (const auto& f : b.faces) {
    std::vector<int> g;
    for (int v : f) g.push_back(map[v]);
    a.faces.push_back(g);
  }
}

}  // namespace

TEST(MeshChecks, AClosedGenusTwoBlockReportsGenusTwo) {
  std::set<std::array<int, 3>> voxels;
  for (int x = 0; x < 3; ++x)
    for (int y = 0; y < 5; ++y)
      if (!(x == 1 && (y == 1 || y == 3))) voxels.insert({x, y, 0});
  const ev::MeshCheck c = ev::check_mesh(voxel_surface(voxels));
  EXPECT_TRUE(c.topology.closed);
  EXPECT_TRUE(c.topology.manifold);
  EXPECT_TRUE(c.topology.oriented);
  EXPECT_EQ(c.topology.components, 1u);
  EXPECT_EQ(c.topology.genus, 2);
  EXPECT_EQ(c.topology.euler, -2);
  EXPECT_EQ(c.intersecting_pairs, 0u);
  EXPECT_EQ(c.degenerate_triangles, 0u);
  EXPECT_EQ(c.non_triangle_faces, c.topology.faces);
  EXPECT_NEAR(c.min_angle_deg, 45.0, 1e-9);  // quads fanned into right isosceles triangles
}

TEST(MeshChecks, ACubeWithOneFaceRemovedIsOpen) {
  mg::PolygonSoup box = mg::make_box(Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones());
  const ev::MeshCheck whole = ev::check_mesh(box);
  EXPECT_TRUE(whole.topology.closed);
  EXPECT_EQ(whole.topology.genus, 0);
  EXPECT_EQ(whole.valence_histogram, (std::map<std::size_t, std::size_t>{{3, 8}}));
  box.faces.pop_back();
  const ev::MeshCheck open = ev::check_mesh(box);
  EXPECT_FALSE(open.topology.closed);
  EXPECT_EQ(open.topology.boundary_edges, 4u);
  EXPECT_EQ(open.topology.genus, -1);
  EXPECT_EQ(open.intersecting_pairs, 0u);
}

TEST(MeshChecks, TwoTetrahedraSharingOneVertexMakeANonManifoldVertex) {
  mg::PolygonSoup soup = tetrahedron(Eigen::Vector3d::Zero(), 1);
  append(soup, tetrahedron(Eigen::Vector3d::Zero(), -1), /*shared_first=*/0);
  // The second tetrahedron, mirrored, is inside out: turn its faces back.
  for (std::size_t f = 4; f < 8; ++f) std::reverse(soup.faces[f].begin(), soup.faces[f].end());
  const ev::MeshCheck c = ev::check_mesh(soup);
  EXPECT_TRUE(c.topology.closed);
  EXPECT_EQ(c.topology.nonmanifold_vertices, 1u);
  EXPECT_EQ(c.topology.nonmanifold_edges, 0u);
  EXPECT_FALSE(c.topology.manifold);
  EXPECT_EQ(c.intersecting_pairs, 0u);  // they only touch at the shared vertex
  EXPECT_EQ(c.degenerate_triangles, 0u);
}

TEST(MeshChecks, InterpenetratingTetrahedraIntersectWithoutDegenerateTriangles) {
  mg::PolygonSoup soup = tetrahedron(Eigen::Vector3d::Zero(), 1);
  append(soup, tetrahedron(Eigen::Vector3d(0.2, 0.2, 0.2), 1));
  const ev::MeshCheck c = ev::check_mesh(soup);
  EXPECT_TRUE(c.topology.closed);
  EXPECT_TRUE(c.topology.manifold);  // combinatorially fine: only geometry catches it
  EXPECT_GT(c.intersecting_pairs, 0u);
  EXPECT_EQ(c.degenerate_triangles, 0u);
  EXPECT_FALSE(c.first_intersection.empty());
}

TEST(MeshChecks, AFoldOntoANeighbourSharingAnEdgeIsAnIntersection) {
  // Two coplanar triangles on the same side of their shared edge overlap.
  mg::PolygonSoup soup;
  soup.points = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0.5, 0.5, 0}};
  soup.faces = {{0, 1, 2}, {1, 0, 3}};
  EXPECT_EQ(ev::check_mesh(soup).intersecting_pairs, 1u);
  soup.points[3] = {0.5, -0.5, 0};  // the other side: a flat, valid pair
  EXPECT_EQ(ev::check_mesh(soup).intersecting_pairs, 0u);
  soup.points[3] = {0.5, 0.5, 0.1};  // not coplanar: a valid pair
  EXPECT_EQ(ev::check_mesh(soup).intersecting_pairs, 0u);
}

TEST(MeshChecks, ADegenerateTriangleIsCountedApartFromIntersections) {
  // A square of two triangles and a sliver whose corners are collinear along one side.
  mg::PolygonSoup soup;
  soup.points = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}};
  soup.faces = {{0, 1, 2}, {0, 2, 3}, {1, 0, 4}};
  const ev::MeshCheck c = ev::check_mesh(soup);
  EXPECT_EQ(c.degenerate_triangles, 1u);
  EXPECT_EQ(c.intersecting_pairs, 0u);
  EXPECT_EQ(c.first_degenerate, "face 2 is degenerate (collinear corners)");
  EXPECT_NEAR(c.min_angle_deg, 45.0, 1e-9);  // over the non-degenerate triangles
}

TEST(MeshChecks, DuplicatedFacesIntersect) {
  mg::PolygonSoup soup = tetrahedron(Eigen::Vector3d::Zero(), 1);
  soup.faces.push_back(soup.faces[0]);
  const ev::MeshCheck c = ev::check_mesh(soup);
  EXPECT_EQ(c.intersecting_pairs, 1u);
  EXPECT_GT(c.topology.nonmanifold_edges, 0u);
}
