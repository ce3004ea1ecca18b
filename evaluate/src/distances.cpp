#include "evaluate/distances.h"

#include "core/errors.h"
#include "core/random.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace mg::evaluate {
namespace {

/// Uniform in [0, 1): draw `index` of stream `stream` of `seed` (counter based: value k
/// depends only on the seed, the stream and k).
double uniform(std::uint64_t seed, std::uint64_t stream, std::uint64_t index) {
  return unit_interval(splitmix64(splitmix64(seed ^ splitmix64(stream)) + index));
}

enum Stream : std::uint64_t { kFaceOffset = 1, kEdgeOffset, kBary1, kBary2 };

double triangle_area(const PolygonSoup& soup, const std::array<int, 3>& t) {
  const Eigen::Vector3d& a = soup.points[t[0]];
  return 0.5 * (soup.points[t[1]] - a).cross(soup.points[t[2]] - a).norm();
}

std::size_t referenced_vertex_count(const PolygonSoup& soup) {
  std::vector<char> used(soup.points.size(), 0);
  for (const auto& f : soup.faces)
    for (int v : f) used[v] = 1;
  return static_cast<std::size_t>(std::count(used.begin(), used.end(), 1));
}

}  // namespace

OneSidedDistance one_sided_distance(const SurfaceSamples& from, const DistanceOracle& to) {
  const std::size_t n = from.points.size();
  if (n == 0) throw InvalidInput("distance: no samples");
  if (from.weights.size() != n)
    throw InvalidInput("distance: " + std::to_string(from.weights.size()) + " weights for " +
                       std::to_string(n) + " samples");
  double weight_sum = 0;
  for (double w : from.weights) {
    if (!(w >= 0) || !std::isfinite(w))
      throw InvalidInput("distance: sample weights must be finite and >= 0");
    weight_sum += w;
  }
  if (!(weight_sum > 0)) throw InvalidInput("distance: sample weights sum to 0");

  std::vector<double> d(n);
  const std::size_t batches = (n + kOracleBatch - 1) / kOracleBatch;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, batches),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t b = range.begin(); b != range.end(); ++b) {
                        const std::size_t first = b * kOracleBatch;
                        to(from.points.data() + first, std::min(kOracleBatch, n - first),
                           d.data() + first);
                      }
                    });

  // Serial sums in sample order: bit-identical at any thread count.
  OneSidedDistance r;
  r.samples = n;
  double sum_d = 0, sum_d2 = 0;
  std::size_t farthest = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double di = d[i];
    if (!(di >= 0) || !std::isfinite(di))
      throw NumericalError("distance: the oracle returned " + std::to_string(di) + " for sample " +
                           std::to_string(i));
    if (di > r.max) {
      r.max = di;
      farthest = i;
    }
    const double w = from.weights[i];
    if (w > 0) {
      ++r.weighted_samples;
      sum_d += w * di;
      sum_d2 += w * di * di;
    }
  }
  r.mean = sum_d / weight_sum;
  r.rms = std::sqrt(sum_d2 / weight_sum);
  r.farthest = from.points[farthest];
  return r;
}

TwoSidedDistance two_sided_distance(const SurfaceSamples& on_a, const DistanceOracle& to_b,
                                    const SurfaceSamples& on_b, const DistanceOracle& to_a) {
  TwoSidedDistance r;
  r.a_to_b = one_sided_distance(on_a, to_b);
  r.b_to_a = one_sided_distance(on_b, to_a);
  r.hausdorff = std::max(r.a_to_b.max, r.b_to_a.max);
  r.rms = std::max(r.a_to_b.rms, r.b_to_a.rms);
  r.mean = std::max(r.a_to_b.mean, r.b_to_a.mean);
  return r;
}

double percent_of_diagonal(double value, double diagonal) {
  if (!(diagonal > 0)) throw InvalidInput("bounding-box diagonal must be > 0");
  return 100.0 * value / diagonal;
}

