// skeletonize: medial atoms of a closed mesh by inner Voronoi poles.
//   skeletonize INPUT_MESH -o OUTPUT.ma [--samples vertices|midpoints|N] [--seed S]
//               [--merge-tol T] [--clamp-radius] [--drop-isolated F] [--connectivity]
//               [--simplify N|P% [--stability-weight K] [--no-stability] [--max-excess F]]
//               [--stats FILE.json] [--threads N]
#include "core/atomic_file.h"
#include "core/cli_main.h"
#include "core/medial_surface.h"
#include "core/mesh_io.h"
#include "core/mesh_topology.h"
#include "core/timer.h"
#include "garbing/target_shape.h"
#include "skeletonize/poles.h"
#include "skeletonize/simplify.h"
#include "skeletonize/union_topology.h"

#include <tbb/parallel_for.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

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

/// --simplify: a count N >= 1 or a percentage P% (0 < P <= 100) of the skeleton's atoms.
struct SimplifyTarget {
  std::size_t count = 0;
  double percent = 0;  ///< > 0: a percentage
};

SimplifyTarget parse_simplify(const std::string& text) {
  const bool percent = !text.empty() && text.back() == '%';
  const std::string number = percent ? text.substr(0, text.size() - 1) : text;
  if (!percent) {
    const bool digits = !number.empty() && number.size() <= 12 &&
                        number.find_first_not_of("0123456789") == std::string::npos;
    if (!digits)
      throw mg::InvalidInput("--simplify: expected a count of atoms or a percentage, got '" + text +
                             "'");
    const std::size_t n = std::stoul(number);
    if (n < 1) throw mg::InvalidInput("--simplify: must be >= 1 atom, not " + text);
    return {n, 0};
  }
  double p = 0;
  try {
    std::size_t used = 0;
    p = std::stod(number, &used);
    if (used != number.size()) throw std::invalid_argument(number);
  } catch (const std::exception&) {
    throw mg::InvalidInput("--simplify: expected a count of atoms or a percentage, got '" + text +
                           "'");
  }
  if (!(p > 0 && p <= 100))
    throw mg::InvalidInput("--simplify: a percentage must be in (0, 100], not " + text);
  return {0, p};
}

/// The one-sided distance from the mesh's samples to the envelope G of the medial mesh: max and
/// mean, model units (a sample inside G: its distance to G's boundary), and the largest over the
/// samples inside G (where G sticks out of the object) and outside it (where G falls short).
struct SampleDistance {
  double max = 0, mean = 0, max_inside = 0, max_outside = 0;
  std::size_t inside = 0;
};

SampleDistance samples_to_envelope(const mg::MedialSurface& s,
                                   const std::vector<Eigen::Vector3d>& samples) {
  namespace gb = mg::garbing;
  const gb::TargetShape g = gb::make_target_shape(s, gb::PrimitiveSet::envelope, {});
  std::vector<double> d(samples.size());
  std::vector<char> in(samples.size());
  tbb::parallel_for(std::size_t(0), samples.size(), [&](std::size_t i) {
    d[i] = g.distance(samples[i]);
    in[i] = g.contains(samples[i]);
  });
  SampleDistance r;
  for (std::size_t i = 0; i < d.size(); ++i) {  // in sample order: the same at any thread count
    r.max = std::max(r.max, d[i]);
    r.mean += d[i];
    (in[i] ? r.max_inside : r.max_outside) = std::max(in[i] ? r.max_inside : r.max_outside, d[i]);
    r.inside += in[i];
  }
  if (!d.empty()) r.mean /= static_cast<double>(d.size());
  return r;
}

