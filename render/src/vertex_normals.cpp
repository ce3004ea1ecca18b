#include "render/vertex_normals.h"

#include "core/errors.h"
#include "core/mesh_normals.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace mg::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// The faces around each vertex with the weight of their corner there (compressed rows).
class Incidence {
 public:
  Incidence(const PolygonSoup& soup, const std::vector<Eigen::Vector3d>& face_normals,
            NormalWeighting weighting)
      : start_(soup.points.size() + 1, 0) {
    for (const auto& face : soup.faces)
      for (int v : face) ++start_[v + 1];
    for (std::size_t v = 0; v < soup.points.size(); ++v) start_[v + 1] += start_[v];
    entries_.resize(start_.back());
    std::vector<int> fill(start_.begin(), start_.end() - 1);
    for (std::size_t f = 0; f < soup.faces.size(); ++f) {
      const int face = static_cast<int>(f);
      for (std::size_t i = 0; i < soup.faces[f].size(); ++i)
        entries_[fill[soup.faces[f][i]]++] =
            Entry{face, corner_weight(soup, face, static_cast<int>(i), face_normals[f], weighting)};
    }
  }

  struct Entry {
    int face;
    double weight;
  };
  const Entry* begin(int v) const { return entries_.data() + start_[v]; }
  const Entry* end(int v) const { return entries_.data() + start_[v + 1]; }

 private:
  std::vector<int> start_;
  std::vector<Entry> entries_;
};

}  // namespace

ShadingNormals shading_normals(const PolygonSoup& soup, const NormalOptions& opt) {
  if (!(opt.crease_angle >= 0.0 && opt.crease_angle <= 180.0))
    throw InvalidInput("crease angle must be in [0, 180] degrees, got " +
                       std::to_string(opt.crease_angle));
  const int nv = static_cast<int>(soup.points.size());
  const std::size_t nf = soup.faces.size();
  // Validates the soup too.
  const std::vector<Eigen::Vector3d> vertex = vertex_normals(soup, opt.weighting);
  std::vector<Eigen::Vector3d> face_normals(nf);
  for (std::size_t f = 0; f < nf; ++f) face_normals[f] = face_normal(soup, static_cast<int>(f));
  const Incidence around(soup, face_normals, opt.weighting);

  // A vertex whose sum vanishes takes the normal of its first non-degenerate face, or +z.
  ShadingNormals out;
  out.normals.resize(nv);
  std::vector<bool> vertex_sum_vanishes(nv, false);
  for (int v = 0; v < nv; ++v) {
    vertex_sum_vanishes[v] = vertex[v].isZero(0);
    if (!vertex_sum_vanishes[v]) {
      out.normals[v] = vertex[v];
      continue;
    }
    out.normals[v] = Eigen::Vector3d::UnitZ();
    for (const auto* e = around.begin(v); e != around.end(v); ++e)
      if (face_normals[e->face].squaredNorm() > 0) {
        out.normals[v] = face_normals[e->face];
        break;
      }
  }

  // Corner normals that differ from the vertex normal, found again by exact comparison, so
  // that equal corners share one entry.
  std::vector<std::vector<int>> extra(nv);
  auto index_of = [&](int v, const Eigen::Vector3d& n) {
    if (n == out.normals[v]) return v;
    for (int i : extra[v])
      if (out.normals[i] == n) return i;
    out.normals.push_back(n);
    extra[v].push_back(static_cast<int>(out.normals.size()) - 1);
    return static_cast<int>(out.normals.size()) - 1;
  };

  const bool smooth_everywhere = opt.crease_angle >= 180.0;
  const double min_cos = std::cos(opt.crease_angle * kPi / 180.0) - 1e-12;
  out.corners.resize(nf);
  for (std::size_t f = 0; f < nf; ++f) {
    const auto& face = soup.faces[f];
    const Eigen::Vector3d& nf_ = face_normals[f];
    out.corners[f].resize(face.size());
    for (std::size_t i = 0; i < face.size(); ++i) {
      const int v = face[i];
      int index = v;
      if (nf_.squaredNorm() == 0) {
        index = v;  // a degenerate face shows no area: any unit normal will do
      } else if (smooth_everywhere) {
        index = vertex_sum_vanishes[v] ? index_of(v, nf_) : v;
      } else {
        Eigen::Vector3d sum = Eigen::Vector3d::Zero();
        bool all_faces = true;
        for (const auto* e = around.begin(v); e != around.end(v); ++e) {
          if (face_normals[e->face].dot(nf_) >= min_cos)
            sum += e->weight * face_normals[e->face];
          else
            all_faces = false;
        }
        if (all_faces && !vertex_sum_vanishes[v])
          index = v;
        else
          index = index_of(v, sum.norm() > 1e-12 ? Eigen::Vector3d(sum.normalized()) : nf_);
      }
      out.corners[f][i] = index;
      if (index != v) out.per_vertex = false;
    }
  }
  return out;
}

}  // namespace mg::render
