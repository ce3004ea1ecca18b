#include "core/shapes.h"

#include "core/errors.h"

#include <array>
#include <cmath>
#include <map>

namespace mg {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// Icosahedron: 12 vertices, 20 faces oriented CCW from outside.
void icosahedron(std::vector<Eigen::Vector3d>& v, std::vector<std::array<int, 3>>& f) {
  const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
  v.clear();
  for (double a : {-1.0, 1.0})
    for (double b : {-phi, phi}) {
      v.emplace_back(0, a, b);
      v.emplace_back(a, b, 0);
      v.emplace_back(b, 0, a);
    }
  // Faces: triples of mutually adjacent vertices (edge length 2), turned to face outward.
  f.clear();
  const int n = static_cast<int>(v.size());
  auto adjacent = [&](int i, int j) { return std::abs((v[i] - v[j]).norm() - 2.0) < 1e-9; };
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      for (int k = j + 1; k < n; ++k)
        if (adjacent(i, j) && adjacent(j, k) && adjacent(i, k)) {
          const Eigen::Vector3d normal = (v[j] - v[i]).cross(v[k] - v[i]);
          if (normal.dot(v[i] + v[j] + v[k]) > 0)
            f.push_back({i, j, k});
          else
            f.push_back({i, k, j});
        }
}

void check_torus(int ring, int tube, double major, double minor) {
  if (ring < 3 || tube < 3) throw InvalidInput("torus: ring and tube need at least 3 samples");
  if (!(minor > 0) || !(major > minor)) throw InvalidInput("torus: need 0 < minor < major radius");
}

/// Grid torus with tube radius r(u, v); both angles sampled uniformly from 0.
template <class Radius>
PolygonSoup grid_torus(int ring, int tube, double major, Radius radius) {
  PolygonSoup soup;
  soup.points.reserve(static_cast<std::size_t>(ring) * tube);
  for (int i = 0; i < ring; ++i) {
    const double u = 2 * kPi * i / ring;
    for (int j = 0; j < tube; ++j) {
      const double v = 2 * kPi * j / tube;
      const double r = radius(u, v);
      const double w = major + r * std::cos(v);
      soup.points.emplace_back(w * std::cos(u), w * std::sin(u), r * std::sin(v));
    }
  }
  auto id = [&](int i, int j) { return (i % ring) * tube + (j % tube); };
  for (int i = 0; i < ring; ++i)
    for (int j = 0; j < tube; ++j) {
      // u grows counter-clockwise about z, v grows from the outer equator upward: (du, dv)
      // is a right-handed frame with the outward normal.
      soup.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      soup.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return soup;
}

}  // namespace

PolygonSoup make_geodesic_sphere(int frequency, double radius) {
  if (frequency < 1) throw InvalidInput("geodesic sphere: frequency must be >= 1");
  if (!(radius > 0)) throw InvalidInput("geodesic sphere: radius must be > 0");
  std::vector<Eigen::Vector3d> corners;
  std::vector<std::array<int, 3>> ico;
  icosahedron(corners, ico);

  // A grid point is keyed by its barycentric weights on icosahedron vertices, sorted by vertex:
  // the same point seen from two faces gets the same key and the same rounding.
  using Key = std::vector<std::pair<int, int>>;
  std::map<Key, int> index;
  PolygonSoup soup;
  const int f = frequency;
  auto point = [&](const std::array<int, 3>& tri, int i, int j) {
    std::array<std::pair<int, int>, 3> w = {{{tri[0], f - i - j}, {tri[1], i}, {tri[2], j}}};
    Key key;
    for (const auto& p : w)
      if (p.second > 0) key.push_back(p);
    std::sort(key.begin(), key.end());
    auto [it, inserted] = index.emplace(key, static_cast<int>(soup.points.size()));
    if (inserted) {
      Eigen::Vector3d p = Eigen::Vector3d::Zero();
      for (const auto& [vertex, weight] : key) p += weight * corners[vertex];
      soup.points.push_back(radius * p.normalized());
    }
    return it->second;
  };
  for (const auto& tri : ico)
    for (int i = 0; i < f; ++i)
      for (int j = 0; i + j < f; ++j) {
        soup.faces.push_back({point(tri, i, j), point(tri, i + 1, j), point(tri, i, j + 1)});
        if (i + j + 1 < f)
          soup.faces.push_back(
              {point(tri, i + 1, j), point(tri, i + 1, j + 1), point(tri, i, j + 1)});
      }
  return soup;
}

PolygonSoup make_torus(int ring, int tube, double major, double minor) {
  check_torus(ring, tube, major, minor);
  return grid_torus(ring, tube, major, [minor](double, double) { return minor; });
}

PolygonSoup make_bumpy_torus(int ring, int tube, double major, double minor, double amplitude,
                             int bumps_ring, int bumps_tube) {
  check_torus(ring, tube, major, minor);
  if (!(amplitude >= 0 && amplitude < 1))
    throw InvalidInput("bumpy torus: need 0 <= amplitude < 1");
  if (!(major > minor * (1 + amplitude)))
    throw InvalidInput(
        "bumpy torus: the bumps would cross the axis (major <= minor * (1 + amplitude))");
  return grid_torus(ring, tube, major, [=](double u, double v) {
    return minor * (1 + amplitude * std::sin(bumps_ring * u) * std::sin(bumps_tube * v));
  });
}

PolygonSoup make_box(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  if (!(lo.array() < hi.array()).all()) throw InvalidInput("box: need lo < hi componentwise");
  PolygonSoup soup;
  for (int k = 0; k < 8; ++k)
    soup.points.emplace_back(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(),
                             k & 4 ? hi.z() : lo.z());
  soup.faces = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  return soup;
}

}  // namespace mg
