// skeletonize: medial atoms of a closed mesh by inner Voronoi poles.
//   skeletonize INPUT_MESH -o OUTPUT.ma [--samples vertices|midpoints|N] [--seed S]
//               [--merge-tol T] [--clamp-radius] [--drop-isolated F] [--connectivity]
//               [--stats FILE.json] [--threads N]
#include "core/atomic_file.h"
#include "core/cli_main.h"
#include "core/medial_surface.h"
#include "core/mesh_io.h"
#include "core/mesh_topology.h"
#include "core/timer.h"
#include "skeletonize/poles.h"
#include "skeletonize/union_topology.h"

#include <nlohmann/json.hpp>

#include <iostream>
#include <string>

namespace {

/// --samples: vertices | midpoints | N (vertices + N random points).
void parse_samples(const std::string& samples, mg::skeletonize::SkeletonOptions& opt) {
  if (samples == "vertices") return;
  if (samples == "midpoints") {
    opt.edge_midpoints = true;
    return;
  }
  const bool digits = !samples.empty() && samples.size() <= 12 &&
                      samples.find_first_not_of("0123456789") == std::string::npos;
  if (!digits)
    throw mg::InvalidInput("--samples: expected vertices, midpoints or a count, got '" + samples +
                           "'");
  opt.random_samples = std::stoul(samples);
}

nlohmann::ordered_json stats_json(const std::string& input, const std::string& sampling,
                                  const mg::skeletonize::Skeleton& skeleton,
                                  const mg::skeletonize::SkeletonOptions& opt,
                                  const mg::skeletonize::UnionTopology& ut,
                                  const mg::MeshTopology& mt, double seconds_union,
                                  double seconds) {
  const auto& s = skeleton.stats;
  nlohmann::ordered_json j;
  j["input"] = input;
  j["sampling"] = sampling;
  j["samples"] = s.samples;
  j["duplicate_samples"] = s.duplicate_samples;
  j["hull_samples"] = s.hull_samples;
  j["skipped_samples"] = s.skipped_samples;
  j["cells"] = s.cells;
  j["exact_circumcentres"] = s.exact_circumcentres;
  j["rejected_cells"] = s.rejected_cells;
  j["poles"] = s.poles;
  j["merged"] = s.merged;
  j["pruned"] = s.pruned;
  j["clamped"] = opt.clamp_radius;
  j["dropped_small"] = s.dropped_small;
  j["atoms"] = s.atoms;
  j["edges"] = skeleton.atoms.edges.size();
  j["triangles"] = skeleton.atoms.faces.size();
  j["hidden_atoms"] = ut.hidden_atoms;
  j["diagonal"] = s.diagonal;
  j["merge_tol"] = s.merge_tol;
  j["rmin"] = s.rmin;
  j["rmax"] = s.rmax;
  j["pole_overshoot"] = s.pole_overshoot;
  j["pole_overshoot_pct"] = 100 * s.pole_overshoot / s.diagonal;
  j["worst_overshoot"] = s.worst_overshoot;
  j["worst_overshoot_pct"] = 100 * s.worst_overshoot / s.diagonal;
  j["union"] = {{"components", ut.components}, {"euler", ut.euler}};
  j["mesh"] = {{"components", mt.components}, {"euler", mt.euler}, {"genus", mt.genus}};
  j["union_matches_mesh"] = ut.components == mt.components && ut.euler == mt.euler;
  j["seconds"] = {{"setup", s.seconds_setup},         {"delaunay", s.seconds_delaunay},
                  {"poles", s.seconds_poles},         {"merge", s.seconds_merge},
                  {"distances", s.seconds_distances}, {"connectivity", s.seconds_connectivity},
                  {"union_topology", seconds_union},  {"total", seconds}};
  return j;
}

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
                 "area-uniform points on the faces)");
  app.add_option("--seed", opt.seed, "seed of the random samples");
  app.add_option("--merge-tol", opt.merge_tol,
                 "poles closer than T/2 are one atom; balls inside another up to T/2 are dropped "
                 "(model units; default 1e-3 of the bounding-box diagonal)")
      ->check(mg::NonNegative);
  app.add_flag("--clamp-radius", opt.clamp_radius,
               "radius = distance from the centre to the mesh (no ball leaves the object)");
  app.add_option("--drop-isolated", opt.isolated_fraction,
                 "with --clamp-radius: drop groups of clamped balls cut off from the rest whose "
                 "largest ball is under F of the bounding-box diagonal (0: keep all)")
      ->check(CLI::Range(0.0, 1.0));
  app.add_flag("--connectivity", opt.connectivity,
               "write the regular triangulation's edges and triangles inside the object");
  app.add_option("--stats", stats_path, "write statistics as JSON");
  app.add_option("--threads", threads, "worker threads (0 = all cores)")->check(mg::NonNegative);
  mg::parse_command_line(app, argc, argv);

  parse_samples(samples, opt);
  mg::check_output_path(output, {input});
  if (!stats_path.empty()) {
    mg::check_output_path(stats_path, {input});
    if (mg::same_file(stats_path, output))
      throw mg::InvalidInput(stats_path + ": --stats names the output file");
  }
  const auto limit = mg::limit_threads(threads);

  const mg::Stopwatch clock;
  const mg::PolygonSoup mesh = mg::read_polygon_soup(input);
  const mg::skeletonize::Skeleton skeleton = mg::skeletonize::skeletonize(mesh, opt, input);
  const mg::Stopwatch union_clock;
  const mg::skeletonize::UnionTopology ut = mg::skeletonize::union_topology(skeleton.atoms);
  const double seconds_union = union_clock.seconds();
  const double seconds = clock.seconds();
  const mg::MeshTopology mt = mg::mesh_topology(mesh);

  // Both files appear, or neither.
  mg::write_files_together(
      {{output, [&](std::ostream& out) { mg::format_medial_surface(out, skeleton.atoms); }},
       {stats_path, [&](std::ostream& out) {
          mg::print_json(out,
                         stats_json(input, samples, skeleton, opt, ut, mt, seconds_union, seconds));
        }}});
  if (ut.components != mt.components || ut.euler != mt.euler)
    std::cerr << "skeletonize: warning: " << input << ": the union of the atoms has "
              << ut.components << " component(s) and Euler characteristic " << ut.euler
              << ", the mesh " << mt.components << " and " << mt.euler
              << " (sample more densely: --samples midpoints or N)\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return mg::run_cli("skeletonize", [&] { return skeletonize_main(argc, argv); });
}
