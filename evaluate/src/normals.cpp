#include "evaluate/normals.h"

#include "core/errors.h"
#include "core/mesh_normals.h"
#include "evaluate/distances.h"
#include "evaluate/mesh_distance.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace mg::evaluate {
namespace {

constexpr double kDegrees = 57.29577951308232;  // 180 / pi

Eigen::Vector3d facet_normal(const PolygonSoup& soup, const std::array<int, 3>& t) {
  const Eigen::Vector3d& a = soup.points[t[0]];
  const Eigen::Vector3d n = (soup.points[t[1]] - a).cross(soup.points[t[2]] - a);
  const double len = n.norm();
  return len > 0 ? Eigen::Vector3d(n / len) : Eigen::Vector3d::Zero();
}

/// Barycentric coordinates of p (on or near triangle abc), clamped to the triangle.
Eigen::Vector3d barycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a,
                            const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d v0 = b - a, v1 = c - a, v2 = p - a;
  const double d00 = v0.dot(v0), d01 = v0.dot(v1), d11 = v1.dot(v1);
  const double d20 = v2.dot(v0), d21 = v2.dot(v1);
  const double den = d00 * d11 - d01 * d01;
  if (!(den > 0)) return Eigen::Vector3d(1.0 / 3, 1.0 / 3, 1.0 / 3);
  const double v = (d11 * d20 - d01 * d21) / den;
  const double w = (d00 * d21 - d01 * d20) / den;
  Eigen::Vector3d l(1 - v - w, v, w);
  l = l.cwiseMax(0.0);
  return l / l.sum();
}

double angle_deg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return kDegrees * std::atan2(a.cross(b).norm(), a.dot(b));
}

}  // namespace

NormalDeviation normal_deviation(const PolygonSoup& mesh, const PolygonSoup& reference,
                                 const NormalOptions& opt, const std::string& mesh_name,
                                 const std::string& reference_name) {
  const std::size_t count = opt.samples > 0 ? opt.samples : default_sample_count(mesh, reference);
  const Triangles mesh_tris = fan_triangles(mesh);
  const TriangleSamples samples = sample_triangles(mesh, mesh_tris, count, opt.seed, mesh_name);
  // The reference must have area too (the same check, same message).
  const Triangles ref_tris = fan_triangles(reference);
  sample_triangles(reference, ref_tris, 1, opt.seed, reference_name);
  const TriangleIndex index(reference, reference_name);
  const std::vector<Eigen::Vector3d> ref_vertex_normals =
      opt.smooth_reference ? vertex_normals(reference, NormalWeighting::angle)
                           : std::vector<Eigen::Vector3d>{};

  const std::size_t n = samples.points.size();
  std::vector<double> angle(n, -1.0);  // -1: reference normal undefined
  const std::size_t batches = (n + kOracleBatch - 1) / kOracleBatch;
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, batches),
      [&](const tbb::blocked_range<std::size_t>& range) {
        std::vector<TriangleIndex::Hit> hits(kOracleBatch);
        for (std::size_t b = range.begin(); b != range.end(); ++b) {
          const std::size_t first = b * kOracleBatch, m = std::min(kOracleBatch, n - first);
          index.closest_points(samples.points.data() + first, m, hits.data());
          for (std::size_t i = 0; i < m; ++i) {
            const Eigen::Vector3d mesh_normal =
                facet_normal(mesh, mesh_tris.corners[samples.triangle[first + i]]);
            const auto& t = ref_tris.corners[hits[i].triangle];
            Eigen::Vector3d ref_normal = facet_normal(reference, t);
            if (opt.smooth_reference) {
              const Eigen::Vector3d l = barycentric(hits[i].point, reference.points[t[0]],
                                                    reference.points[t[1]], reference.points[t[2]]);
              const Eigen::Vector3d s = l[0] * ref_vertex_normals[t[0]] +
                                        l[1] * ref_vertex_normals[t[1]] +
                                        l[2] * ref_vertex_normals[t[2]];
              if (s.norm() > 1e-12) ref_normal = s.normalized();
            }
            if (!ref_normal.isZero() && !mesh_normal.isZero())
              angle[first + i] = angle_deg(mesh_normal, ref_normal);
          }
        }
      });

  NormalDeviation r;
  std::vector<double> measured;
  measured.reserve(n);
  double sum = 0;
  for (double a : angle) {
    if (a < 0) {
      ++r.skipped;
      continue;
    }
    measured.push_back(a);
    sum += a;
    r.max_deg = std::max(r.max_deg, a);
  }
  r.samples = measured.size();
  if (measured.empty())
    throw InvalidInput(reference_name + ": no sample of " + mesh_name +
                       " found a defined reference normal");
  r.mean_deg = sum / static_cast<double>(measured.size());
  const std::size_t k =
      static_cast<std::size_t>(std::ceil(0.95 * static_cast<double>(measured.size()))) - 1;
  std::nth_element(measured.begin(), measured.begin() + static_cast<std::ptrdiff_t>(k),
                   measured.end());
  r.p95_deg = measured[k];
  return r;
}

}  // namespace mg::evaluate
