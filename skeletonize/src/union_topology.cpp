// The regular triangulation of the atoms and the dual complex of their union. The one CGAL
// translation unit of mg::skeletonize for weighted triangulations.
#include "skeletonize/union_topology.h"

#include "core/detail/cgal_conversions.h"
#include "core/errors.h"
#include "core/union_find.h"

#include <CGAL/Alpha_shape_2.h>
#include <CGAL/Alpha_shape_face_base_2.h>
#include <CGAL/Alpha_shape_vertex_base_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Fixed_alpha_shape_3.h>
#include <CGAL/Fixed_alpha_shape_cell_base_3.h>
#include <CGAL/Fixed_alpha_shape_vertex_base_3.h>
#include <CGAL/Regular_triangulation_2.h>
#include <CGAL/Regular_triangulation_3.h>
#include <CGAL/Triangulation_vertex_base_with_info_3.h>

#include <algorithm>
#include <numeric>
#include <tuple>

namespace mg::skeletonize {
namespace {

using K = CGAL::Epick;

// 3D: alpha complex at alpha = 0 over the regular triangulation, atom index as vertex info.
using Vb3 = CGAL::Fixed_alpha_shape_vertex_base_3<
    K, CGAL::Triangulation_vertex_base_with_info_3<int, K,
                                                   CGAL::Regular_triangulation_vertex_base_3<K>>>;
using Cb3 = CGAL::Fixed_alpha_shape_cell_base_3<K, CGAL::Regular_triangulation_cell_base_3<K>>;
using Tds3 = CGAL::Triangulation_data_structure_3<Vb3, Cb3>;
using Regular3 = CGAL::Regular_triangulation_3<K, Tds3>;
using Alpha3 = CGAL::Fixed_alpha_shape_3<Regular3>;

// 2D, for coplanar centres: the same in the centres' plane.
using Vb2 = CGAL::Alpha_shape_vertex_base_2<K, CGAL::Regular_triangulation_vertex_base_2<K>>;
using Fb2 = CGAL::Alpha_shape_face_base_2<K, CGAL::Regular_triangulation_face_base_2<K>>;
using Tds2 = CGAL::Triangulation_data_structure_2<Vb2, Fb2>;
using Regular2 = CGAL::Regular_triangulation_2<K, Tds2>;
using Alpha2 = CGAL::Alpha_shape_2<Regular2>;

Regular3 regular_triangulation(const MedialSurface& atoms) {
  std::vector<std::pair<Regular3::Weighted_point, int>> points;
  points.reserve(atoms.atoms.size());
  for (std::size_t i = 0; i < atoms.atoms.size(); ++i)
    points.emplace_back(detail::to_weighted_point<K>(atoms.atoms[i]), static_cast<int>(i));
  return Regular3(points.begin(), points.end());
}

/// The dual complex: its vertices (atoms), edges, triangles and tetrahedra, as atom indices. A
/// ball covered by the others can keep a power cell (far away) that its ball misses: it is in
/// the triangulation but not in the dual complex, and must not count as a component.
/// Fixed_alpha_shape_3 gets this right (its vertices must be Gabriel); Alpha_shape_2 does not
/// (tested): in 2D an isolated vertex is kept only if its centre lies in its own power cell (it
/// is its own nearest power vertex), which for a vertex without complex edges is the same as its
/// ball meeting its cell.
struct Complex {
  std::vector<int> vertices;
  std::vector<std::array<int, 2>> edges;
  std::vector<std::array<int, 3>> triangles;
  std::vector<std::array<int, 4>> tetrahedra;
};

UnionTopology summarise(const Complex& c, std::size_t n_atoms, std::size_t hidden) {
  UnionFind sets(n_atoms);
  for (const auto& e : c.edges) sets.unite(e[0], e[1]);
  UnionTopology t;
  std::vector<std::size_t> roots;
  for (int v : c.vertices) roots.push_back(sets.find(v));
  std::sort(roots.begin(), roots.end());
  t.components = static_cast<std::size_t>(std::unique(roots.begin(), roots.end()) - roots.begin());
  t.solid_euler = static_cast<long>(c.vertices.size()) - static_cast<long>(c.edges.size()) +
                  static_cast<long>(c.triangles.size()) - static_cast<long>(c.tetrahedra.size());
  t.euler = 2 * t.solid_euler;
  t.hidden_atoms = hidden;
  return t;
}

template <std::size_t N>
std::array<int, N> sorted(std::array<int, N> s) {
  std::sort(s.begin(), s.end());
  return s;
}

Complex complex_3d(Regular3& rt) {
  Alpha3 alpha(rt, 0);  // takes the triangulation over (swaps it)
  Complex c;
  for (auto e = alpha.finite_edges_begin(); e != alpha.finite_edges_end(); ++e)
    if (alpha.classify(*e) != Alpha3::EXTERIOR)
      c.edges.push_back(
          sorted<2>({e->first->vertex(e->second)->info(), e->first->vertex(e->third)->info()}));
  for (auto v = alpha.finite_vertices_begin(); v != alpha.finite_vertices_end(); ++v)
    if (alpha.classify(v) != Alpha3::EXTERIOR) c.vertices.push_back(v->info());
  for (auto f = alpha.finite_facets_begin(); f != alpha.finite_facets_end(); ++f)
    if (alpha.classify(*f) != Alpha3::EXTERIOR) {
      std::array<int, 3> t;
      for (int k = 0, j = 0; k < 4; ++k)
        if (k != f->second) t[j++] = f->first->vertex(k)->info();
      c.triangles.push_back(sorted(t));
    }
  for (auto k = alpha.finite_cells_begin(); k != alpha.finite_cells_end(); ++k)
    if (alpha.classify(k) != Alpha3::EXTERIOR)
      c.tetrahedra.push_back(sorted<4>({k->vertex(0)->info(), k->vertex(1)->info(),
                                        k->vertex(2)->info(), k->vertex(3)->info()}));
  return c;
}

/// Coplanar centres: the union is symmetric about their plane, so its dual complex is the
/// planar one of the same weighted points. `index`: the atoms' indices in the caller's list.
Complex complex_2d(const std::vector<MedialAtom>& a, const std::vector<int>& index) {
  const Eigen::Vector3d p0 = a[0].centre;
  Eigen::Vector3d e1 = Eigen::Vector3d::UnitX(), normal = Eigen::Vector3d::UnitZ();
  double best = 0;
  for (std::size_t i = 1; i < a.size(); ++i) {
    const Eigen::Vector3d d = a[i].centre - p0;
    if (d.norm() > best) {
      best = d.norm();
      e1 = d / d.norm();
    }
  }
  best = 0;
  for (std::size_t i = 1; i < a.size(); ++i) {
    const Eigen::Vector3d n = e1.cross(a[i].centre - p0);
    if (n.norm() > best) {
      best = n.norm();
      normal = n / n.norm();
    }
  }
  const Eigen::Vector3d e2 = normal.cross(e1);
  std::vector<std::pair<Regular2::Weighted_point, int>> points;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const Eigen::Vector3d d = a[i].centre - p0;
    points.emplace_back(
        Regular2::Weighted_point(K::Point_2(d.dot(e1), d.dot(e2)), a[i].radius * a[i].radius),
        index[i]);
  }
  // Regular_triangulation_2 has no info vertex base here: map back by exact coordinates.
  Alpha2 alpha(0, Alpha2::GENERAL);
  std::vector<Regular2::Weighted_point> wp;
  for (const auto& p : points) wp.push_back(p.first);
  alpha.make_alpha_shape(wp.begin(), wp.end());
  alpha.set_alpha(0);
  std::vector<std::pair<std::pair<double, double>, int>> by_position;
  for (const auto& p : points) by_position.push_back({{p.first.x(), p.first.y()}, p.second});
  std::sort(by_position.begin(), by_position.end());
  auto atom_of = [&](Alpha2::Vertex_handle v) {
    const auto key = std::make_pair(v->point().x(), v->point().y());
    // Equal centres keep the largest weight in the triangulation: any index of that centre.
    auto it = std::lower_bound(by_position.begin(), by_position.end(), std::make_pair(key, -1));
    return it->second;
  };
  Complex c;
  for (auto e = alpha.finite_edges_begin(); e != alpha.finite_edges_end(); ++e)
    if (alpha.classify(*e) != Alpha2::EXTERIOR)
      c.edges.push_back(sorted<2>({atom_of(e->first->vertex(Regular2::cw(e->second))),
                                   atom_of(e->first->vertex(Regular2::ccw(e->second)))}));
  std::vector<int> linked;
  for (const auto& e : c.edges) linked.insert(linked.end(), e.begin(), e.end());
  std::sort(linked.begin(), linked.end());
  for (auto v = alpha.finite_vertices_begin(); v != alpha.finite_vertices_end(); ++v)
    if (alpha.classify(v) != Alpha2::EXTERIOR &&
        (std::binary_search(linked.begin(), linked.end(), atom_of(v)) ||
         alpha.nearest_power_vertex(v->point().point()) == Alpha2::Vertex_handle(v)))
      c.vertices.push_back(atom_of(v));
  for (auto f = alpha.finite_faces_begin(); f != alpha.finite_faces_end(); ++f)
    if (alpha.classify(f) != Alpha2::EXTERIOR)
      c.triangles.push_back(
          sorted<3>({atom_of(f->vertex(0)), atom_of(f->vertex(1)), atom_of(f->vertex(2))}));
  return c;
}

/// Collinear (or coincident) centres: the union is a solid of revolution whose sections are
/// disks, so each component is contractible; components are the overlapping runs of the
/// balls' intervals on the line, each joined as a path of edges (each interval to the one
/// reaching farthest before it).
Complex complex_1d(const std::vector<MedialAtom>& a, const std::vector<int>& index) {
  Eigen::Vector3d dir = Eigen::Vector3d::UnitX();
  double best = 0;
  for (const auto& x : a)
    if ((x.centre - a[0].centre).norm() > best) {
      best = (x.centre - a[0].centre).norm();
      dir = (x.centre - a[0].centre) / best;
    }
  std::vector<std::tuple<double, double, int>> intervals;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double t = (a[i].centre - a[0].centre).dot(dir);
    intervals.emplace_back(t - a[i].radius, t + a[i].radius, index[i]);
  }
  std::sort(intervals.begin(), intervals.end());
  Complex c;
  double end = -INFINITY;
  int reach = -1;
  for (const auto& [lo, hi, i] : intervals) {
    c.vertices.push_back(i);
    if (lo <= end) c.edges.push_back(sorted<2>({reach, i}));
    if (hi > end) {
      end = hi;
      reach = i;
    }
  }
  return c;
}

