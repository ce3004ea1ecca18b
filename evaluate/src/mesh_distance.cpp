// The CGAL AABB-tree translation unit of mg::evaluate: closest points on a triangle soup.
#include "evaluate/mesh_distance.h"

#include "core/detail/cgal_conversions.h"
#include "core/detail/plain_distance_traits.h"
#include "core/errors.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <tbb/parallel_invoke.h>

#include <array>
#include <cmath>
#include <exception>

namespace mg::evaluate {

namespace {

using Kernel = CGAL::Epick;
using Point = Kernel::Point_3;
using CgalTriangle = Kernel::Triangle_3;
using TriangleIterator = std::vector<CgalTriangle>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, TriangleIterator>;

double squared(const Point& a, const Point& b) { return detail::squared_plain(a, b); }

/// Closest-point queries in plain doubles (core/detail/plain_distance_traits.h).
using Tree = CGAL::AABB_tree<detail::PlainDistanceTraits<Primitive>>;

}  // namespace

struct TriangleIndex::Impl {
  PolygonSoup soup;
  Triangles triangles;
  std::vector<CgalTriangle> cgal_triangles;  ///< the non-degenerate triangles
  std::vector<std::size_t> triangle_of;  ///< cgal_triangles[i] is triangles.corners[triangle_of[i]]
  Tree tree;
  /// distances(): the previous closest point hints the next query when it lies within the
  /// previous distance plus this much of it (twice the mean edge length, model units).
  double hint_reach = 0;
};

TriangleIndex::TriangleIndex(const PolygonSoup& soup, const std::string& name)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.soup = soup;
  m.triangles = fan_triangles(soup);
  for (std::size_t i = 0; i < m.triangles.corners.size(); ++i) {
    const auto& c = m.triangles.corners[i];
    const Point a = detail::to_cgal_point<Kernel>(soup.points[c[0]]);
    const Point b = detail::to_cgal_point<Kernel>(soup.points[c[1]]);
    const Point d = detail::to_cgal_point<Kernel>(soup.points[c[2]]);
    // A degenerate triangle's points lie on its own longest edge, which neighbouring faces
    // hold; CGAL's projection onto it is not defined, so it stays out of the tree.
    if (CGAL::collinear(a, b, d)) continue;
    m.cgal_triangles.emplace_back(a, b, d);
    m.triangle_of.push_back(i);
  }
  if (m.cgal_triangles.empty())
    throw InvalidInput(name + ": no non-degenerate triangle to find closest points on");
  double edges = 0;
  for (const CgalTriangle& t : m.cgal_triangles)
    edges += std::sqrt(squared(t[0], t[1])) + std::sqrt(squared(t[1], t[2])) +
             std::sqrt(squared(t[2], t[0]));
  m.hint_reach = 2 * edges / (3.0 * static_cast<double>(m.cgal_triangles.size()));
  m.tree.insert(m.cgal_triangles.cbegin(), m.cgal_triangles.cend());
  m.tree.build();
  m.tree.accelerate_distance_queries();  // built now: later queries are const and thread-safe
}

TriangleIndex::~TriangleIndex() = default;

const PolygonSoup& TriangleIndex::soup() const { return impl_->soup; }
const Triangles& TriangleIndex::triangles() const { return impl_->triangles; }

void TriangleIndex::closest_points(const Eigen::Vector3d* queries, std::size_t count,
                                   Hit* hits) const {
  const Impl& m = *impl_;
  const TriangleIterator begin = m.cgal_triangles.cbegin();
  Tree::Point_and_primitive_id hint;
  for (std::size_t i = 0; i < count; ++i) {
    const Point q = detail::to_cgal_point<Kernel>(queries[i]);
    hint = i == 0 ? m.tree.closest_point_and_primitive(q)
                  : m.tree.closest_point_and_primitive(q, hint);
    hits[i].point = detail::to_eigen(hint.first);
    hits[i].triangle = m.triangle_of[static_cast<std::size_t>(hint.second - begin)];
  }
}

void TriangleIndex::distances(const Eigen::Vector3d* queries, std::size_t count,
                              double* out) const {
  const Impl& m = *impl_;
  Tree::Point_and_primitive_id hint;
  for (std::size_t i = 0; i < count; ++i) {
    const Point q = detail::to_cgal_point<Kernel>(queries[i]);
    // CGAL searches within |q - hint| first: a far hint (queries in random order, as G's
    // area-uniform samples in atoms_distance) visits much of the tree (measured: 10x slower on
    // a 340k-triangle mesh), so a far one gives way to CGAL's k-d tree hint.
    const double reach = i == 0 ? 0 : out[i - 1] + m.hint_reach;
    hint = i > 0 && squared(q, hint.first) <= reach * reach
               ? m.tree.closest_point_and_primitive(q, hint)
               : m.tree.closest_point_and_primitive(q);
    out[i] = std::sqrt(CGAL::squared_distance(q, hint.first));
  }
}

DistanceOracle TriangleIndex::oracle() const {
  return [this](const Eigen::Vector3d* points, std::size_t count, double* out) {
    distances(points, count, out);
  };
}

MeshDistance mesh_distance(const PolygonSoup& mesh, const PolygonSoup& reference,
                           const MeshDistanceOptions& opt, const std::string& mesh_name,
                           const std::string& reference_name) {
  SamplingOptions sampling;
  sampling.count = opt.samples > 0 ? opt.samples : default_sample_count(mesh, reference);
  sampling.seed = opt.seed;
  sampling.vertices_and_edges = opt.vertices_and_edges;
  // The four set-up tasks are independent: run them side by side; errors are rethrown in task
  // order, so the message does not depend on which thread failed first.
  SurfaceSamples on_mesh, on_reference;
  std::unique_ptr<TriangleIndex> mesh_index, reference_index;
  std::array<std::exception_ptr, 4> errors;
  auto guarded = [&errors](int task, auto&& work) {
    return [&errors, task, work] {
      try {
        work();
      } catch (...) {
        errors[task] = std::current_exception();
      }
    };
  };
  tbb::parallel_invoke(
      guarded(0, [&] { on_mesh = sample_surface(mesh, sampling, mesh_name); }),
      guarded(1, [&] { on_reference = sample_surface(reference, sampling, reference_name); }),
      guarded(2, [&] { mesh_index = std::make_unique<TriangleIndex>(mesh, mesh_name); }),
      guarded(3, [&] {
        reference_index = std::make_unique<TriangleIndex>(reference, reference_name);
      }));
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);

  MeshDistance r;
  r.samples = sampling.count;
  r.diagonal = bbox_diagonal(reference.points);
  if (!(r.diagonal > 0))
    throw InvalidInput(reference_name + ": bounding-box diagonal is 0 (all points coincide)");
  r.distance =
      two_sided_distance(on_mesh, reference_index->oracle(), on_reference, mesh_index->oracle());
  return r;
}

}  // namespace mg::evaluate
