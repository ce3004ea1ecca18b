#include "core/shapes.h"

#include "core/errors.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <utility>

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

/// Builds a medial mesh as a simplicial complex: every side of a face is also an edge, and no
/// edge is listed twice (in either direction).
class ComplexBuilder {
 public:
  int atom(const Eigen::Vector3d& centre, double radius) {
    s_.atoms.push_back({centre, radius});
    return static_cast<int>(s_.atoms.size()) - 1;
  }
  void edge(int i, int j) {
    if (listed_.insert({std::min(i, j), std::max(i, j)}).second) s_.edges.push_back({i, j});
  }
  void face(int i, int j, int k) {
    s_.faces.push_back({i, j, k});
    edge(i, j);
    edge(j, k);
    edge(k, i);
  }
  const Eigen::Vector3d& centre(int i) const { return s_.atoms[i].centre; }
  MedialSurface take() { return std::move(s_); }

 private:
  MedialSurface s_;
  std::set<std::pair<int, int>> listed_;
};

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

PolygonSoup make_capsule(int ring, int rows, double half_length, double radius) {
  if (ring < 3 || rows < 1) throw InvalidInput("capsule: need ring >= 3 and rows >= 1");
  if (!(half_length > 0 && radius > 0 && std::isfinite(half_length) && std::isfinite(radius)))
    throw InvalidInput("capsule: need half_length > 0 and radius > 0 (0: a sphere)");
  // The profile from the north pole to the south pole, as (z, distance to the axis), poles
  // excluded.
  std::vector<std::array<double, 2>> profile;
  for (int k = 1; k <= rows; ++k) {
    const double t = kPi / 2 * k / rows;
    profile.push_back({half_length + radius * std::cos(t), radius * std::sin(t)});
  }
  const int bands =
      std::max(1, static_cast<int>(std::lround(2 * half_length / (radius * kPi / 2 / rows))));
  for (int j = 1; j < bands; ++j)
    profile.push_back({half_length - 2 * half_length * j / bands, radius});
  for (int k = rows; k >= 1; --k) {
    const double t = kPi / 2 * k / rows;
    profile.push_back({-half_length - radius * std::cos(t), radius * std::sin(t)});
  }
  PolygonSoup soup;
  const int north = 0;
  soup.points.emplace_back(0, 0, half_length + radius);
  for (const auto& [z, rho] : profile)
    for (int i = 0; i < ring; ++i) {
      const double u = 2 * kPi * i / ring;
      soup.points.emplace_back(rho * std::cos(u), rho * std::sin(u), z);
    }
  const int south = static_cast<int>(soup.points.size());
  soup.points.emplace_back(0, 0, -half_length - radius);
  const int rings = static_cast<int>(profile.size());
  auto id = [&](int r, int i) { return 1 + r * ring + (i % ring); };
  // u grows counter-clockwise about z and the profile runs downward: (du, d(profile)) is
  // left-handed with the outward normal, so each triangle lists the lower ring first.
  for (int i = 0; i < ring; ++i) soup.faces.push_back({north, id(0, i), id(0, i + 1)});
  for (int r = 0; r + 1 < rings; ++r)
    for (int i = 0; i < ring; ++i) {
      soup.faces.push_back({id(r, i), id(r + 1, i), id(r + 1, i + 1)});
      soup.faces.push_back({id(r, i), id(r + 1, i + 1), id(r, i + 1)});
    }
  for (int i = 0; i < ring; ++i)
    soup.faces.push_back({south, id(rings - 1, i + 1), id(rings - 1, i)});
  return soup;
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

MedialSurface make_medial_capsule() {
  ComplexBuilder b;
  const int a = b.atom(Eigen::Vector3d(-0.5, -0.05, -0.025), 0.4);
  const int c = b.atom(Eigen::Vector3d(0.5, 0.05, 0.025), 0.2);
  b.edge(a, c);
  return b.take();
}

MedialSurface make_medial_slab() {
  ComplexBuilder b;
  const int a = b.atom(Eigen::Vector3d(-0.5, -0.3, 0.0), 0.18);
  const int c = b.atom(Eigen::Vector3d(0.6, -0.25, 0.05), 0.12);
  const int d = b.atom(Eigen::Vector3d(0.0, 0.55, 0.15), 0.08);
  b.face(a, c, d);
  return b.take();
}

MedialSurface make_medial_ring(int atoms) {
  if (atoms < 3)
    throw InvalidInput("medial ring: need at least 3 atoms, got " + std::to_string(atoms));
  ComplexBuilder b;
  for (int k = 0; k < atoms; ++k) {
    const double t = 2 * kPi * k / atoms;
    b.atom(Eigen::Vector3d(std::cos(t), std::sin(t), 0.1 * std::sin(3 * t)),
           0.16 + 0.06 * std::cos(2 * t));
  }
  for (int k = 0; k < atoms; ++k) b.edge(k, (k + 1) % atoms);
  return b.take();
}

MedialSurface make_medial_disc(int rings) {
  if (rings < 1 || rings > 100)
    throw InvalidInput("medial disc: rings must be in [1, 100], got " + std::to_string(rings));
  // Axial lattice coordinates (q, r): position h (q + r / 2, r sqrt(3) / 2), inside the hexagon
  // when max(|q|, |r|, |q + r|) <= rings.
  const double h = 1.0 / rings;
  auto inside = [rings](int q, int r) {
    return std::max({std::abs(q), std::abs(r), std::abs(q + r)}) <= rings;
  };
  ComplexBuilder b;
  std::map<std::pair<int, int>, int> id;
  for (int r = -rings; r <= rings; ++r)
    for (int q = -rings; q <= rings; ++q) {
      if (!inside(q, r)) continue;
      const double x = h * (q + 0.5 * r), y = h * r * std::sqrt(3.0) / 2;
      const double rho = std::hypot(x, y);
      id[{q, r}] = b.atom(Eigen::Vector3d(x, y, 0.25 * rho * rho), 0.2 - 0.13 * rho);
    }
  // Each lattice rhombus (q, r), (q + 1, r), (q + 1, r + 1), (q, r + 1) gives its two
  // triangles that lie in the hexagon, CCW seen from +z.
  // (q, r) itself may lie outside when its second triangle lies inside.
  for (int r = -rings - 1; r <= rings; ++r)
    for (int q = -rings - 1; q <= rings; ++q) {
      if (inside(q, r) && inside(q + 1, r) && inside(q, r + 1))
        b.face(id[{q, r}], id[{q + 1, r}], id[{q, r + 1}]);
      if (inside(q + 1, r) && inside(q + 1, r + 1) && inside(q, r + 1))
        b.face(id[{q + 1, r}], id[{q + 1, r + 1}], id[{q, r + 1}]);
    }
  return b.take();
}

MedialSurface make_medial_sheets() {
  ComplexBuilder b;
  const int bottom = b.atom(Eigen::Vector3d(0, 0, -0.5), 0.18);
  const int top = b.atom(Eigen::Vector3d(0, 0, 0.5), 0.15);
  b.edge(bottom, top);
  for (int k = 0; k < 3; ++k) {
    const double a = kPi / 2 + 2 * kPi * k / 3;
    const Eigen::Vector3d out(0.8 * std::cos(a), 0.8 * std::sin(a), 0);
    const int lo = b.atom(out + Eigen::Vector3d(0, 0, -0.5), 0.1 + 0.01 * k);
    const int hi = b.atom(out + Eigen::Vector3d(0, 0, 0.5), 0.14 - 0.01 * k);
    b.face(bottom, lo, hi);
    b.face(bottom, hi, top);
  }
  return b.take();
}

MedialSurface make_medial_hand() {
  ComplexBuilder b;
  // Palm: a 4 x 4 grid, cupped (z = 0.3 x^2); thickest inside, thinnest along the top row
  // (the knuckles). Any two of its balls overlap or keep apart by 0.03 or more: none is near
  // tangent to another.
  int palm[4][4];  // [column i][row j]
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const double x = -0.3 + 0.2 * i, y = -0.45 + 0.2 * j;
      const bool interior = i > 0 && i < 3 && j > 0 && j < 3;
      const double r = j == 3 ? 0.08 : interior ? 0.17 : 0.16;
      palm[i][j] = b.atom(Eigen::Vector3d(x, y, 0.3 * x * x), r);
    }
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      b.face(palm[i][j], palm[i + 1][j], palm[i + 1][j + 1]);
      b.face(palm[i][j], palm[i + 1][j + 1], palm[i][j + 1]);
    }
  // A chain of atoms at distances d along `direction` from the palm atom `base`, rising by
  // lift_linear d + lift_square d^2 in z; the first joined to the base.
  auto chain = [&b](int base, const Eigen::Vector3d& direction, const std::vector<double>& d,
                    const std::vector<double>& radius, double lift_linear, double lift_square) {
    const Eigen::Vector3d from = b.centre(base);  // a copy: atom() may move the atoms
    int previous = base;
    for (std::size_t k = 0; k < d.size(); ++k) {
      const Eigen::Vector3d p =
          from + d[k] * direction +
          Eigen::Vector3d(0, 0, lift_linear * d[k] + lift_square * d[k] * d[k]);
      const int next = b.atom(p, radius[k]);
      b.edge(previous, next);
      previous = next;
    }
  };
  // Fingers from the top row, fanned out (angle from +y, degrees), curling toward +z.
  const double angle[4] = {-10, -3, 4, 12};
  const std::vector<double> d[4] = {
      {0.2, 0.38, 0.54, 0.68}, {0.2, 0.4, 0.58, 0.74}, {0.2, 0.38, 0.55, 0.7}, {0.18, 0.33, 0.46}};
  const std::vector<double> r[4] = {{0.07, 0.06, 0.052, 0.045},
                                    {0.072, 0.063, 0.055, 0.047},
                                    {0.068, 0.06, 0.052, 0.045},
                                    {0.06, 0.052, 0.045}};
  for (int i = 0; i < 4; ++i) {
    const double a = angle[i] * kPi / 180;
    const int base = palm[i][3];
    chain(base, Eigen::Vector3d(std::sin(a), std::cos(a), 0), d[i], r[i], 0, 0.15);
  }
  // Thumb from the left side, pointing out and up, rising out of the palm's plane.
  const int thumb_base = palm[0][1];
  chain(thumb_base, Eigen::Vector3d(-0.94, 0.34, 0).normalized(), {0.3, 0.48, 0.64},
        {0.085, 0.07, 0.06}, 0.25, 0);
  return b.take();
}

}  // namespace mg