nlohmann::ordered_json simplify_json(const mg::skeletonize::SimplifyStats& s, std::size_t target,
                                     const mg::skeletonize::SimplifyOptions& opt,
                                     const SampleDistance& d, double diagonal,
                                     double seconds_distance) {
  nlohmann::ordered_json j;
  j["target_atoms"] = target;
  j["target_reached"] = s.target_reached;
  j["stability"] = opt.stability;
  j["stability_weight"] = opt.stability_weight;
  j["max_excess"] = opt.max_excess;
  j["max_shortfall"] = opt.max_shortfall;
  j["before"] = {{"atoms", s.atoms_before},
                 {"edges", s.edges_before},
                 {"faces", s.faces_before},
                 {"cells", s.cells_before}};
  j["after"] = {{"atoms", s.atoms_after},
                {"edges", s.edges_after},
                {"faces", s.faces_after},
                {"cells", s.cells_after}};
  j["union_complex"] = opt.union_complex;
  j["dropped"] = {
      {"edges", s.dropped_edges}, {"faces", s.dropped_faces}, {"cells", s.dropped_cells}};
  j["joined_isolated"] = s.joined_isolated;
  j["thinned"] = {{"cells", s.thinned_cells}, {"faces", s.thinned_faces}};
  j["pruned"] = {{"edges", s.pruned_edges},          {"faces", s.pruned_faces},
                 {"cells", s.pruned_cells},          {"removed_edges", s.removed_edges},
                 {"removed_faces", s.removed_faces}, {"kept_over_excess", s.kept_excess}};
  j["collapses"] = s.collapses;
  j["contracted_loops"] = s.contracted_loops;
  j["refusals"] = {{"topology", s.refused_topology},
                   {"outside", s.refused_outside},
                   {"excess", s.refused_excess},
                   {"shortfall", s.refused_shortfall}};
  j["placements"] = {{"minimiser", s.placed_minimiser},
                     {"nearest_minimiser", s.placed_nearest_minimiser},
                     {"fallback", s.placed_fallback}};
  j["clamped_radii"] = s.clamped_radii;
  j["rounds"] = s.rounds;
  j["complex"] = {{"components_before", s.complex_components_before},
                  {"components_after", s.complex_components_after},
                  {"euler_before", s.complex_euler_before},
                  {"euler_after", s.complex_euler_after}};
  j["diagonal"] = s.diagonal;
  j["worst_excess"] = s.worst_excess;
  j["worst_excess_pct"] = 100 * s.worst_excess / diagonal;
  j["input_shortfall_pct"] = 100 * s.input_shortfall / diagonal;
  j["max_quadric_error"] = s.max_error;
  j["samples_to_envelope"] = {{"max", d.max},
                              {"mean", d.mean},
                              {"max_pct", 100 * d.max / diagonal},
                              {"mean_pct", 100 * d.mean / diagonal},
                              {"inside", d.inside},
                              {"max_inside_pct", 100 * d.max_inside / diagonal},
                              {"max_outside_pct", 100 * d.max_outside / diagonal}};
  j["seconds"] = {{"setup", s.seconds_setup},
                  {"prune", s.seconds_prune},
                  {"quadrics", s.seconds_quadrics},
                  {"collapse", s.seconds_collapse},
                  {"output", s.seconds_output},
                  {"simplify", s.seconds_setup + s.seconds_prune + s.seconds_quadrics +
                                   s.seconds_collapse + s.seconds_output},
                  {"samples_to_envelope", seconds_distance}};
  return j;
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
  std::string simplify;
  mg::skeletonize::SimplifyOptions sopt;
  bool no_stability = false;
  app.add_option("--simplify", simplify,
                 "N | P%: collapse the medial mesh of the poles (implies --connectivity) down to N "
                 "atoms, or P% of the skeleton's atoms");
  app.add_option("--stability-weight", sopt.stability_weight,
                 "with --simplify: kappa of the cost (E + kappa D^4) gamma^2 (D: the mesh's "
                 "bounding-box diagonal)")
      ->check(mg::NonNegative);
  bool all_simplices = false;
  app.add_flag("--all-simplices", all_simplices,
               "with --simplify: start from every --connectivity simplex (default: only those of "
               "the union's dual complex, balls that meet)");
  bool slab_planes = false;
  app.add_flag("--slab-planes", slab_planes,
               "with --simplify: quadrics from the medial mesh's slab and cone tangent planes "
               "(Q-MAT) instead of the object's face planes");
  app.add_flag("--no-stability", no_stability,
               "with --simplify: cost = quadric error alone (no stability ratio)");
  app.add_option("--max-excess", sopt.max_excess,
                 "with --simplify: no hull of a merged atom may stick out of the object by more "
                 "than F of D, or than its poles did (0: no bound)")
      ->check(mg::NonNegative);
  app.add_option("--max-shortfall", sopt.max_shortfall,
                 "with --simplify: no sample of a merged atom may lie farther than F of D outside "
                 "its star's balls, cones and slabs (0: no bound)")
      ->check(mg::NonNegative);
  app.add_option("--stats", stats_path, "write statistics as JSON");
  app.add_option("--threads", threads, "worker threads (0 = all cores)")->check(mg::NonNegative);
  mg::parse_command_line(app, argc, argv);

  parse_samples(samples, opt);
  std::optional<SimplifyTarget> target;
  if (!simplify.empty()) {
    target = parse_simplify(simplify);
    opt.connectivity = true;
  } else if (no_stability || all_simplices || slab_planes || app.count("--stability-weight") ||
             app.count("--max-excess") || app.count("--max-shortfall")) {
    throw mg::InvalidInput(
        "--stability-weight, --no-stability, --max-excess, --max-shortfall, --all-simplices and "
        "--slab-planes need --simplify");
  }
  sopt.stability = !no_stability;
  sopt.surface_planes = !slab_planes;
  sopt.union_complex = !all_simplices;
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
  const mg::skeletonize::UnionTopology ut = skeleton.union_complex
                                                ? skeleton.union_complex->topology
                                                : mg::skeletonize::union_topology(skeleton.atoms);
  const double seconds_union = union_clock.seconds();

  // The simplification of the poles' medial mesh.
  std::optional<mg::skeletonize::SimplifiedMedialMesh> simplified;
  SampleDistance to_envelope;
  double seconds_distance = 0;
  if (target) {
    const std::size_t poles = skeleton.atoms.atoms.size();
    sopt.target_atoms =
        target->percent > 0
            ? std::max<std::size_t>(1, static_cast<std::size_t>(std::llround(
                                           target->percent / 100 * static_cast<double>(poles))))
            : target->count;
    if (sopt.target_atoms > poles)
      throw mg::InvalidInput("--simplify " + simplify + ": more than the skeleton's " +
                             std::to_string(poles) + " atoms (poles) of " + input);
    simplified = mg::skeletonize::simplify_medial_mesh(
        mesh, skeleton.atoms, skeleton.cells, sopt, skeleton.samples, skeleton.atom_of_sample,
        skeleton.union_complex ? &*skeleton.union_complex : nullptr);
    const mg::Stopwatch distance_clock;
    to_envelope = samples_to_envelope(simplified->surface, skeleton.samples);
    seconds_distance = distance_clock.seconds();
  }
  const double seconds = clock.seconds();
  const mg::MeshTopology mt = mg::mesh_topology(mesh);
  const mg::MedialSurface& written = simplified ? simplified->surface : skeleton.atoms;

  // Both files appear, or neither.
  mg::write_files_together(
      {{output, [&](std::ostream& out) { mg::format_medial_surface(out, written); }},
       {stats_path, [&](std::ostream& out) {
          auto j = stats_json(input, samples, skeleton, opt, ut, mt, seconds_union, seconds);
          if (simplified)
            j["simplify"] = simplify_json(simplified->stats, sopt.target_atoms, sopt, to_envelope,
                                          skeleton.stats.diagonal, seconds_distance);
          mg::print_json(out, j);
        }}});
  if (simplified && !simplified->stats.target_reached)
    std::cerr << "skeletonize: warning: " << input << ": --simplify stopped at "
              << simplified->stats.atoms_after << " atoms, above the target of "
              << sopt.target_atoms << ": every further collapse was refused\n";
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
