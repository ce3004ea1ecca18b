// skeletonize: medial atoms of a closed mesh by inner Voronoi poles.
//   skeletonize INPUT_MESH -o OUTPUT.ma [--samples vertices|midpoints|N] [--seed S]
//               [--merge-tol T] [--clamp-radius] [--connectivity] [--stats FILE.json] [--threads N]
#include "garbing/atomic_file.h"
#include "garbing/cli_main.h"
#include "garbing/mesh_io.h"
#include "garbing/mesh_topology.h"
#include "skeletonize/poles.h"
#include "skeletonize/union_topology.h"

#include <nlohmann/json.hpp>
#include <tbb/global_control.h>

#include <chrono>
#include <iomanip>
#include <memory>

namespace {

int skeletonize_main(int argc, char** argv) {
  CLI::App app{"Medial atoms (inner Voronoi poles) of a closed mesh, written as .ma."};
  app.option_defaults()->always_capture_default();
  std::string input, output, samples = "vertices", stats_path;
  mg::skeletonize::SkeletonOptions opt;
  int threads = 0;
  app.add_option("input", input, "closed mesh (.off .obj .ply .stl)")->required();
  app.add_option("-o,--output", output, "output medial surface (.ma)")->required();
  app.add_option("--samples", samples,
                 "vertices | midpoints (vertices + edge midpoints) | N (vertices + N random "
                 "area-uniform points)");
  app.add_option("--seed", opt.seed, "seed of the random samples");
  app.add_option("--merge-tol", opt.merge_tol,
                 "poles closer than T are one atom; balls inside another up to T are dropped "
                 "(model units; default 1e-3 of the bounding-box diagonal)")
      ->check(CLI::NonNegativeNumber);
  app.add_flag("--clamp-radius", opt.clamp_radius,
               "radius = distance from the centre to the mesh (no ball leaves the object)");
  app.add_flag("--connectivity", opt.connectivity,
               "write the regular triangulation's edges and triangles inside the object");
  app.add_option("--stats", stats_path, "write statistics as JSON");
  app.add_option("--threads", threads, "worker threads (0 = all cores)")->check(CLI::NonNegativeNumber);
  mg::parse_command_line(app, argc, argv);

  if (samples == "midpoints") {
    opt.edge_midpoints = true;
  } else if (samples != "vertices") {
    std::size_t used = 0;
    long n = -1;
    try {
      n = std::stol(samples, &used);
    } catch (const std::exception&) {
    }
    if (used != samples.size() || n < 0)
      throw mg::InvalidInput("--samples: expected vertices, midpoints or a count, got '" + samples + "'");
    opt.random_samples = static_cast<std::size_t>(n);
  }
  mg::check_output_path(output, {input});
  if (!stats_path.empty()) mg::check_output_path(stats_path, {input});
  std::unique_ptr<tbb::global_control> limit;
  if (threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                  static_cast<std::size_t>(threads));

  const auto t0 = std::chrono::steady_clock::now();
  const mg::PolygonSoup mesh = mg::read_polygon_soup(input);
  const mg::skeletonize::Skeleton skeleton = mg::skeletonize::skeletonize(mesh, opt, input);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  mg::write_medial_surface(skeleton.atoms, output);

  const mg::MeshTopology mt = mg::mesh_topology(mesh);
  const mg::skeletonize::UnionTopology ut = mg::skeletonize::union_topology(skeleton.atoms);
  if (ut.components != mt.components || ut.euler != mt.euler)
    std::cerr << "skeletonize: warning: the union of the atoms has " << ut.components
              << " component(s) and Euler characteristic " << ut.euler << ", the mesh "
              << mt.components << " and " << mt.euler
              << " (sample more densely: --samples midpoints or N)\n";
  if (!stats_path.empty()) {
    const auto& s = skeleton.stats;
    nlohmann::ordered_json j;
    j["input"] = input;
    j["samples"] = s.samples;
    j["sampling"] = samples;
    j["duplicate_samples"] = s.duplicate_samples;
    j["hull_samples"] = s.hull_samples;
    j["skipped_samples"] = s.skipped_samples;
    j["cells"] = s.cells;
    j["exact_circumcentres"] = s.exact_circumcentres;
    j["rejected_cells"] = s.rejected_cells;
    j["poles"] = s.poles;
    j["merged"] = s.merged;
    j["pruned"] = s.pruned;
    j["dropped_small"] = s.dropped_small;
    j["atoms"] = s.atoms;
    j["edges"] = skeleton.atoms.edges.size();
    j["triangles"] = skeleton.atoms.faces.size();
    j["hidden_atoms"] = s.hidden_atoms;
    j["clamped"] = opt.clamp_radius;
    j["diagonal"] = s.diagonal;
    j["merge_tol"] = s.merge_tol;
    j["rmin"] = s.rmin;
    j["rmax"] = s.rmax;
    j["worst_overshoot"] = s.worst_overshoot;
    j["worst_overshoot_pct"] = 100 * s.worst_overshoot / s.diagonal;
    j["union"] = {{"components", ut.components}, {"euler", ut.euler}};
    j["mesh"] = {{"components", mt.components}, {"euler", mt.euler}, {"genus", mt.genus}};
    j["union_matches_mesh"] = ut.components == mt.components && ut.euler == mt.euler;
    j["seconds"] = {{"delaunay", s.seconds_delaunay}, {"poles", s.seconds_poles},
                    {"merge", s.seconds_merge},       {"clamp", s.seconds_clamp},
                    {"connectivity", s.seconds_connectivity}, {"total", seconds}};
    mg::write_file_atomically(stats_path, [&](std::ostream& out) { out << std::setw(2) << j << '\n'; });
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return mg::run_cli("skeletonize", [&] { return skeletonize_main(argc, argv); });
}
