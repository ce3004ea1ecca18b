// render: POV-Ray pictures of meshes and medial surfaces (union of spheres coloured by radius;
// a medial mesh as its envelope: the spheres, its edges' cones and its faces' slabs).
//   render INPUT... -o OUTPUT.png [--pov SCENE.pov] [--width W] [--height H] [--view VIEW.json]
//          [--direction X Y Z] [--fov DEG] [--flat] [--crease DEG] [--normals angle|area]
//          [--primitives auto|ma|rt] [--transmit T] [--antialias T] [--threads N] [--povray EXE]
#include "core/atomic_file.h"
#include "core/cli_main.h"
#include "core/mesh_io.h"
#include "garbing/target_shape.h"
#include "render/povray_scene.h"
#include "render/run_povray.h"
#include "render/view.h"

#include <cmath>
#include <filesystem>
#include <fstream>

namespace {

/// The camera: read from an existing view file (resized to --width/--height if given, at the
/// same aspect ratio), else framed on the first object.
/// @param reframing  --direction or --fov was given: refused with an existing view file
/// @throws InvalidInput, IoError
mg::render::View choose_view(const std::string& view_path, bool view_exists, bool reframing,
                             int width, int height, const mg::render::SceneObject& first,
                             const mg::render::FramingOptions& framing) {
  if (!view_exists)
    return mg::render::frame_object(first, width ? width : 800, height ? height : 600, framing);
  if (reframing)
    throw mg::InvalidInput(view_path +
                           ": --direction and --fov apply only when framing a new "
                           "view; this view file exists");
  mg::render::View view = mg::render::read_view(view_path);
  const int w = width ? width : (height ? 0 : view.width);
  const int h = height ? height : (width ? 0 : view.height);
  // One size given: the other follows the view's aspect ratio.
  const int fw =
      w ? w : static_cast<int>(std::lround(static_cast<double>(h) * view.width / view.height));
  const int fh =
      h ? h : static_cast<int>(std::lround(static_cast<double>(w) * view.height / view.width));
  if (static_cast<long long>(fw) * view.height != static_cast<long long>(fh) * view.width)
    throw mg::InvalidInput(view_path + ": framed for " + std::to_string(view.width) + "x" +
                           std::to_string(view.height) + ", not for the aspect ratio of " +
                           std::to_string(fw) + "x" + std::to_string(fh));
  view.width = fw;
  view.height = fh;
  return view;
}

int render_main(int argc, char** argv) {
  CLI::App app{
      "Render meshes (.off .obj .ply .stl) and medial surfaces (.ma .xyzr: spheres coloured by "
      "radius, red = small to blue = large; a medial mesh as its envelope, with the cones of its "
      "edges and the slabs of its faces) with POV-Ray, in one scene framed on the first input."};
  app.option_defaults()->always_capture_default();
  std::vector<std::string> inputs;
  std::string output, pov_path, view_path, normals = "angle", primitives = "auto";
  int width = 0, height = 0;
  std::vector<double> direction;
  mg::render::FramingOptions framing;
  mg::render::SceneOptions scene_opt;
  mg::render::PovrayOptions povray;
  app.add_option("inputs", inputs, "meshes and medial surfaces; the first one is framed")
      ->required();
  app.add_option("-o,--output", output, "output image (.png)");
  app.add_option("--pov", pov_path, "also write the POV-Ray scene here (alone if no -o)");
  app.add_option("--width", width, "image width, pixels (default 800, or the view file's)")
      ->check(CLI::Range(1, 16384));
  app.add_option("--height", height, "image height, pixels (default 600, or the view file's)")
      ->check(CLI::Range(1, 16384));
  app.add_option(
      "--view", view_path,
      "camera file (JSON): read if it exists, else framed on the first input and written");
  app.add_option("--direction", direction,
                 "from the object towards the eye when framing (model axes; default 0.5 0.5 1)")
      ->expected(3);
  app.add_option("--fov", framing.angle, "horizontal field of view when framing, degrees")
      ->check(CLI::Range(1.0, 150.0));
  app.add_flag("--flat", scene_opt.flat_shading, "flat shading of meshes (no vertex normals)");
  app.add_option("--crease", scene_opt.normals.crease_angle,
                 "crease angle, degrees: sharper edges stay sharp (180 = smooth everywhere)")
      ->check(CLI::Range(0.0, 180.0));
  app.add_option("--normals", normals, "vertex normal weighting: angle | area")
      ->check(CLI::IsMember({"angle", "area"}));
  app.add_option("--primitives", primitives,
                 "medial surfaces: ma (the envelope: balls, a cone per edge, a slab per face), rt "
                 "(the balls alone), auto (ma when the file has edges or faces)");
  app.add_option("--transmit", scene_opt.mesh_transmit,
                 "meshes let this fraction of light through, [0, 1) (e.g. 0.6 shows atoms inside)")
      ->check(CLI::Range(0.0, 0.99));
  app.add_option("--antialias", povray.antialias_threshold,
                 "anti-aliasing threshold (POV-Ray +A, method 2, no jitter); 0 = off")
      ->check(CLI::Range(0.0, 3.0));
  app.add_option("--threads", povray.threads, "POV-Ray threads (0 = every core)")
      ->check(mg::NonNegative);
  app.add_option("--povray", povray.executable, "POV-Ray executable (name on PATH, or a path)");
  mg::parse_command_line(app, argc, argv);

  if (output.empty() && pov_path.empty())
    throw mg::InvalidInput("nothing to write: give -o OUTPUT.png and/or --pov SCENE.pov");
  if (!output.empty() && mg::file_extension(output) != ".png")
    throw mg::InvalidInput(output + ": the output image must be a .png file");
  std::vector<std::string> protected_paths = inputs;
  if (!view_path.empty()) protected_paths.push_back(view_path);
  if (!output.empty()) mg::check_output_path(output, protected_paths);
  if (!pov_path.empty()) {
    mg::check_output_path(pov_path, protected_paths);
    if (pov_path == output) throw mg::InvalidInput(pov_path + ": --pov and -o name the same file");
  }
  if (!view_path.empty() && !std::filesystem::exists(view_path))
    mg::check_output_path(view_path, inputs);
  if (!direction.empty())
    framing.direction = Eigen::Vector3d(direction[0], direction[1], direction[2]);
  try {
    scene_opt.primitives = mg::garbing::parse_primitive_set(primitives);
  } catch (const mg::InvalidInput& e) {
    throw mg::InvalidInput(std::string("--primitives: ") + e.what());
  }
  scene_opt.normals.weighting =
      normals == "area" ? mg::render::NormalWeighting::area : mg::render::NormalWeighting::angle;

  std::vector<mg::render::SceneObject> objects;
  for (const std::string& input : inputs) objects.push_back(mg::render::read_scene_object(input));

  const bool view_exists = !view_path.empty() && std::filesystem::exists(view_path);
  const mg::render::View view =
      choose_view(view_path, view_exists, !direction.empty() || app.count("--fov"), width, height,
                  objects.front(), framing);

  const std::string scene = mg::render::povray_scene(objects, view, scene_opt);
  if (!view_path.empty() && !view_exists) mg::render::write_view(view, view_path);
  if (!pov_path.empty()) {
    const std::string pov_name = std::filesystem::path(pov_path).filename().string();
    mg::write_file_atomically(pov_path, [&](std::ostream& out) {
      out << "// render with: povray "
          << mg::render::povray_arguments(pov_name, "image.png", view.width, view.height, povray)
          << '\n'
          << scene;
    });
  }
  if (!output.empty()) mg::render::render_png(scene, output, view.width, view.height, povray);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return mg::run_cli("render", [&] { return render_main(argc, argv); });
}
