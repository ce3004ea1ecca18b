// The skeletons of the reference models (materialised by the reference_models fixture), at the
// sampling experiments/models.json documents for each.
#include "garbing/mesh_io.h"
#include "garbing/mesh_topology.h"
#include "skeletonize/poles.h"
#include "skeletonize/union_topology.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>

namespace {

namespace sk = mg::skeletonize;

struct Model {
  std::string name;
  sk::SkeletonOptions options;  // the documented sampling
  bool clamp = false;
};

std::vector<Model> models() {
  std::ifstream in(MG_SOURCE_DIR "/experiments/models.json");
  const auto doc = nlohmann::json::parse(in);
  std::vector<Model> out;
  for (const auto& m : doc["models"]) {
    Model model{m["name"], {}, m["skeleton"]["clamp"]};
    const std::string samples = m["skeleton"]["samples"];
    if (samples == "midpoints")
      model.options.edge_midpoints = true;
    else if (samples != "vertices")
      model.options.random_samples = std::stoul(samples);
    out.push_back(model);
  }
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

TEST_P(ReferenceSkeleton, PolesAreInsideAndTouchTheirSamples) {
  const Model m = model();
  const auto soup = mesh();
  const sk::Skeleton s = sk::skeletonize(soup, m.options, GetParam());
  const sk::SolidQuery solid(soup);
  const double tol = s.stats.merge_tol;
  for (const auto& a : s.atoms.atoms) EXPECT_TRUE(solid.contains(a.centre)) << a.centre.transpose();
  // Each sample within merge-tol of the surface of its atom; none deeper than merge-tol inside
  // any ball (polar balls are empty).
  for (std::size_t i = 0; i < s.samples.size(); ++i) {
    const int a = s.atom_of_sample[i];
    if (a < 0) continue;
    const auto& atom = s.atoms.atoms[a];
    EXPECT_NEAR((s.samples[i] - atom.centre).norm(), atom.radius, tol)
        << GetParam() << " sample " << i;
  }
  double deepest = 0;
  for (const auto& p : s.samples)
    for (const auto& atom : s.atoms.atoms)
      deepest = std::max(deepest, atom.radius - (p - atom.centre).norm());
  EXPECT_LE(deepest, tol) << GetParam();
}

TEST_P(ReferenceSkeleton, ClampedBallsStayInside) {
  Model m = model();
  m.options.clamp_radius = true;
  const auto soup = mesh();
  const sk::Skeleton s = sk::skeletonize(soup, m.options, GetParam());
  const sk::SolidQuery solid(soup);
  for (const auto& a : s.atoms.atoms) {
    EXPECT_TRUE(solid.contains(a.centre));
    EXPECT_LE(a.radius - solid.distance(a.centre), 1e-9 * s.stats.diagonal) << GetParam();
  }
  EXPECT_EQ(s.stats.worst_overshoot, 0.0);
}

TEST_P(ReferenceSkeleton, DocumentedSamplingKeepsTheTopology) {
  Model m = model();
  m.options.clamp_radius = m.clamp;
  const auto soup = mesh();
  const auto t = mg::mesh_topology(soup);
  const auto u = sk::union_topology(sk::skeletonize(soup, m.options, GetParam()).atoms);
  EXPECT_EQ(u.components, t.components) << GetParam();
  EXPECT_EQ(u.euler, t.euler) << GetParam();
}

INSTANTIATE_TEST_SUITE_P(Models, ReferenceSkeleton,
                         ::testing::Values("sphere", "torus", "knot", "eight", "hand", "homer",
                                           "anchor_dense", "bumpy_torus", "cube"),
                         [](const auto& p) { return p.param; });

}  // namespace
