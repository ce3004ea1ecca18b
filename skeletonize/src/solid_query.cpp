// SolidQuery: CGAL's AABB tree over the mesh's triangles and Side_of_triangle_mesh.
#include "skeletonize/solid_query.h"

#include "core/detail/plain_distance_traits.h"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <cmath>

namespace mg::skeletonize {
namespace {

using K = CGAL::Epick;
using Point = K::Point_3;
using Vec3 = Eigen::Vector3d;
using SurfaceMesh = CGAL::Surface_mesh<Point>;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<SurfaceMesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;
// Closest points in plain doubles (core/detail/plain_distance_traits.h).
using PlainTree = CGAL::AABB_tree<detail::PlainDistanceTraits<Primitive>>;
using Inside = CGAL::Side_of_triangle_mesh<SurfaceMesh, K, CGAL::Default, Tree>;

Point to_point(const Vec3& p) { return Point(p.x(), p.y(), p.z()); }

/// Triangles of the mesh (polygons fanned) as a CGAL surface mesh.
SurfaceMesh triangle_mesh(const PolygonSoup& soup) {
  SurfaceMesh sm;
  std::vector<SurfaceMesh::Vertex_index> v;
  v.reserve(soup.points.size());
  for (const auto& p : soup.points) v.push_back(sm.add_vertex(to_point(p)));
  for (const auto& t : fan_triangles(soup).corners) sm.add_face(v[t[0]], v[t[1]], v[t[2]]);
  return sm;
}

/// The traversal of within(): stops at the first triangle closer than the radius, descending
/// only into boxes closer than it (plain doubles, as the distance queries).
class WithinTraversal {
 public:
  WithinTraversal(const PlainTree& tree, double radius) : tree_(&tree), r2_(radius * radius) {}
  bool go_further() const { return !found_; }
  void intersection(const Point& p, const Primitive& primitive) {
    const auto& t = CGAL::internal::Primitive_helper<PlainTree::AABB_traits>::get_datum(
        primitive, tree_->traits());
    if (detail::squared_plain(p, detail::closest_on_triangle(p, t)) < r2_) found_ = true;
  }
  template <class Node>
  bool do_intersect(const Point& p, const Node& node) const {
    return detail::box_squared_distance(p, node.bbox()) < r2_;
  }
  bool found() const { return found_; }

 private:
  const PlainTree* tree_;
  double r2_;
  bool found_ = false;
};

}  // namespace

struct SolidQuery::Impl {
  SurfaceMesh surface;
  std::unique_ptr<Tree> tree;
  std::unique_ptr<Inside> inside;
  std::unique_ptr<PlainTree> plain;  // with plain distances: the distance queries' tree
};

SolidQuery::SolidQuery(const PolygonSoup& mesh, Distances distances)
    : impl_(std::make_unique<Impl>()) {
  impl_->surface = triangle_mesh(mesh);
  impl_->tree = std::make_unique<Tree>(faces(impl_->surface).first, faces(impl_->surface).second,
                                       impl_->surface);
  impl_->tree->build();
  // The distance search's k-d tree on the tree that answers distances only.
  if (distances == Distances::cgal) impl_->tree->accelerate_distance_queries();
  impl_->inside = std::make_unique<Inside>(*impl_->tree);
  if (distances == Distances::plain) {
    impl_->plain = std::make_unique<PlainTree>(faces(impl_->surface).first,
                                               faces(impl_->surface).second, impl_->surface);
    impl_->plain->build();
    impl_->plain->accelerate_distance_queries();
  }
}

SolidQuery::~SolidQuery() = default;

bool SolidQuery::contains(const Vec3& p) const {
  return (*impl_->inside)(to_point(p)) == CGAL::ON_BOUNDED_SIDE;
}

double SolidQuery::distance(const Vec3& p) const {
  const Point q = to_point(p);
  return std::sqrt(impl_->plain ? impl_->plain->squared_distance(q)
                                : impl_->tree->squared_distance(q));
}

double SolidQuery::distance(const Vec3& p, const Vec3& hint) const {
  const Point q = to_point(p), h = to_point(hint);
  return std::sqrt(impl_->plain ? impl_->plain->squared_distance(q, h)
                                : impl_->tree->squared_distance(q, h));
}

Vec3 SolidQuery::closest_point(const Vec3& p) const {
  const Point q = impl_->plain ? impl_->plain->closest_point(to_point(p))
                               : impl_->tree->closest_point(to_point(p));
  return {q.x(), q.y(), q.z()};
}

bool SolidQuery::within(const Vec3& p, double radius) const {
  if (!(radius > 0)) return false;
  if (!impl_->plain) return impl_->tree->squared_distance(to_point(p)) < radius * radius;
  // (CGAL's traversal starts below the root without testing its box.)
  const Point q = to_point(p);
  if (!(detail::box_squared_distance(q, impl_->plain->bbox()) < radius * radius)) return false;
  WithinTraversal traversal(*impl_->plain, radius);
  impl_->plain->traversal(q, traversal);
  return traversal.found();
}

Vec3 SolidQuery::closest_point(const Vec3& p, const Vec3& hint) const {
  const Point q = to_point(p), h = to_point(hint);
  const Point c =
      impl_->plain ? impl_->plain->closest_point(q, h) : impl_->tree->closest_point(q, h);
  return {c.x(), c.y(), c.z()};
}

int SolidQuery::closest_triangle(const Vec3& p) const {
  const Point q = to_point(p);
  return static_cast<int>(impl_->plain ? impl_->plain->closest_point_and_primitive(q).second.idx()
                                       : impl_->tree->closest_point_and_primitive(q).second.idx());
}

bool SolidQuery::segment_inside(const Vec3& a, const Vec3& b) const {
  return !impl_->tree->do_intersect(K::Segment_3(to_point(a), to_point(b))) &&
         contains((a + b) / 2);
}

bool SolidQuery::triangle_inside(const Vec3& a, const Vec3& b, const Vec3& c) const {
  return !impl_->tree->do_intersect(K::Triangle_3(to_point(a), to_point(b), to_point(c))) &&
         contains((a + b + c) / 3);
}

}  // namespace mg::skeletonize
