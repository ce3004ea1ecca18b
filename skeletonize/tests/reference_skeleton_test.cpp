// The skeletons of every reference model in experiments/models.json (materialised by the
// reference_models fixture), at the sampling models.json documents for each.
#include "core/mesh_io.h"
#include "core/mesh_topology.h"
#include "skeletonize/poles.h"
#include "skeletonize/union_topology.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <functional>
#include <map>
#include <numeric>

namespace {

using Eigen::Vector3d;
namespace sk = mg::skeletonize;

struct Model {
  std::string name;
  sk::SkeletonOptions options;  ///< the documented sampling, clamped if documented so
};

std::vector<Model> models() {
  std::ifstream in(MG_SOURCE_DIR "/experiments/models.json");
  const auto doc = nlohmann::json::parse(in);
  std::vector<Model> out;
  for (const auto& m : doc.at("models")) {
    Model model{m.at("name"), {}};
    const std::string samples = m.at("skeleton").at("samples");
    if (samples == "midpoints")
      model.options.edge_midpoints = true;
    else if (samples != "vertices")
      model.options.random_samples = std::stoul(samples);
    model.options.clamp_radius = m.at("skeleton").at("clamp");
    out.push_back(model);
  }
  return out;
}

std::vector<std::string> model_names() {
  std::vector<std::string> names;
  for (const auto& m : models()) names.push_back(m.name);
  return names;
}

// ---- Brute-force oracles over every face, independent of CGAL. ------------------------------

/// Distance from p to triangle (a, b, c) (closest point by Voronoi regions, Ericson 5.1.5).
double triangle_distance(const Vector3d& p, const Vector3d& a, const Vector3d& b,
                         const Vector3d& c) {
  const Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return ap.norm();
  const Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return bp.norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
  const Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return cp.norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0)
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  const double denom = 1 / (va + vb + vc);
  return (p - (a + ab * (vb * denom) + ac * (vc * denom))).norm();
}

/// Unsigned distance to the mesh and its winding number at p (sum of the faces' solid angles).
struct BruteForce {
  double distance = INFINITY;
  double winding = 0;
};

BruteForce brute_force(const mg::PolygonSoup& mesh, const Vector3d& p) {
  BruteForce r;
  for (const auto& f : mesh.faces)
    for (std::size_t i = 1; i + 1 < f.size(); ++i) {
      const Vector3d &a = mesh.points[f[0]], &b = mesh.points[f[i]], &c = mesh.points[f[i + 1]];
      r.distance = std::min(r.distance, triangle_distance(p, a, b, c));
      const Vector3d x = a - p, y = b - p, z = c - p;
      const double lx = x.norm(), ly = y.norm(), lz = z.norm();
      r.winding += 2 * std::atan2(x.dot(y.cross(z)),
                                  lx * ly * lz + x.dot(y) * lz + x.dot(z) * ly + y.dot(z) * lx);
    }
  r.winding /= 4 * M_PI;
  return r;
}

/// At most ~200 atoms, spread over the list (which runs from the largest pole to the smallest).
std::vector<std::size_t> some_atoms(std::size_t n) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < n; i += std::max<std::size_t>(1, n / 200)) out.push_back(i);
  return out;
}

class ReferenceSkeleton : public ::testing::TestWithParam<std::string> {
 protected:
  Model model() const {
    for (const auto& m : models())
      if (m.name == GetParam()) return m;
    throw std::runtime_error(GetParam() + " is not in models.json");
  }
  mg::PolygonSoup mesh() const {
    return mg::read_polygon_soup(std::string(MG_BINARY_DIR "/models/") + GetParam() + ".off");
  }
};

TEST_P(ReferenceSkeleton, PolesAreInsideAndTheirBallsTouchTheirSamples) {
  sk::SkeletonOptions opt = model().options;
  opt.clamp_radius = false;
  const auto soup = mesh();
  const sk::Skeleton s = sk::skeletonize(soup, opt, GetParam());
  const sk::SolidQuery solid(soup);
  const double tol = s.stats.merge_tol;
  for (const auto& a : s.atoms.atoms) EXPECT_TRUE(solid.contains(a.centre)) << a.centre.transpose();
  for (std::size_t i : some_atoms(s.atoms.atoms.size()))  // inside by winding number too
    EXPECT_GT(std::abs(brute_force(soup, s.atoms.atoms[i].centre).winding), 0.5) << "atom " << i;
  // Each sample within merge-tol of the surface of its atom; none deeper than merge-tol inside
  // any ball (polar balls are empty).
  std::size_t with_atom = 0;
  for (std::size_t i = 0; i < s.samples.size(); ++i) {
    const int a = s.atom_of_sample[i];
    if (a < 0) continue;
    ++with_atom;
    const auto& atom = s.atoms.atoms[a];
    EXPECT_NEAR((s.samples[i] - atom.centre).norm(), atom.radius, tol)
        << GetParam() << " sample " << i;
  }
  if (s.stats.skipped_samples == 0) {
    EXPECT_EQ(with_atom, s.samples.size());
  }
  double deepest = 0;
  for (const auto& p : s.samples)
    for (const auto& atom : s.atoms.atoms)
      deepest = std::max(deepest, atom.radius - (p - atom.centre).norm());
  EXPECT_LE(deepest, tol) << GetParam();
  EXPECT_NEAR(s.stats.worst_overshoot, s.stats.pole_overshoot, 0.0);
}

