#include "core/mesh_normals.h"

#include "core/errors.h"

#include <algorithm>
#include <cmath>

namespace mg {

Eigen::Vector3d newell_vector(const PolygonSoup& soup, int face) {
  const std::vector<int>& f = soup.faces[face];
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  const std::size_t k = f.size();
  for (std::size_t i = 0; i < k; ++i) n += soup.points[f[i]].cross(soup.points[f[(i + 1) % k]]);
  return n;
}

Eigen::Vector3d face_normal(const PolygonSoup& soup, int face) {
  const std::vector<int>& f = soup.faces[face];
  const Eigen::Vector3d n = newell_vector(soup, face);
  double longest = 0.0;  // squared, as the area
  for (std::size_t i = 0; i < f.size(); ++i)
    longest =
        std::max(longest, (soup.points[f[(i + 1) % f.size()]] - soup.points[f[i]]).squaredNorm());
  if (!(n.norm() > 1e-12 * longest)) return Eigen::Vector3d::Zero();
  return n.normalized();
}

double corner_weight(const PolygonSoup& soup, int face, int corner, const Eigen::Vector3d& normal,
                     NormalWeighting weighting) {
  if (!(normal.squaredNorm() > 0)) return 0.0;
  if (weighting == NormalWeighting::area) return 0.5 * newell_vector(soup, face).norm();
  const std::vector<int>& f = soup.faces[face];
  const std::size_t k = f.size(), i = static_cast<std::size_t>(corner);
  const Eigen::Vector3d& p = soup.points[f[i]];
  const Eigen::Vector3d a = soup.points[f[(i + k - 1) % k]] - p;
  const Eigen::Vector3d b = soup.points[f[(i + 1) % k]] - p;
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

std::vector<Eigen::Vector3d> vertex_normals(const PolygonSoup& soup, NormalWeighting weighting) {
  validate_soup(soup, "mesh");
  std::vector<Eigen::Vector3d> sum(soup.points.size(), Eigen::Vector3d::Zero());
  for (std::size_t f = 0; f < soup.faces.size(); ++f) {
    const int face = static_cast<int>(f);
    const Eigen::Vector3d n = face_normal(soup, face);
    for (std::size_t i = 0; i < soup.faces[f].size(); ++i)
      sum[soup.faces[f][i]] += corner_weight(soup, face, static_cast<int>(i), n, weighting) * n;
  }
  for (auto& v : sum)
    v = v.norm() > 1e-12 ? Eigen::Vector3d(v.normalized()) : Eigen::Vector3d::Zero();
  return sum;
}

}  // namespace mg