TriangleSamples sample_triangles(const PolygonSoup& soup, const Triangles& triangles,
                                 std::size_t count, std::uint64_t seed, const std::string& name) {
  if (triangles.corners.empty()) throw InvalidInput(name + ": no face to sample");
  std::vector<double> cumulative(triangles.corners.size() + 1, 0.0);
  for (std::size_t i = 0; i < triangles.corners.size(); ++i)
    cumulative[i + 1] = cumulative[i] + triangle_area(soup, triangles.corners[i]);
  const double area = cumulative.back();
  if (!(area > 0) || !std::isfinite(area))
    throw InvalidInput(name + ": the surface has zero area, nothing to sample");
  if (count == 0) throw InvalidInput(name + ": the sample count must be >= 1");

  TriangleSamples s;
  s.points.reserve(count);
  s.triangle.reserve(count);
  const double offset = uniform(seed, kFaceOffset, 0);
  std::size_t tri = 0;
  for (std::size_t k = 0; k < count; ++k) {
    // t < area, so the walk stops on a triangle of positive area.
    const double t = (static_cast<double>(k) + offset) * area / static_cast<double>(count);
    while (tri + 1 < triangles.corners.size() && cumulative[tri + 1] <= t) ++tri;
    const auto& c = triangles.corners[tri];
    const double r1 = std::sqrt(uniform(seed, kBary1, k));
    const double r2 = uniform(seed, kBary2, k);
    s.points.push_back((1 - r1) * soup.points[c[0]] + r1 * (1 - r2) * soup.points[c[1]] +
                       r1 * r2 * soup.points[c[2]]);
    s.triangle.push_back(tri);
  }
  return s;
}

SurfaceSamples sample_surface(const PolygonSoup& soup, const SamplingOptions& opt,
                              const std::string& name) {
  if (opt.count == 0) throw InvalidInput(name + ": the sample count must be >= 1");
  SurfaceSamples s;
  std::size_t n_edges = 0, n_faces = opt.count;
  if (opt.vertices_and_edges) {
    std::vector<char> used(soup.points.size(), 0);
    std::vector<std::pair<int, int>> edges;
    for (const auto& f : soup.faces)
      for (std::size_t i = 0; i < f.size(); ++i) {
        used[f[i]] = 1;
        const int a = f[i], b = f[(i + 1) % f.size()];
        edges.emplace_back(std::min(a, b), std::max(a, b));
      }
    const auto v = static_cast<std::size_t>(std::count(used.begin(), used.end(), 1));
    if (opt.count < 2 * v)
      throw InvalidInput(name + ": " + std::to_string(opt.count) +
                         " samples are fewer than twice its " + std::to_string(v) +
                         " vertices (Metro sampling takes every vertex): raise the count or "
                         "sample faces only");
    const std::size_t rest = opt.count - v;
    n_edges = rest / 4;
    n_faces = rest - n_edges;
    s.points.reserve(opt.count);
    for (std::size_t i = 0; i < soup.points.size(); ++i)
      if (used[i]) s.points.push_back(soup.points[i]);

    // Edge points: systematic along the cumulative length of the distinct edges.
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    std::vector<double> cum_len(edges.size() + 1, 0.0);
    for (std::size_t i = 0; i < edges.size(); ++i)
      cum_len[i + 1] =
          cum_len[i] + (soup.points[edges[i].second] - soup.points[edges[i].first]).norm();
    const double length = cum_len.back();
    const double offset = uniform(opt.seed, kEdgeOffset, 0);
    std::size_t e = 0;
    for (std::size_t k = 0; k < n_edges && !edges.empty(); ++k) {
      const double t = (static_cast<double>(k) + offset) * length / static_cast<double>(n_edges);
      while (e + 1 < edges.size() && cum_len[e + 1] <= t) ++e;
      const double seg = cum_len[e + 1] - cum_len[e];
      const double u = seg > 0 ? std::clamp((t - cum_len[e]) / seg, 0.0, 1.0) : 0.0;
      s.points.push_back((1 - u) * soup.points[edges[e].first] + u * soup.points[edges[e].second]);
    }
  }
  s.weights.assign(s.points.size(), 0.0);  // vertices and edge points: the maximum only

  TriangleSamples faces = sample_triangles(soup, fan_triangles(soup), n_faces, opt.seed, name);
  s.points.insert(s.points.end(), faces.points.begin(), faces.points.end());
  s.weights.resize(s.points.size(), 1.0);  // equal areas
  return s;
}

std::size_t default_sample_count(const PolygonSoup& a, const PolygonSoup& b) {
  return std::max<std::size_t>(1000000,
                               10 * (referenced_vertex_count(a) + referenced_vertex_count(b)));
}

}  // namespace mg::evaluate
