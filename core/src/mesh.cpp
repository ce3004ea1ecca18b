#include "core/mesh.h"

#include "core/errors.h"
#include "core/mesh_topology.h"

namespace mg {

PolygonSoup soup_from_mesh(const Mesh& mesh) {
  PolygonSoup soup;
  soup.points.reserve(mesh.n_vertices());
  for (const auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    soup.points.emplace_back(p[0], p[1], p[2]);
  }
  soup.faces.reserve(mesh.n_faces());
  for (const auto f : mesh.faces()) {
    std::vector<int> face;
    for (const auto v : mesh.fv_range(f)) face.push_back(v.idx());
    soup.faces.push_back(std::move(face));
  }
  return soup;
}

void validate_soup(const PolygonSoup& soup, const std::string& name) {
  for (std::size_t i = 0; i < soup.points.size(); ++i)
    if (!soup.points[i].allFinite())
      throw InvalidInput(name + ": vertex " + std::to_string(i) + " has a non-finite coordinate");
  const int n = static_cast<int>(soup.points.size());
  for (std::size_t f = 0; f < soup.faces.size(); ++f) {
    const auto& face = soup.faces[f];
    if (face.size() < 3)
      throw InvalidInput(name + ": face " + std::to_string(f) + " has " +
                         std::to_string(face.size()) + " vertices (3 or more needed)");
    for (std::size_t i = 0; i < face.size(); ++i) {
      if (face[i] < 0 || face[i] >= n)
        throw InvalidInput(name + ": face " + std::to_string(f) + ": vertex index " +
                           std::to_string(face[i]) + " out of range [0, " + std::to_string(n) +
                           ")");
      for (std::size_t j = 0; j < i; ++j)
        if (face[j] == face[i])
          throw InvalidInput(name + ": face " + std::to_string(f) + " repeats vertex " +
                             std::to_string(face[i]));
    }
  }
}

Triangles fan_triangles(const PolygonSoup& soup) {
  Triangles t;
  for (std::size_t f = 0; f < soup.faces.size(); ++f) {
    const auto& face = soup.faces[f];
    for (std::size_t i = 1; i + 1 < face.size(); ++i) {
      t.corners.push_back({face[0], face[i], face[i + 1]});
      t.face.push_back(f);
      t.fan.push_back(static_cast<int>(i));
    }
  }
  return t;
}

Mesh mesh_from_soup(const PolygonSoup& soup, const std::string& name) {
  validate_soup(soup, name);
  const MeshTopology topo = mesh_topology(soup);
  if (!topo.oriented) throw InvalidInput(name + ": " + topo.first_problem);
  return mesh_from_manifold_soup(soup, name);
}

Mesh mesh_from_manifold_soup(const PolygonSoup& soup, const std::string& name) {
  Mesh mesh;
  std::size_t corners = 0;
  for (const auto& f : soup.faces) corners += f.size();
  mesh.reserve(soup.points.size(), corners / 2, soup.faces.size());
  std::vector<Mesh::VertexHandle> handles;
  handles.reserve(soup.points.size());
  for (const auto& p : soup.points)
    handles.push_back(mesh.add_vertex(Mesh::Point(p.x(), p.y(), p.z())));
  std::vector<Mesh::VertexHandle> loop;
  for (std::size_t f = 0; f < soup.faces.size(); ++f) {
    loop.clear();
    for (int v : soup.faces[f]) loop.push_back(handles[v]);
    if (!mesh.add_face(loop).is_valid()) {
      const MeshTopology t = mesh_topology(soup);
      throw TopologyError(
          name + ": face " + std::to_string(f) + " was refused by the half-edge mesh: " +
          (t.first_problem.empty() ? "the soup is an oriented manifold" : t.first_problem));
    }
  }
  return mesh;
}

double bbox_diagonal(const std::vector<Eigen::Vector3d>& points) {
  if (points.empty()) return 0.0;
  Eigen::Vector3d lo = points.front(), hi = points.front();
  for (const auto& p : points) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}

}  // namespace mg
