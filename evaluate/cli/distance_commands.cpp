// evaluate distance, atoms, normals and check: measures of a mesh, read as a polygon soup.
#include "commands.h"

#include "core/medial_surface.h"
#include "core/mesh_io.h"
#include "core/timer.h"
#include "evaluate/atoms_distance.h"
#include "evaluate/distances.h"
#include "evaluate/mesh_checks.h"
#include "evaluate/mesh_distance.h"
#include "evaluate/normals.h"

#include <initializer_list>
#include <iomanip>
#include <sstream>
#include <utility>

namespace mg::evaluate::cli {
namespace {

/// Labelled lengths for text reports, each with its percentage of the diagonal:
/// "max 0.01 (0.5 %), RMS 0.002 (0.1 %)".
std::string lengths_text(std::initializer_list<std::pair<const char*, double>> lengths,
                         double diagonal) {
  std::ostringstream s;
  s << std::setprecision(6);
  const char* separator = "";
  for (const auto& [label, value] : lengths) {
    s << separator << label << ' ' << value << " (" << percent_of_diagonal(value, diagonal)
      << " %)";
    separator = ", ";
  }
  return s.str();
}

Json one_sided_json(const OneSidedDistance& d, double diagonal) {
  return Json{{"max", d.max},
              {"max_pct", percent_of_diagonal(d.max, diagonal)},
              {"mean", d.mean},
              {"mean_pct", percent_of_diagonal(d.mean, diagonal)},
              {"rms", d.rms},
              {"rms_pct", percent_of_diagonal(d.rms, diagonal)},
              {"samples", d.samples},
              {"weighted_samples", d.weighted_samples},
              {"farthest", {d.farthest.x(), d.farthest.y(), d.farthest.z()}}};
}

/// The keys distance and atoms share: the diagonal, the two-sided values with their
/// percentages, then each side under its name.
void add_two_sided_json(Json& j, const TwoSidedDistance& d, double diagonal, const char* a_to_b_key,
                        const char* b_to_a_key) {
  j["diagonal"] = diagonal;
  j["hausdorff"] = d.hausdorff;
  j["hausdorff_pct"] = percent_of_diagonal(d.hausdorff, diagonal);
  j["rms"] = d.rms;
  j["rms_pct"] = percent_of_diagonal(d.rms, diagonal);
  j["mean"] = d.mean;
  j["mean_pct"] = percent_of_diagonal(d.mean, diagonal);
  j[a_to_b_key] = one_sided_json(d.a_to_b, diagonal);
  j[b_to_a_key] = one_sided_json(d.b_to_a, diagonal);
}

/// What distance and normals say of themselves in --help.
struct MeshPairHelp {
  const char* name;
  const char* description;
  const char* reference;  ///< of REFERENCE
  const char* samples;    ///< of --samples
  const char* flag;       ///< the sub-command's one flag, and its help
  const char* flag_help;
};

/// distance or normals: MESH, REFERENCE, --samples, --seed, the flag, --json and --stats.
CLI::App* add_mesh_pair(CLI::App& app, const MeshPairHelp& help, MeshPairArgs& args, bool& flag) {
  auto* sub = app.add_subcommand(help.name, help.description);
  sub->add_option("mesh", args.mesh, "mesh to judge")->required();
  sub->add_option("reference", args.reference, help.reference)->required();
  sub->add_option("--samples", args.samples, help.samples);
  sub->add_option("--seed", args.seed, "random seed of the sampling");
  sub->add_flag(help.flag, flag, help.flag_help);
  add_report_options(*sub, args.report);
  return sub;
}

/// distance and normals: reads MESH and REFERENCE once --stats is known to overwrite neither
/// (REFERENCE first: when both are unreadable, the message names REFERENCE), then measures
/// MESH against REFERENCE with --samples and --seed set in `opt`.
/// @return the measure and the seconds from reading to it
template <class Result, class Options>
std::pair<Result, double> measure_pair(const MeshPairArgs& args, Options opt,
                                       Result (*measure)(const PolygonSoup&, const PolygonSoup&,
                                                         const Options&, const std::string&,
                                                         const std::string&)) {
  opt.samples = args.samples;
  opt.seed = args.seed;
  const Stopwatch clock;
  check_report_path(args.report, {args.mesh, args.reference});
  const PolygonSoup ref = read_polygon_soup(args.reference);
  const PolygonSoup mesh = read_polygon_soup(args.mesh);
  Result result = measure(mesh, ref, opt, args.mesh, args.reference);
  return {std::move(result), clock.seconds()};
}

}  // namespace

// --- distance --------------------------------------------------------------------------------

CLI::App* add_distance(CLI::App& app, DistanceArgs& args) {
  return add_mesh_pair(
      app,
      {"distance", "two-sided Hausdorff, RMS and mean distance between MESH and REFERENCE",
       "reference mesh (its diagonal gives the %)",
       "samples per side (0 = max(1e6, 10 (V_mesh + V_reference)))", "--faces-only",
       "sample faces only (as MeshLab with only \"Sample Faces\"); default: "
       "vertices, edge points and face points (Metro)"},
      args.pair, args.faces_only);
}

int run_distance(const DistanceArgs& args) {
  const MeshPairArgs& p = args.pair;
  MeshDistanceOptions opt;
  opt.vertices_and_edges = !args.faces_only;
  const auto [r, seconds] = measure_pair(p, opt, mesh_distance);
  const double diag = r.diagonal;
  const TwoSidedDistance& d = r.distance;

  Json j = {{"mesh", p.mesh},
            {"reference", p.reference},
            {"samples", r.samples},
            {"sampling", args.faces_only ? "faces" : "metro"},
            {"seed", p.seed}};
  add_two_sided_json(j, d, diag, "mesh_to_reference", "reference_to_mesh");
  j["seconds"] = seconds;

  std::ostringstream text;
  text << "mesh -> reference: "
       << lengths_text({{"max", d.a_to_b.max}, {"mean", d.a_to_b.mean}, {"RMS", d.a_to_b.rms}},
                       diag)
       << "\nreference -> mesh: "
       << lengths_text({{"max", d.b_to_a.max}, {"mean", d.b_to_a.mean}, {"RMS", d.b_to_a.rms}},
                       diag)
       << '\n'
       << lengths_text({{"Hausdorff", d.hausdorff}, {"RMS", d.rms}, {"mean", d.mean}}, diag)
       << "\n(% of the reference's bounding-box diagonal " << std::setprecision(6) << diag << "; "
       << r.samples << " samples per side, " << (args.faces_only ? "faces" : "Metro")
       << " sampling, seed " << p.seed << ", " << std::setprecision(3) << seconds << " s)\n";
  emit_report(p.report, j, text.str());
  return 0;
}

// --- atoms -----------------------------------------------------------------------------------

CLI::App* add_atoms(CLI::App& app, AtomsArgs& args) {
  auto* sub = app.add_subcommand(
      "atoms",
      "two-sided distances between MESH and G: the union of the atoms' spheres and cones, or a "
      "medial mesh's envelope");
  sub->add_option("mesh", args.mesh, "mesh to judge")->required();
  sub->add_option("atoms", args.atoms, "medial atoms (.ma, or x y z r lines)")->required();
  sub->add_option("--primitives", args.primitives, "G's primitives: auto, ma or rt (as garb)")
      ->check(CLI::IsMember({"auto", "ma", "rt"}));
  const auto given = [&args](const std::string&) { args.cone_options_given = true; };
  sub->add_option("--cones", args.cones, "cone pairs of G: rt, all, edges or none (as garb)")
      ->check(CLI::IsMember({"rt", "all", "edges", "none"}))
      ->each(given);
  sub->add_option("--cone-filter", args.cone_filter, "as garb --cone-filter")
      ->check(CLI::Range(0.0, 1.0))
      ->each(given);
  sub->add_option("--cone-collar", args.cone_collar, "as garb --cone-collar")
      ->check(NonNegative)
      ->each(given);
  sub->add_option("--samples", args.samples, "samples per side (0 = max(1e5, 10 V_mesh))");
  sub->add_option("--seed", args.seed, "random seed of the sampling");
  sub->add_option("--diagonal", args.diagonal,
                  "diagonal for the percentages, model units (0 = MESH's bounding box)")
      ->check(NonNegative);
  add_report_options(*sub, args.report);
  return sub;
}

int run_atoms(const AtomsArgs& args) {
  const Stopwatch clock;  // from reading to the result
  check_report_path(args.report, {args.mesh, args.atoms});
  const PolygonSoup mesh = read_polygon_soup(args.mesh);
  const MedialSurface atoms = read_medial_surface(args.atoms);
  AtomsDistanceOptions opt;
  opt.primitives = garbing::parse_primitive_set(args.primitives);
  if (args.cone_options_given && opt.primitives == garbing::PrimitiveSet::envelope)
    throw InvalidInput(
        "--cones, --cone-filter and --cone-collar choose the cones of --primitives "
        "rt, not ma");
  if (args.cone_options_given) opt.primitives = garbing::PrimitiveSet::atoms;
  opt.cones.source = garbing::parse_cone_source(args.cones);
  opt.cones.min_circle_ratio = args.cone_filter;
  opt.cones.max_collar = args.cone_collar;
  opt.samples = args.samples;
  opt.seed = args.seed;
  const AtomsDistance r = atoms_distance(mesh, atoms, opt, args.mesh);
  const double seconds = clock.seconds();
  const double diag = args.diagonal > 0 ? args.diagonal : r.diagonal;
  const TwoSidedDistance& d = r.distance;

  Json j = {{"mesh", args.mesh},
            {"atoms", args.atoms},
            {"primitives", r.envelope ? "ma" : "rt"},
            {"cones", r.cones},
            {"slabs", r.slabs},
            {"cone_source", args.cones},
            {"cone_filter", args.cone_filter},
            {"cone_collar", args.cone_collar},
            {"mesh_samples", r.mesh_samples},
            {"g_samples", r.g_samples},
            {"g_area_uniform_samples", r.g_unbiased},
            {"seed", args.seed}};
  add_two_sided_json(j, d, diag, "mesh_to_g", "g_to_mesh");
  j["seconds"] = seconds;

  std::ostringstream text;
  text << "mesh -> G: " << lengths_text({{"max", d.a_to_b.max}, {"RMS", d.a_to_b.rms}}, diag)
       << "\nG -> mesh: " << lengths_text({{"max", d.b_to_a.max}, {"RMS", d.b_to_a.rms}}, diag)
       << '\n'
       << lengths_text({{"Hausdorff", d.hausdorff}, {"RMS", d.rms}}, diag)
       << "\n(G: " << atoms.atoms.size() << " spheres, " << r.cones << " cones, " << r.slabs
       << " slabs; " << r.mesh_samples << " mesh samples, " << r.g_samples << " samples of G; "
       << std::setprecision(3) << seconds << " s)\n";
  emit_report(args.report, j, text.str());
  return 0;
}

// --- normals ---------------------------------------------------------------------------------

CLI::App* add_normals(CLI::App& app, NormalsArgs& args) {
  return add_mesh_pair(
      app,
      {"normals", "angle between MESH's facet normals and REFERENCE's normal at the closest point",
       "reference mesh", "area-uniform samples on MESH (0 = max(1e6, 10 (V_mesh + V_reference)))",
       "--flat-reference",
       "use REFERENCE's facet normals instead of its interpolated vertex normals"},
      args.pair, args.flat_reference);
}

int run_normals(const NormalsArgs& args) {
  const MeshPairArgs& p = args.pair;
  NormalOptions opt;
  opt.smooth_reference = !args.flat_reference;
  const auto [r, seconds] = measure_pair(p, opt, normal_deviation);
  const char* normals = args.flat_reference ? "flat" : "smooth";
  const Json j = {
      {"mesh", p.mesh},         {"reference", p.reference}, {"reference_normals", normals},
      {"samples", r.samples},   {"skipped", r.skipped},     {"seed", p.seed},
      {"mean_deg", r.mean_deg}, {"p95_deg", r.p95_deg},     {"max_deg", r.max_deg},
      {"seconds", seconds}};
  std::ostringstream text;
  text << std::setprecision(4) << "normal deviation: mean " << r.mean_deg
       << " deg, 95th percentile " << r.p95_deg << " deg, max " << r.max_deg << " deg ("
       << r.samples << " area-uniform samples, " << normals << " reference normals)\n";
  emit_report(p.report, j, text.str());
  return 0;
}

// --- check -----------------------------------------------------------------------------------

CLI::App* add_check(CLI::App& app, CheckArgs& args) {
  auto* sub = app.add_subcommand(
      "check", "closed, 2-manifold, oriented, genus, self-intersections, degenerate triangles");
  sub->add_option("mesh", args.mesh, "mesh file, read as a polygon soup")->required();
  add_report_options(*sub, args.report);
  return sub;
}

int run_check(const CheckArgs& args) {
  check_report_path(args.report, {args.mesh});
  const PolygonSoup soup = read_polygon_soup(args.mesh);
  const MeshCheck c = check_mesh(soup);
  const MeshTopology& t = c.topology;
  Json valence = Json::object();
  for (const auto& [k, n] : c.valence_histogram) valence[std::to_string(k)] = n;
  Json j = {{"file", args.mesh},
            {"vertices", t.vertices},
            {"faces", t.faces},
            {"edges", t.edges},
            {"triangles", c.triangles},
            {"non_triangle_faces", c.non_triangle_faces},
            {"closed", t.closed},
            {"boundary_edges", t.boundary_edges},
            {"manifold", t.manifold},
            {"nonmanifold_edges", t.nonmanifold_edges},
            {"nonmanifold_vertices", t.nonmanifold_vertices},
            {"oriented", t.oriented},
            {"misoriented_edges", t.misoriented_edges},
            {"components", t.components},
            {"euler", t.euler},
            {"genus", t.genus},
            {"intersecting_pairs", c.intersecting_pairs},
            {"degenerate_triangles", c.degenerate_triangles},
            {"min_angle_deg", c.min_angle_deg},
            {"valence_histogram", valence},
            {"bbox_diagonal", bbox_diagonal(soup.points)}};
  if (!t.first_problem.empty()) j["first_problem"] = t.first_problem;
  if (!c.first_intersection.empty()) j["first_intersection"] = c.first_intersection;
  if (!c.first_degenerate.empty()) j["first_degenerate"] = c.first_degenerate;

  auto yes = [](bool b) { return b ? "yes" : "no"; };
  std::ostringstream text;
  text << args.mesh << ": V " << t.vertices << ", F " << t.faces << ", E " << t.edges
       << "\n  closed " << yes(t.closed) << " (" << t.boundary_edges << " boundary edges)"
       << ", 2-manifold " << yes(t.manifold) << " (" << t.nonmanifold_edges
       << " non-manifold edges, " << t.nonmanifold_vertices << " non-manifold vertices)"
       << ", oriented " << yes(t.oriented) << "\n  components " << t.components << ", euler "
       << t.euler << ", genus " << t.genus << "\n  intersecting face pairs " << c.intersecting_pairs
       << ", degenerate triangles " << c.degenerate_triangles << ", minimum angle "
       << std::setprecision(4) << c.min_angle_deg << " deg\n  valence:";
  for (const auto& [k, n] : c.valence_histogram) text << ' ' << k << ':' << n;
  text << '\n';
  for (const std::string* s : {&t.first_problem, &c.first_intersection, &c.first_degenerate})
    if (!s->empty()) text << "  " << *s << '\n';
  emit_report(args.report, j, text.str());
  return 0;
}

}  // namespace mg::evaluate::cli