TEST_P(ReferenceSkeleton, ClampedBallsStayInside) {
  sk::SkeletonOptions opt = model().options;
  opt.clamp_radius = true;
  const auto soup = mesh();
  const sk::Skeleton s = sk::skeletonize(soup, opt, GetParam());
  const double bound = 1e-9 * s.stats.diagonal;
  const sk::SolidQuery solid(soup);
  for (const auto& a : s.atoms.atoms) {
    EXPECT_TRUE(solid.contains(a.centre));
    EXPECT_LE(a.radius - solid.distance(a.centre), bound) << GetParam();
  }
  for (std::size_t i : some_atoms(s.atoms.atoms.size())) {  // against every face, by brute force
    const BruteForce b = brute_force(soup, s.atoms.atoms[i].centre);
    EXPECT_LE(s.atoms.atoms[i].radius - b.distance, bound) << GetParam() << " atom " << i;
    EXPECT_GT(std::abs(b.winding), 0.5) << GetParam() << " atom " << i;
  }
  EXPECT_EQ(s.stats.worst_overshoot, 0.0);
}

TEST_P(ReferenceSkeleton, ClampingDropsExactlyTheSmallCutOffGroups) {
  sk::SkeletonOptions opt = model().options;
  opt.clamp_radius = true;
  opt.isolated_fraction = 0;
  const auto soup = mesh();
  const auto all = sk::skeletonize(soup, opt, GetParam()).atoms.atoms;
  opt.isolated_fraction = 0.01;
  const auto kept = sk::skeletonize(soup, opt, GetParam());
  // The groups of balls that meet (components of their union), by brute force.
  std::vector<int> group(all.size());
  std::iota(group.begin(), group.end(), 0);
  std::function<int(int)> find = [&](int x) {
    return group[x] == x ? x : group[x] = find(group[x]);
  };
  for (std::size_t i = 0; i < all.size(); ++i)
    for (std::size_t j = 0; j < i; ++j)
      if ((all[i].centre - all[j].centre).norm() <= all[i].radius + all[j].radius)
        group[find(static_cast<int>(i))] = find(static_cast<int>(j));
  std::map<int, double> largest_in;
  for (std::size_t i = 0; i < all.size(); ++i) {
    double& r = largest_in[find(static_cast<int>(i))];
    r = std::max(r, all[i].radius);
  }
  const int largest =
      static_cast<int>(std::max_element(all.begin(), all.end(),
                                        [](auto& a, auto& b) { return a.radius < b.radius; }) -
                       all.begin());
  std::vector<mg::MedialAtom> expected;
  for (std::size_t i = 0; i < all.size(); ++i) {
    const int g = find(static_cast<int>(i));
    if (largest_in[g] >= 0.01 * kept.stats.diagonal || g == find(largest))
      expected.push_back(all[i]);
  }
  ASSERT_EQ(kept.atoms.atoms.size(), expected.size()) << GetParam();
  EXPECT_EQ(kept.stats.dropped_small, all.size() - expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_EQ(kept.atoms.atoms[i].centre, expected[i].centre) << GetParam() << " atom " << i;
    EXPECT_EQ(kept.atoms.atoms[i].radius, expected[i].radius) << GetParam() << " atom " << i;
  }
}

TEST_P(ReferenceSkeleton, DocumentedSamplingKeepsTheTopology) {
  const auto soup = mesh();
  const auto t = mg::mesh_topology(soup);
  const auto u = sk::union_topology(sk::skeletonize(soup, model().options, GetParam()).atoms);
  EXPECT_EQ(u.components, t.components) << GetParam();
  EXPECT_EQ(u.euler, t.euler) << GetParam();
}

INSTANTIATE_TEST_SUITE_P(Models, ReferenceSkeleton, ::testing::ValuesIn(model_names()),
                         [](const auto& p) { return p.param; });

}  // namespace
