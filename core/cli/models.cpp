// models: generate the project's analytic reference meshes and report a mesh's topology.
//   models generate sphere|torus|bumpy-torus [shape options] -o MESH
//   models info MESH [--json]
#include "core/atomic_file.h"
#include "core/cli_main.h"
#include "core/mesh_io.h"
#include "core/mesh_topology.h"
#include "core/shapes.h"

#include <nlohmann/json.hpp>

#include <iomanip>

namespace {

int models_main(int argc, char** argv) {
  CLI::App app{"Generate reference meshes (sphere, torus, bumpy torus) and report mesh topology."};
  app.option_defaults()->always_capture_default();
  app.require_subcommand(1);

  auto* gen = app.add_subcommand("generate", "write a generated closed triangle mesh");
  std::string shape, output;
  int frequency = 18, ring = 60, tube = 20, bumps_ring = 12, bumps_tube = 6;
  double radius = 1.0, major = 1.0, minor = 0.3, amplitude = 0.1;
  gen->add_option("shape", shape, "sphere | torus | bumpy-torus")
      ->required()
      ->check(CLI::IsMember({"sphere", "torus", "bumpy-torus"}));
  gen->add_option("-o,--output", output, "output mesh (.off, .obj, .ply, .stl)")->required();
  gen->add_option("--frequency", frequency, "sphere: geodesic frequency f (V = 10 f^2 + 2)");
  gen->add_option("--radius", radius, "sphere: radius, model units");
  gen->add_option("--ring", ring, "torus: samples around the z axis");
  gen->add_option("--tube", tube, "torus: samples around the tube");
  gen->add_option("--major", major, "torus: distance from the axis to the tube centre");
  gen->add_option("--minor", minor, "torus: tube radius");
  gen->add_option("--amplitude", amplitude, "bumpy torus: relative bump height");
  gen->add_option("--bumps-ring", bumps_ring, "bumpy torus: bumps around the z axis");
  gen->add_option("--bumps-tube", bumps_tube, "bumpy torus: bumps around the tube");

  auto* info = app.add_subcommand("info", "print vertices, faces, genus, closedness, diagonal");
  std::string input;
  bool json = false;
  info->add_option("mesh", input, "input mesh")->required();
  info->add_flag("--json", json, "machine-readable output");

  mg::parse_command_line(app, argc, argv);

  if (*gen) {
    mg::check_output_path(output, {});
    mg::PolygonSoup soup;
    if (shape == "sphere")
      soup = mg::make_geodesic_sphere(frequency, radius);
    else if (shape == "torus")
      soup = mg::make_torus(ring, tube, major, minor);
    else
      soup = mg::make_bumpy_torus(ring, tube, major, minor, amplitude, bumps_ring, bumps_tube);
    mg::write_mesh(mg::mesh_from_soup(soup, shape), output);
    return 0;
  }

  const mg::PolygonSoup soup = mg::read_polygon_soup(input);
  const mg::MeshTopology t = mg::mesh_topology(soup);
  const double diagonal = mg::bbox_diagonal(soup.points);
  if (json) {
    nlohmann::ordered_json j;
    j["file"] = input;
    j["vertices"] = t.vertices;
    j["faces"] = t.faces;
    j["edges"] = t.edges;
    j["components"] = t.components;
    j["euler"] = t.euler;
    j["genus"] = t.genus;
    j["closed"] = t.closed;
    j["manifold"] = t.manifold;
    j["oriented"] = t.oriented;
    j["boundary_edges"] = t.boundary_edges;
    j["nonmanifold_edges"] = t.nonmanifold_edges;
    j["nonmanifold_vertices"] = t.nonmanifold_vertices;
    j["bbox_diagonal"] = diagonal;
    if (!t.first_problem.empty()) j["first_problem"] = t.first_problem;
    std::cout << std::setw(2) << j << '\n';
  } else {
    std::cout << input << ": V " << t.vertices << ", F " << t.faces << ", E " << t.edges
              << ", components " << t.components << ", euler " << t.euler << ", genus "
              << t.genus << ", closed " << (t.closed ? "yes" : "no") << ", manifold "
              << (t.manifold ? "yes" : "no") << ", oriented " << (t.oriented ? "yes" : "no")
              << ", bbox diagonal " << std::setprecision(6) << diagonal << '\n';
    if (!t.first_problem.empty()) std::cout << "  first defect: " << t.first_problem << '\n';
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return mg::run_cli("models", [&] { return models_main(argc, argv); });
}
