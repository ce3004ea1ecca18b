// evaluate check: the combinatorial report of mg::mesh_topology and the geometric checks, whose
// intersection test is the fold repair's (mg::find_triangle_defects).
#include "evaluate/mesh_checks.h"

#include "core/triangle_defects.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace mg::evaluate {
namespace {

constexpr double kDegrees = 57.29577951308232;  // 180 / pi

}  // namespace

MeshCheck check_mesh(const PolygonSoup& soup) {
  MeshCheck c;
  c.topology = mesh_topology(soup);
  for (const auto& f : soup.faces)
    if (f.size() > 3) ++c.non_triangle_faces;

  // The faces fanned into triangles, checked as the fold repair checks M2.
  const Triangles fan = fan_triangles(soup);
  c.triangles = fan.corners.size();
  PolygonSoup triangles;
  triangles.points = soup.points;
  triangles.faces.reserve(fan.corners.size());
  for (const auto& t : fan.corners) triangles.faces.push_back({t[0], t[1], t[2]});
  const TriangleDefects d = find_triangle_defects(triangles);
  c.degenerate_triangles = d.degenerate_faces.size();
  if (!d.degenerate_faces.empty())
    c.first_degenerate = "face " + std::to_string(fan.face[d.degenerate_faces.front()]) +
                         " is degenerate (collinear corners)";

  // Smallest angle over the triangles that are not degenerate.
  double min_angle = 180;
  std::size_t next_degenerate = 0;
  for (std::size_t i = 0; i < fan.corners.size(); ++i) {
    if (next_degenerate < d.degenerate_faces.size() &&
        d.degenerate_faces[next_degenerate] == static_cast<int>(i)) {
      ++next_degenerate;
      continue;
    }
    const auto& t = fan.corners[i];
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d e1 = soup.points[t[(k + 1) % 3]] - soup.points[t[k]];
      const Eigen::Vector3d e2 = soup.points[t[(k + 2) % 3]] - soup.points[t[k]];
      min_angle = std::min(min_angle, kDegrees * std::atan2(e1.cross(e2).norm(), e1.dot(e2)));
    }
  }
  c.min_angle_deg = d.degenerate_faces.size() == fan.corners.size() ? 0.0 : min_angle;

  // Intersecting pairs of faces: pairs of triangles of one polygon do not count.
  std::vector<std::pair<std::size_t, std::size_t>> face_pairs;
  for (const auto& [i, j] : d.intersecting_pairs) {
    const std::size_t fa = fan.face[i], fb = fan.face[j];
    if (fa != fb) face_pairs.emplace_back(std::min(fa, fb), std::max(fa, fb));
  }
  std::sort(face_pairs.begin(), face_pairs.end());
  face_pairs.erase(std::unique(face_pairs.begin(), face_pairs.end()), face_pairs.end());
  c.intersecting_pairs = face_pairs.size();
  if (!face_pairs.empty())
    c.first_intersection = "faces " + std::to_string(face_pairs.front().first) + " and " +
                           std::to_string(face_pairs.front().second) + " intersect";

  // Valence: distinct neighbours through the faces' sides.
  std::vector<std::pair<int, int>> edges;
  for (const auto& f : soup.faces)
    for (std::size_t i = 0; i < f.size(); ++i) {
      const int a = f[i], b = f[(i + 1) % f.size()];
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<std::size_t> valence(soup.points.size(), 0);
  for (const auto& [a, b] : edges) {
    ++valence[a];
    ++valence[b];
  }
  for (std::size_t v : valence)
    if (v > 0) ++c.valence_histogram[v];
  return c;
}

}  // namespace mg::evaluate
