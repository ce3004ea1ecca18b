// Every reference model of experiments/models.json, as materialised in <build>/models by the
// reference_models fixture: closed, 2-manifold, oriented, with the manifest's genus.
#include "core/mesh_io.h"
#include "core/mesh_topology.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>

namespace {

nlohmann::json manifest() {
  std::ifstream in(MG_SOURCE_DIR "/experiments/models.json");
  return nlohmann::json::parse(in);
}

class ReferenceModel : public ::testing::TestWithParam<std::string> {};

TEST_P(ReferenceModel, IsClosedManifoldWithItsGenus) {
  const nlohmann::json doc = manifest();
  for (const auto& m : doc["models"]) {
    if (m["name"] != GetParam()) continue;
    const std::string path = std::string(MG_BINARY_DIR "/models/") + GetParam() + ".off";
    const mg::PolygonSoup soup = mg::read_polygon_soup(path);
    const mg::MeshTopology t = mg::mesh_topology(soup);
    EXPECT_TRUE(t.closed) << path << ": " << t.boundary_edges << " boundary edges";
    EXPECT_TRUE(t.manifold) << path << ": " << t.first_problem;
    EXPECT_TRUE(t.oriented) << path << ": " << t.first_problem;
    EXPECT_EQ(t.components, 1u) << path;
    EXPECT_EQ(t.genus, m["genus"].get<int>()) << path;
    EXPECT_NO_THROW(mg::read_mesh(path));
    return;
  }
  FAIL() << GetParam() << " is not in experiments/models.json";
}

INSTANTIATE_TEST_SUITE_P(Manifest, ReferenceModel,
                         ::testing::Values("sphere", "torus", "knot", "eight", "hand", "homer",
                                           "anchor_dense", "bumpy_torus", "cube"),
                         [](const auto& p) { return p.param; });

TEST(ReferenceModels, ManifestListsExactlyTheTestedModels) {
  std::vector<std::string> names;
  const nlohmann::json doc = manifest();
  for (const auto& m : doc["models"]) names.push_back(m["name"]);
  EXPECT_EQ(names, (std::vector<std::string>{"sphere", "torus", "knot", "eight", "hand", "homer",
                                             "anchor_dense", "bumpy_torus", "cube"}));
}

}  // namespace