/// The dual complex of the union of all the atoms (hidden ones excluded), from their regular
/// triangulation `rt` (taken over in 3D).
Complex dual_complex(const MedialSurface& atoms, Regular3& rt) {
  Complex c;
  if (rt.dimension() == 3) {
    c = complex_3d(rt);
  } else {
    // Fewer dimensions: the balls with a vertex (the others lie inside the union of these)
    // have coplanar or collinear centres.
    std::vector<MedialAtom> visible;
    std::vector<int> index;
    for (auto v = rt.finite_vertices_begin(); v != rt.finite_vertices_end(); ++v) {
      visible.push_back(atoms.atoms[v->info()]);
      index.push_back(v->info());
    }
    c = rt.dimension() == 2 ? complex_2d(visible, index) : complex_1d(visible, index);
  }
  std::sort(c.vertices.begin(), c.vertices.end());
  std::sort(c.edges.begin(), c.edges.end());
  c.edges.erase(std::unique(c.edges.begin(), c.edges.end()), c.edges.end());
  std::sort(c.triangles.begin(), c.triangles.end());
  c.triangles.erase(std::unique(c.triangles.begin(), c.triangles.end()), c.triangles.end());
  std::sort(c.tetrahedra.begin(), c.tetrahedra.end());
  return c;
}

