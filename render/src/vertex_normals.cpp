#include "render/vertex_normals.h"

#include "garbing/errors.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace mg::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// Twice the vector area of a polygon (Newell's method).
Eigen::Vector3d newell_vector(const PolygonSoup& soup, const std::vector<int>& face) {
  Eigen::Vector3d n = Eigen::Vector3d::Zero();
  const std::size_t k = face.size();
  for (std::size_t i = 0; i < k; ++i)
    n += soup.points[face[i]].cross(soup.points[face[(i + 1) % k]]);
  return n;
}

/// The faces around each vertex with the weight of their corner there (compressed rows).
class Incidence {
 public:
  Incidence(const PolygonSoup& soup, const std::vector<Eigen::Vector3d>& face_normals,
            const std::vector<double>& face_areas, NormalWeighting weighting)
      : start_(soup.points.size() + 1, 0) {
    for (const auto& face : soup.faces)
      for (int v : face) ++start_[v + 1];
    for (std::size_t v = 0; v < soup.points.size(); ++v) start_[v + 1] += start_[v];
    entries_.resize(start_.back());
    std::vector<int> fill(start_.begin(), start_.end() - 1);
    for (std::size_t f = 0; f < soup.faces.size(); ++f) {
      const auto& face = soup.faces[f];
      const std::size_t k = face.size();
      for (std::size_t i = 0; i < k; ++i) {
        double w = 0.0;
        if (face_normals[f].squaredNorm() > 0) {
          if (weighting == NormalWeighting::area) {
            w = face_areas[f];
          } else {
            const Eigen::Vector3d& p = soup.points[face[i]];
            const Eigen::Vector3d a = soup.points[face[(i + k - 1) % k]] - p;
            const Eigen::Vector3d b = soup.points[face[(i + 1) % k]] - p;
            w = std::atan2(a.cross(b).norm(), a.dot(b));
          }
        }
        entries_[fill[face[i]]++] = Entry{static_cast<int>(f), w};
      }
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

Eigen::Vector3d face_normal(const PolygonSoup& soup, int face) {
  const std::vector<int>& f = soup.faces.at(face);
  const Eigen::Vector3d n = newell_vector(soup, f);
  // Degenerate if the area is negligible against the face's size (collinear points give a
  // rounding-noise direction otherwise).
  double longest = 0.0;
  for (std::size_t i = 0; i < f.size(); ++i)
    longest =
        std::max(longest, (soup.points[f[(i + 1) % f.size()]] - soup.points[f[i]]).squaredNorm());
  if (!(n.norm() > 1e-12 * longest)) return Eigen::Vector3d::Zero();
  return n.normalized();
}

ShadingNormals shading_normals(const PolygonSoup& soup, const NormalOptions& opt) {
  if (!(opt.crease_angle >= 0.0 && opt.crease_angle <= 180.0))
    throw InvalidInput("crease angle must be in [0, 180] degrees, got " +
                       std::to_string(opt.crease_angle));
  const int nv = static_cast<int>(soup.points.size());
  const std::size_t nf = soup.faces.size();
  for (std::size_t f = 0; f < nf; ++f) {
    if (soup.faces[f].size() < 3)
      throw InvalidInput("face " + std::to_string(f) + " has fewer than 3 vertices");
    for (int v : soup.faces[f])
      if (v < 0 || v >= nv)
        throw InvalidInput("face " + std::to_string(f) + ": vertex index " + std::to_string(v) +
                           " out of range");
  }

  std::vector<Eigen::Vector3d> face_normals(nf);
  std::vector<double> face_areas(nf);
  for (std::size_t f = 0; f < nf; ++f) {
    face_normals[f] = face_normal(soup, static_cast<int>(f));
    face_areas[f] = 0.5 * newell_vector(soup, soup.faces[f]).norm();
  }
  const Incidence around(soup, face_normals, face_areas, opt.weighting);

  ShadingNormals out;
  out.normals.resize(nv);
  std::vector<bool> vertex_sum_vanishes(nv, false);
  for (int v = 0; v < nv; ++v) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    Eigen::Vector3d fallback = Eigen::Vector3d::UnitZ();
    bool has_fallback = false;
    for (const auto* e = around.begin(v); e != around.end(v); ++e) {
      sum += e->weight * face_normals[e->face];
      if (!has_fallback && face_normals[e->face].squaredNorm() > 0) {
        fallback = face_normals[e->face];
        has_fallback = true;
      }
    }
    vertex_sum_vanishes[v] = !(sum.norm() > 1e-12);
    out.normals[v] = vertex_sum_vanishes[v] ? fallback : sum.normalized();
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
