// models: generate the project's analytic reference meshes and medial meshes, and report a
// mesh's topology.
//   models generate sphere|torus|bumpy-torus|capsule [shape options] -o MESH
//   models generate medial-capsule|medial-slab|medial-ring|medial-disc|medial-sheets|medial-hand
//                   [--atoms N] [--hex-rings R] -o OUT.ma
//   models info MESH [--json]
#include "core/atomic_file.h"
#include "core/cli_main.h"
#include "core/mesh_io.h"
#include "core/mesh_topology.h"
#include "core/shapes.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <iomanip>
#include <string>
#include <vector>

namespace {

const std::vector<std::string> kMeshShapes = {"sphere", "torus", "bumpy-torus", "capsule"};
const std::vector<std::string> kMedialShapes = {"medial-capsule", "medial-slab",   "medial-ring",
                                                "medial-disc",    "medial-sheets", "medial-hand"};

bool is_medial_shape(const std::string& shape) {
  return std::find(kMedialShapes.begin(), kMedialShapes.end(), shape) != kMedialShapes.end();
}

/// `models generate SHAPE -o MESH`: the shape's parameters, defaults as on the command line.
struct GenerateArgs {
  std::string shape;  ///< one of kMeshShapes or kMedialShapes
  std::string output;
  int frequency = 18;        ///< sphere: geodesic frequency (V = 10 f^2 + 2)
  double radius = 1.0;       ///< sphere, model units
  int ring = 60;             ///< torus: samples around the z axis
  int tube = 20;             ///< torus: samples around the tube
  double major = 1.0;        ///< torus: axis to tube centre
  double minor = 0.3;        ///< torus: tube radius
  double amplitude = 0.1;    ///< bumpy torus: relative bump height
  int bumps_ring = 12;       ///< bumpy torus: bumps around the z axis
  int bumps_tube = 6;        ///< bumpy torus: bumps around the tube
  int atoms = 16;            ///< medial ring: atoms on the circle
  int hex_rings = 3;         ///< medial disc: rings of atoms around the centre atom
  int rows = 8;              ///< capsule: rings per quarter circle of a cap
  double half_length = 0.5;  ///< capsule: half the cylinder's length
};

CLI::App* add_generate(CLI::App& app, GenerateArgs& args) {
  auto* sub = app.add_subcommand(
      "generate", "write a generated closed triangle mesh, or a medial mesh (medial-*, .ma)");
  std::vector<std::string> shapes = kMeshShapes;
  shapes.insert(shapes.end(), kMedialShapes.begin(), kMedialShapes.end());
  sub->add_option(
         "shape", args.shape,
         "sphere | torus | bumpy-torus | capsule (meshes) | medial-capsule | medial-slab | "
         "medial-ring | medial-disc | medial-sheets | medial-hand (medial meshes)")
      ->required()
      ->check(CLI::IsMember(shapes));
  sub->add_option("-o,--output", args.output,
                  "output: a mesh (.off, .obj, .ply, .stl), or .ma for a medial mesh")
      ->required();
  sub->add_option("--frequency", args.frequency, "sphere: geodesic frequency f (V = 10 f^2 + 2)");
  sub->add_option("--radius", args.radius, "sphere, capsule: radius, model units");
  sub->add_option("--ring", args.ring, "torus, capsule: samples around the z axis");
  sub->add_option("--tube", args.tube, "torus: samples around the tube");
  sub->add_option("--major", args.major, "torus: distance from the axis to the tube centre");
  sub->add_option("--minor", args.minor, "torus: tube radius");
  sub->add_option("--amplitude", args.amplitude, "bumpy torus: relative bump height");
  sub->add_option("--bumps-ring", args.bumps_ring, "bumpy torus: bumps around the z axis");
  sub->add_option("--bumps-tube", args.bumps_tube, "bumpy torus: bumps around the tube");
  sub->add_option("--rows", args.rows, "capsule: rings per quarter circle of a cap");
  sub->add_option("--half-length", args.half_length,
                  "capsule: half the cylinder's length (along z), model units");
  sub->add_option("--atoms", args.atoms, "medial ring: atoms on the circle (>= 3)");
  sub->add_option("--hex-rings", args.hex_rings,
                  "medial disc: rings of atoms around the centre atom, 1-100 "
                  "(V = 3 R^2 + 3 R + 1)");
  return sub;
}

mg::MedialSurface generate_medial(const GenerateArgs& args) {
  const std::string& shape = args.shape;
  if (shape == "medial-capsule") return mg::make_medial_capsule();
  if (shape == "medial-slab") return mg::make_medial_slab();
  if (shape == "medial-ring") return mg::make_medial_ring(args.atoms);
  if (shape == "medial-disc") return mg::make_medial_disc(args.hex_rings);
  if (shape == "medial-sheets") return mg::make_medial_sheets();
  return mg::make_medial_hand();
}

int run_generate(const GenerateArgs& args) {
  mg::check_output_path(args.output, {});
  const bool ma_output = mg::file_extension(args.output) == ".ma";
  if (is_medial_shape(args.shape)) {
    if (!ma_output)
      throw mg::InvalidInput(args.output + ": " + args.shape +
                             " is a medial mesh: the output must be a .ma file");
    mg::write_medial_surface(generate_medial(args), args.output);
    return 0;
  }
  if (ma_output)
    throw mg::InvalidInput(args.output + ": " + args.shape +
                           " is a triangle mesh: the output must be .off, .obj, .ply or .stl");
  mg::PolygonSoup soup;
  if (args.shape == "sphere")
    soup = mg::make_geodesic_sphere(args.frequency, args.radius);
  else if (args.shape == "torus")
    soup = mg::make_torus(args.ring, args.tube, args.major, args.minor);
  else if (args.shape == "capsule")
    soup = mg::make_capsule(args.ring, args.rows, args.half_length, args.radius);
  else
    soup = mg::make_bumpy_torus(args.ring, args.tube, args.major, args.minor, args.amplitude,
                                args.bumps_ring, args.bumps_tube);
  mg::write_mesh(mg::mesh_from_soup(soup, args.shape), args.output);
  return 0;
}

/// `models info MESH [--json]`.
struct InfoArgs {
  std::string mesh;
  bool json = false;
};

CLI::App* add_info(CLI::App& app, InfoArgs& args) {
  auto* sub = app.add_subcommand("info", "print vertices, faces, genus, closedness, diagonal");
  sub->add_option("mesh", args.mesh, "input mesh")->required();
  sub->add_flag("--json", args.json, "machine-readable output");
  return sub;
}

int run_info(const InfoArgs& args) {
  const std::string& input = args.mesh;
  const mg::PolygonSoup soup = mg::read_polygon_soup(input);
  const mg::MeshTopology t = mg::mesh_topology(soup);
  const double diagonal = mg::bbox_diagonal(soup.points);
  if (args.json) {
    nlohmann::ordered_json j = {{"file", input},
                                {"vertices", t.vertices},
                                {"faces", t.faces},
                                {"edges", t.edges},
                                {"components", t.components},
                                {"euler", t.euler},
                                {"genus", t.genus},
                                {"closed", t.closed},
                                {"manifold", t.manifold},
                                {"oriented", t.oriented},
                                {"boundary_edges", t.boundary_edges},
                                {"nonmanifold_edges", t.nonmanifold_edges},
                                {"nonmanifold_vertices", t.nonmanifold_vertices},
                                {"bbox_diagonal", diagonal}};
    if (!t.first_problem.empty()) j["first_problem"] = t.first_problem;
    mg::print_json(std::cout, j);
  } else {
    std::cout << input << ": V " << t.vertices << ", F " << t.faces << ", E " << t.edges
              << ", components " << t.components << ", euler " << t.euler << ", genus " << t.genus
              << ", closed " << (t.closed ? "yes" : "no") << ", manifold "
              << (t.manifold ? "yes" : "no") << ", oriented " << (t.oriented ? "yes" : "no")
              << ", bbox diagonal " << std::setprecision(6) << diagonal << '\n';
    if (!t.first_problem.empty()) std::cout << "  first defect: " << t.first_problem << '\n';
  }
  return 0;
}

int models_main(int argc, char** argv) {
  CLI::App app{
      "Generate reference meshes (sphere, torus, bumpy torus) and medial meshes (.ma), and "
      "report mesh topology."};
  app.option_defaults()->always_capture_default();
  app.require_subcommand(1);
  GenerateArgs generate;
  InfoArgs info;
  CLI::App* generate_cmd = add_generate(app, generate);
  add_info(app, info);
  mg::parse_command_line(app, argc, argv);
  return *generate_cmd ? run_generate(generate) : run_info(info);
}

}  // namespace

int main(int argc, char** argv) {
  return mg::run_cli("models", [&] { return models_main(argc, argv); });
}
