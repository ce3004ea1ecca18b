// The one translation unit of mg::mesh that includes CGAL: its polygon-soup readers.
#include "core/mesh.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/polygon_soup_io.h>

#include <new>
#include <stdexcept>
#include <string>
#include <vector>

namespace mg {

bool read_polygon_soup_with_cgal(const std::string& path, PolygonSoup& soup) {
  using Point = CGAL::Epick::Point_3;
  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  // CGAL's readers size buffers by the file's own counts: a negative or huge list count (found
  // by fuzz_ply) throws length_error or bad_alloc from inside them. That is a malformed file.
  // PLY counts are checked against the file's size first (check_ply); this stays a safety net.
  try {
    if (!CGAL::IO::read_polygon_soup(path, points, polygons, CGAL::parameters::verbose(false)))
      return false;
  } catch (const std::length_error&) {
    return false;
  } catch (const std::bad_alloc&) {
    return false;
  }
  soup.points.clear();
  soup.points.reserve(points.size());
  for (const Point& p : points) soup.points.emplace_back(p.x(), p.y(), p.z());
  soup.faces.clear();
  soup.faces.reserve(polygons.size());
  for (const auto& poly : polygons) {
    std::vector<int> face;
    face.reserve(poly.size());
    for (std::size_t v : poly) face.push_back(v < points.size() ? static_cast<int>(v) : -1);
    soup.faces.push_back(std::move(face));
  }
  return true;
}

}  // namespace mg
