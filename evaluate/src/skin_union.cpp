// The CGAL Skin_surface_3 translation unit: skin surface and union of balls baselines.
#include "evaluate/baselines.h"

#include "core/detail/cgal_conversions.h"
#include "core/errors.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polyhedron_3.h>
#include <CGAL/make_skin_surface_mesh_3.h>

#include <map>
#include <sstream>
#include <string>

namespace mg::evaluate {
namespace {

using Kernel = CGAL::Epick;
using Polyhedron = CGAL::Polyhedron_3<Kernel>;
using WeightedPoint = Kernel::Weighted_point_3;

std::vector<WeightedPoint> weighted_points(const MedialSurface& atoms) {
  validate(atoms);
  std::vector<WeightedPoint> points;
  points.reserve(atoms.atoms.size());
  for (const MedialAtom& a : atoms.atoms) points.push_back(detail::to_weighted_point<Kernel>(a));
  return points;
}

PolygonSoup soup_of(const Polyhedron& p) {
  PolygonSoup soup;
  std::map<Polyhedron::Vertex_const_handle, int> index;
  for (auto v = p.vertices_begin(); v != p.vertices_end(); ++v) {
    index.emplace(v, static_cast<int>(soup.points.size()));
    soup.points.push_back(detail::to_eigen(v->point()));
  }
  for (auto f = p.facets_begin(); f != p.facets_end(); ++f) {
    std::vector<int> face;
    auto h = f->facet_begin();
    do {
      face.push_back(index.at(h->vertex()));
    } while (++h != f->facet_begin());
    soup.faces.push_back(std::move(face));
  }
  return soup;
}

void check_subdivisions(int subdivisions) {
  if (subdivisions < 0)
    throw InvalidInput("--subdivisions must be >= 0, got " + std::to_string(subdivisions));
}

}  // namespace

PolygonSoup skin_surface_mesh(const MedialSurface& atoms, const SkinOptions& opt) {
  if (!(opt.shrink > 0) || !std::isfinite(opt.shrink)) {
    std::ostringstream m;
    m << "--shrink must be in (0, 1), got " << opt.shrink;
    throw InvalidInput(m.str());
  }
  if (opt.shrink >= 1) {
    std::ostringstream m;
    m << "--shrink " << opt.shrink
      << " >= 1 is the union of balls (CGAL switches silently): use `evaluate union`";
    throw InvalidInput(m.str());
  }
  check_subdivisions(opt.subdivisions);
  const std::vector<WeightedPoint> points = weighted_points(atoms);
  Polyhedron p;
  CGAL::make_skin_surface_mesh_3(p, points.begin(), points.end(), opt.shrink, opt.subdivisions,
                                 /*grow_balls=*/true);
  return soup_of(p);
}

PolygonSoup union_of_balls_mesh(const MedialSurface& atoms, int subdivisions) {
  check_subdivisions(subdivisions);
  const std::vector<WeightedPoint> points = weighted_points(atoms);
  Polyhedron p;
  CGAL::make_union_of_balls_mesh_3(p, points.begin(), points.end(), subdivisions);
  return soup_of(p);
}

}  // namespace mg::evaluate