UnionComplex union_complex_of(const MedialSurface& atoms, Regular3& rt) {
  const std::size_t hidden = atoms.atoms.size() - rt.number_of_vertices();
  Complex c = dual_complex(atoms, rt);
  UnionComplex out;
  out.topology = summarise(c, atoms.atoms.size(), hidden);
  out.edges = std::move(c.edges);
  out.triangles = std::move(c.triangles);
  out.tetrahedra = std::move(c.tetrahedra);
  return out;
}

}  // namespace

UnionTopology union_topology(const MedialSurface& atoms) { return union_complex(atoms).topology; }

UnionComplex union_complex(const MedialSurface& atoms) {
  validate(atoms);
  Regular3 rt = regular_triangulation(atoms);
  return union_complex_of(atoms, rt);
}

RegularSimplices regular_simplices(const MedialSurface& atoms, UnionComplex* dual) {
  validate(atoms);
  Regular3 rt = regular_triangulation(atoms);
  RegularSimplices out;
  out.hidden_atoms = atoms.atoms.size() - rt.number_of_vertices();
  for (auto e = rt.finite_edges_begin(); e != rt.finite_edges_end(); ++e) {
    std::array<int, 2> s = {e->first->vertex(e->second)->info(),
                            e->first->vertex(e->third)->info()};
    std::sort(s.begin(), s.end());
    out.edges.push_back(s);
  }
  for (auto f = rt.finite_facets_begin(); f != rt.finite_facets_end(); ++f) {
    std::array<int, 3> s;
    if (rt.dimension() == 3) {
      for (int k = 0, j = 0; k < 4; ++k)
        if (k != f->second) s[j++] = f->first->vertex(k)->info();
    } else {  // coplanar centres: the facets are the cells' three vertices
      for (int k = 0; k < 3; ++k) s[k] = f->first->vertex(k)->info();
    }
    std::sort(s.begin(), s.end());
    out.triangles.push_back(s);
  }
  if (rt.dimension() == 3)
    for (auto c = rt.finite_cells_begin(); c != rt.finite_cells_end(); ++c) {
      std::array<int, 4> s;
      for (int k = 0; k < 4; ++k) s[k] = c->vertex(k)->info();
      std::sort(s.begin(), s.end());
      out.tetrahedra.push_back(s);
    }
  std::sort(out.edges.begin(), out.edges.end());
  std::sort(out.triangles.begin(), out.triangles.end());
  std::sort(out.tetrahedra.begin(), out.tetrahedra.end());
  if (dual) *dual = union_complex_of(atoms, rt);  // last: takes the triangulation over
  return out;
}

}  // namespace mg::skeletonize
