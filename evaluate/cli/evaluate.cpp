// evaluate: distances, smoothness and validity checks, timed baselines.
//   evaluate distance MESH REFERENCE [--samples N] [--seed S] [--faces-only] [--json]
//   evaluate atoms MESH ATOMS.ma [--cones rt|all|edges|none] [--cone-filter F] [--cone-collar C] [--samples N]
//                  [--seed S] [--diagonal D] [--json]
//   evaluate normals MESH REFERENCE [--samples N] [--seed S] [--flat-reference] [--json]
//   evaluate check MESH [--json]
//   evaluate skin INPUT.ma -o OUT [--shrink F] [--subdivisions K] [--repeat K] [--json]
//   evaluate union INPUT.ma -o OUT [--subdivisions K] [--repeat K] [--json]
//   evaluate vdb INPUT.ma -o OUT [--voxel H | --match-vertices N | --match-hausdorff P REF]
//                [--samples N] [--repeat K] [--json]
// Every sub-command also takes --stats FILE (the JSON report, written atomically); --threads N
// limits the worker threads.
#include "evaluate/atoms_distance.h"
#include "evaluate/baselines.h"
#include "evaluate/mesh_checks.h"
#include "evaluate/mesh_distance.h"
#include "evaluate/normals.h"
#include "evaluate/timing.h"
#include "evaluate/vdb_mesh.h"
#include "core/atomic_file.h"
#include "core/cli_main.h"
#include "core/medial_surface.h"
#include "core/mesh_io.h"

#include <tbb/global_control.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace {

namespace ev = mg::evaluate;
using Json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// What every sub-command shares: --json (report on stdout) and --stats FILE.
struct Report {
  bool json = false;
  std::string stats;

  void add_options(CLI::App* sub) {
    sub->add_flag("--json", json, "print the report as JSON");
    sub->add_option("--stats", stats, "also write the JSON report to this file");
  }
  /// Refuses a stats path that would overwrite an input, before any work.
  void check(const std::vector<std::string>& inputs) const {
    if (!stats.empty()) mg::check_output_path(stats, inputs);
  }
  void emit(const Json& j, const std::string& text) const {
    if (!stats.empty())
      mg::write_file_atomically(stats,
                                [&j](std::ostream& out) { out << std::setw(2) << j << '\n'; });
    if (json)
      std::cout << std::setw(2) << j << '\n';
    else
      std::cout << text;
  }
};

/// A length with its percentage of the diagonal, for text reports.
std::string length_text(double value, double diagonal) {
  std::ostringstream s;
  s << std::setprecision(6) << value << " (" << ev::percent_of_diagonal(value, diagonal) << " %)";
  return s.str();
}

Json one_sided_json(const ev::OneSidedDistance& d, double diagonal) {
  return Json{{"max", d.max},
              {"max_pct", ev::percent_of_diagonal(d.max, diagonal)},
              {"mean", d.mean},
              {"mean_pct", ev::percent_of_diagonal(d.mean, diagonal)},
              {"rms", d.rms},
              {"rms_pct", ev::percent_of_diagonal(d.rms, diagonal)},
              {"samples", d.samples},
              {"weighted_samples", d.weighted_samples},
              {"farthest", {d.farthest.x(), d.farthest.y(), d.farthest.z()}}};
}

Json timing_json(const ev::StageTiming& t) {
  return Json{{"min", t.min}, {"median", t.median}, {"max", t.max}, {"runs", t.seconds}};
}

std::string timing_text(const ev::StageTiming& t) {
  std::ostringstream s;
  s << std::setprecision(4);
  if (t.seconds.size() == 1)
    s << t.min << " s";
  else
    s << "min " << t.min << " s, median " << t.median << " s, max " << t.max << " s over "
      << t.seconds.size() << " runs";
  return s.str();
}

void check_mesh_output(const std::string& output, const std::vector<std::string>& inputs) {
  mg::check_output_path(output, inputs);
  if (!mg::has_mesh_extension(output))
    throw mg::InvalidInput(output + ": unknown mesh extension (expected .off, .obj, .ply or .stl)");
}

Json mesh_size_json(const mg::PolygonSoup& soup) {
  return Json{{"vertices", soup.points.size()}, {"faces", soup.faces.size()}};
}

std::string mesh_size_text(const mg::PolygonSoup& soup) {
  return "V " + std::to_string(soup.points.size()) + ", F " + std::to_string(soup.faces.size());
}

int evaluate_main(int argc, char** argv) {
  CLI::App app{
      "Distances (Metro-style Hausdorff, RMS, mean), normal deviation, mesh checks, "
      "and the timed baselines (CGAL skin surface, union of balls, OpenVDB)."};
  app.option_defaults()->always_capture_default();
  app.require_subcommand(1);
  app.fallthrough();
  int threads = 0;
  app.add_option("--threads", threads, "worker threads (0 = all cores)")
      ->check(mg::NonNegative);

  // distance
  auto* distance = app.add_subcommand(
      "distance", "two-sided Hausdorff, RMS and mean distance between MESH and REFERENCE");
  std::string mesh_path, ref_path;
  std::size_t samples = 0;
  std::uint64_t seed = 1;
  bool faces_only = false;
  Report distance_report;
  distance->add_option("mesh", mesh_path, "mesh to judge")->required();
  distance->add_option("reference", ref_path, "reference mesh (its diagonal gives the %)")
      ->required();
  distance->add_option("--samples", samples,
                       "samples per side (0 = max(1e6, 10 (V_mesh + V_reference)))");
  distance->add_option("--seed", seed, "random seed of the sampling");
  distance->add_flag("--faces-only", faces_only,
                     "sample faces only (as MeshLab with only \"Sample Faces\"); default: "
                     "vertices, edge points and face points (Metro)");
  distance_report.add_options(distance);

  // atoms
  auto* atoms_cmd = app.add_subcommand(
      "atoms", "two-sided distances between MESH and G, the union of the atoms' spheres and cones");
  std::string atoms_file, cones = "rt";
  double cone_filter = mg::garbing::ConeOptions{}.min_circle_ratio, cone_collar = mg::garbing::ConeOptions{}.max_collar,
         diagonal = 0;
  Report atoms_report;
  atoms_cmd->add_option("mesh", mesh_path, "mesh to judge")->required();
  atoms_cmd->add_option("atoms", atoms_file, "medial atoms (.ma, or x y z r lines)")->required();
  atoms_cmd->add_option("--cones", cones, "cone pairs of G: rt, all, edges or none (as garb)")
      ->check(CLI::IsMember({"rt", "all", "edges", "none"}));
  atoms_cmd->add_option("--cone-filter", cone_filter, "as garb --cone-filter")->check(CLI::Range(0.0, 1.0));
  atoms_cmd->add_option("--cone-collar", cone_collar, "as garb --cone-collar")->check(mg::NonNegative);
  atoms_cmd->add_option("--samples", samples, "samples per side (0 = max(1e5, 10 V_mesh))");
  atoms_cmd->add_option("--seed", seed, "random seed of the sampling");
  atoms_cmd->add_option("--diagonal", diagonal,
                        "diagonal for the percentages, model units (0 = MESH's bounding box)")
      ->check(mg::NonNegative);
  atoms_report.add_options(atoms_cmd);

  // normals
  auto* normals = app.add_subcommand(
      "normals", "angle between MESH's facet normals and REFERENCE's normal at the closest point");
  bool flat_reference = false;
  Report normals_report;
  normals->add_option("mesh", mesh_path, "mesh to judge")->required();
  normals->add_option("reference", ref_path, "reference mesh")->required();
  normals->add_option("--samples", samples,
                      "area-uniform samples on MESH (0 = max(1e6, 10 (V_mesh + V_reference)))");
  normals->add_option("--seed", seed, "random seed of the sampling");
  normals->add_flag("--flat-reference", flat_reference,
                    "use REFERENCE's facet normals instead of its interpolated vertex normals");
  normals_report.add_options(normals);

  // check
  auto* check = app.add_subcommand(
      "check", "closed, 2-manifold, oriented, genus, self-intersections, degenerate triangles");
  Report check_report;
  check->add_option("mesh", mesh_path, "mesh file, read as a polygon soup")->required();
  check_report.add_options(check);

  // skin, union, vdb
  std::string atoms_path, output;
  int subdivisions = 0, repeat = 1;
  ev::SkinOptions skin_opt;
  auto add_baseline = [&](const std::string& name, const std::string& what) {
    auto* sub = app.add_subcommand(name, what);
    sub->add_option("input", atoms_path, "medial atoms (.ma, or x y z r lines)")->required();
    sub->add_option("-o,--output", output, "output mesh (.off .obj .ply .stl)")->required();
    sub->add_option("--repeat", repeat, "time the algorithm over K runs (min, median, max)")
        ->check(mg::Positive);
    return sub;
  };
  auto* skin = add_baseline("skin", "CGAL skin surface of the atoms (make_skin_surface_mesh_3)");
  Report skin_report;
  skin->add_option("--shrink", skin_opt.shrink, "shrink factor, in (0, 1)");
  skin->add_option("--subdivisions", subdivisions, "CGAL refinement rounds");
  skin_report.add_options(skin);

  auto* onion =
      add_baseline("union", "CGAL union of balls (Union_of_balls_3 + mesh_union_of_balls_3)");
  Report union_report;
  onion->add_option("--subdivisions", subdivisions, "CGAL refinement rounds");
  union_report.add_options(onion);

  auto* vdb = add_baseline("vdb", "OpenVDB level set of the spheres, meshed (volumeToMesh)");
  Report vdb_report;
  double voxel = 0;
  std::size_t match_vertices = 0;
  std::vector<std::string> match_hausdorff;
  auto* voxel_opt =
      vdb->add_option("--voxel", voxel, "voxel size, model units (0 = diagonal / 400)");
  auto* mv_opt = vdb->add_option("--match-vertices", match_vertices,
                                 "search the voxel giving about N vertices (at most 5 probes)");
  auto* mh_opt =
      vdb->add_option("--match-hausdorff", match_hausdorff,
                      "P REF: search the voxel giving a Hausdorff distance to REF of P % "
                      "of REF's diagonal (at most 5 probes)")
          ->expected(2);
  vdb->add_option("--samples", samples,
                  "--match-hausdorff: samples per side (0 = default; raised to twice the larger "
                  "vertex count when below it)");
  voxel_opt->excludes(mv_opt)->excludes(mh_opt);
  mv_opt->excludes(mh_opt);
  vdb_report.add_options(vdb);

  mg::parse_command_line(app, argc, argv);

  std::unique_ptr<tbb::global_control> limit;
  if (threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                  static_cast<std::size_t>(threads));

  // distance and normals: MESH and REFERENCE, timed from reading to the result.
  const auto t0 = Clock::now();
  auto read_pair = [&](const Report& report) {
    report.check({mesh_path, ref_path});
    return std::make_pair(mg::read_polygon_soup(mesh_path), mg::read_polygon_soup(ref_path));
  };

  if (*distance) {
    const auto [mesh, ref] = read_pair(distance_report);
    ev::MeshDistanceOptions opt;
    opt.samples = samples;
    opt.seed = seed;
    opt.vertices_and_edges = !faces_only;
    const ev::MeshDistance r = ev::mesh_distance(mesh, ref, opt, mesh_path, ref_path);
    const double seconds = seconds_since(t0);
    const double diag = r.diagonal;
    const auto& d = r.distance;
    Json j;
    j["mesh"] = mesh_path;
    j["reference"] = ref_path;
    j["samples"] = r.samples;
    j["sampling"] = faces_only ? "faces" : "metro";
    j["seed"] = seed;
    j["diagonal"] = diag;
    j["hausdorff"] = d.hausdorff;
    j["hausdorff_pct"] = ev::percent_of_diagonal(d.hausdorff, diag);
    j["rms"] = d.rms;
    j["rms_pct"] = ev::percent_of_diagonal(d.rms, diag);
    j["mean"] = d.mean;
    j["mean_pct"] = ev::percent_of_diagonal(d.mean, diag);
    j["mesh_to_reference"] = one_sided_json(d.a_to_b, diag);
    j["reference_to_mesh"] = one_sided_json(d.b_to_a, diag);
    j["seconds"] = seconds;
    std::ostringstream text;
    text << "mesh -> reference: max " << length_text(d.a_to_b.max, diag) << ", mean "
         << length_text(d.a_to_b.mean, diag) << ", RMS " << length_text(d.a_to_b.rms, diag)
         << "\nreference -> mesh: max " << length_text(d.b_to_a.max, diag) << ", mean "
         << length_text(d.b_to_a.mean, diag) << ", RMS " << length_text(d.b_to_a.rms, diag)
         << "\nHausdorff " << length_text(d.hausdorff, diag) << ", RMS " << length_text(d.rms, diag)
         << ", mean " << length_text(d.mean, diag)
         << "\n(% of the reference's bounding-box diagonal " << std::setprecision(6) << diag << "; "
         << r.samples << " samples per side, " << (faces_only ? "faces" : "Metro")
         << " sampling, seed " << seed << ", " << std::setprecision(3) << seconds << " s)\n";
    distance_report.emit(j, text.str());
    return 0;
  }

  if (*atoms_cmd) {
    atoms_report.check({mesh_path, atoms_file});
    const mg::PolygonSoup mesh = mg::read_polygon_soup(mesh_path);
    const mg::MedialSurface atoms = mg::read_medial_surface(atoms_file);
    ev::AtomsDistanceOptions opt;
    opt.cones.source = mg::garbing::parse_cone_source(cones);
    opt.cones.min_circle_ratio = cone_filter;
    opt.cones.max_collar = cone_collar;
    opt.samples = samples;
    opt.seed = seed;
    const ev::AtomsDistance r = ev::atoms_distance(mesh, atoms, opt, mesh_path);
    const double seconds = seconds_since(t0);
    const double diag = diagonal > 0 ? diagonal : r.diagonal;
    const auto& d = r.distance;
    Json j;
    j["mesh"] = mesh_path;
    j["atoms"] = atoms_file;
    j["cones"] = r.cones;
    j["cone_source"] = cones;
    j["cone_filter"] = cone_filter;
    j["cone_collar"] = cone_collar;
    j["mesh_samples"] = r.mesh_samples;
    j["g_samples"] = r.g_samples;
    j["g_area_uniform_samples"] = r.g_unbiased;
    j["seed"] = seed;
    j["diagonal"] = diag;
    j["hausdorff"] = d.hausdorff;
    j["hausdorff_pct"] = ev::percent_of_diagonal(d.hausdorff, diag);
    j["rms"] = d.rms;
    j["rms_pct"] = ev::percent_of_diagonal(d.rms, diag);
    j["mean"] = d.mean;
    j["mean_pct"] = ev::percent_of_diagonal(d.mean, diag);
    j["mesh_to_g"] = one_sided_json(d.a_to_b, diag);
    j["g_to_mesh"] = one_sided_json(d.b_to_a, diag);
    j["seconds"] = seconds;
    std::ostringstream text;
    text << "mesh -> G: max " << length_text(d.a_to_b.max, diag) << ", RMS " << length_text(d.a_to_b.rms, diag)
         << "\nG -> mesh: max " << length_text(d.b_to_a.max, diag) << ", RMS " << length_text(d.b_to_a.rms, diag)
         << "\nHausdorff " << length_text(d.hausdorff, diag) << ", RMS " << length_text(d.rms, diag)
         << "\n(G: " << atoms.atoms.size() << " spheres, " << r.cones << " cones; " << r.mesh_samples
         << " mesh samples, " << r.g_samples << " samples of G; " << std::setprecision(3) << seconds << " s)\n";
    atoms_report.emit(j, text.str());
    return 0;
  }

  if (*normals) {
    const auto [mesh, ref] = read_pair(normals_report);
    ev::NormalOptions opt;
    opt.samples = samples;
    opt.seed = seed;
    opt.smooth_reference = !flat_reference;
    const ev::NormalDeviation r = ev::normal_deviation(mesh, ref, opt, mesh_path, ref_path);
    const double seconds = seconds_since(t0);
    Json j;
    j["mesh"] = mesh_path;
    j["reference"] = ref_path;
    j["reference_normals"] = flat_reference ? "flat" : "smooth";
    j["samples"] = r.samples;
    j["skipped"] = r.skipped;
    j["seed"] = seed;
    j["mean_deg"] = r.mean_deg;
    j["p95_deg"] = r.p95_deg;
    j["max_deg"] = r.max_deg;
    j["seconds"] = seconds;
    std::ostringstream text;
    text << std::setprecision(4) << "normal deviation: mean " << r.mean_deg
         << " deg, 95th percentile " << r.p95_deg << " deg, max " << r.max_deg << " deg ("
         << r.samples << " area-uniform samples, " << (flat_reference ? "flat" : "smooth")
         << " reference normals)\n";
    normals_report.emit(j, text.str());
    return 0;
  }

  if (*check) {
    check_report.check({mesh_path});
    const mg::PolygonSoup soup = mg::read_polygon_soup(mesh_path);
    const ev::MeshCheck c = ev::check_mesh(soup);
    const mg::MeshTopology& t = c.topology;
    Json valence = Json::object();
    for (const auto& [k, n] : c.valence_histogram) valence[std::to_string(k)] = n;
    Json j;
    j["file"] = mesh_path;
    j["vertices"] = t.vertices;
    j["faces"] = t.faces;
    j["edges"] = t.edges;
    j["triangles"] = c.triangles;
    j["non_triangle_faces"] = c.non_triangle_faces;
    j["closed"] = t.closed;
    j["boundary_edges"] = t.boundary_edges;
    j["manifold"] = t.manifold;
    j["nonmanifold_edges"] = t.nonmanifold_edges;
    j["nonmanifold_vertices"] = t.nonmanifold_vertices;
    j["oriented"] = t.oriented;
    j["misoriented_edges"] = t.misoriented_edges;
    j["components"] = t.components;
    j["euler"] = t.euler;
    j["genus"] = t.genus;
    j["intersecting_pairs"] = c.intersecting_pairs;
    j["degenerate_triangles"] = c.degenerate_triangles;
    j["min_angle_deg"] = c.min_angle_deg;
    j["valence_histogram"] = valence;
    j["bbox_diagonal"] = mg::bbox_diagonal(soup.points);
    if (!t.first_problem.empty()) j["first_problem"] = t.first_problem;
    if (!c.first_intersection.empty()) j["first_intersection"] = c.first_intersection;
    if (!c.first_degenerate.empty()) j["first_degenerate"] = c.first_degenerate;
    auto yes = [](bool b) { return b ? "yes" : "no"; };
    std::ostringstream text;
    text << mesh_path << ": V " << t.vertices << ", F " << t.faces << ", E " << t.edges
         << "\n  closed " << yes(t.closed) << " (" << t.boundary_edges << " boundary edges)"
         << ", 2-manifold " << yes(t.manifold) << " (" << t.nonmanifold_edges
         << " non-manifold edges, " << t.nonmanifold_vertices << " non-manifold vertices)"
         << ", oriented " << yes(t.oriented) << "\n  components " << t.components << ", euler "
         << t.euler << ", genus " << t.genus << "\n  intersecting face pairs "
         << c.intersecting_pairs << ", degenerate triangles " << c.degenerate_triangles
         << ", minimum angle " << std::setprecision(4) << c.min_angle_deg << " deg\n  valence:";
    for (const auto& [k, n] : c.valence_histogram) text << ' ' << k << ':' << n;
    text << '\n';
    for (const std::string* s : {&t.first_problem, &c.first_intersection, &c.first_degenerate})
      if (!s->empty()) text << "  " << *s << '\n';
    check_report.emit(j, text.str());
    return 0;
  }

  // Baselines: atoms in, mesh out, timed without file input/output.
  const std::vector<std::string> inputs = {atoms_path};
  check_mesh_output(output, inputs);
  for (const Report* r : {&skin_report, &union_report, &vdb_report})
    if (!r->stats.empty() &&
        std::filesystem::weakly_canonical(r->stats) == std::filesystem::weakly_canonical(output))
      throw mg::InvalidInput(r->stats + ": --stats and --output name the same file");
  Json j;
  std::ostringstream text;
  mg::PolygonSoup result;
  if (*skin || *onion) {
    (*skin ? skin_report : union_report).check(inputs);
    const mg::MedialSurface atoms = mg::read_medial_surface(atoms_path);
    skin_opt.subdivisions = subdivisions;
    const ev::StageTiming t = ev::time_stage(repeat, [&] {
      result = *skin ? ev::skin_surface_mesh(atoms, skin_opt)
                     : ev::union_of_balls_mesh(atoms, subdivisions);
    });
    j["method"] = *skin ? "cgal_skin_surface" : "cgal_union_of_balls";
    j["input"] = atoms_path;
    j["output"] = output;
    j["atoms"] = atoms.atoms.size();
    if (*skin) j["shrink"] = skin_opt.shrink;
    j["subdivisions"] = subdivisions;
    j.update(mesh_size_json(result));
    j["seconds"] = timing_json(t);
    text << (*skin ? "skin surface" : "union of balls") << ": " << mesh_size_text(result) << ", "
         << timing_text(t) << '\n';
  } else {
    std::vector<std::string> vdb_inputs = inputs;
    std::string match_ref;
    double match_pct = 0;
    if (!match_hausdorff.empty()) {
      std::istringstream p(match_hausdorff[0]);
      if (!(p >> match_pct) || !p.eof())
        throw mg::InvalidInput("--match-hausdorff: '" + match_hausdorff[0] +
                               "' is not a percentage");
      match_ref = match_hausdorff[1];
      vdb_inputs.push_back(match_ref);
      check_mesh_output(output, vdb_inputs);
    }
    vdb_report.check(vdb_inputs);
    const mg::MedialSurface atoms = mg::read_medial_surface(atoms_path);
    ev::VdbOptions opt;
    opt.voxel = voxel;
    Json probes = Json::array();
    bool clamped = false;
    if (match_vertices > 0 || !match_ref.empty()) {
      ev::VdbMatch m;
      if (match_vertices > 0) {
        m = ev::vdb_match_vertices(atoms, match_vertices);
      } else {
        const mg::PolygonSoup ref = mg::read_polygon_soup(match_ref);
        ev::MeshDistanceOptions dopt;
        dopt.samples = samples;
        m = ev::vdb_match_hausdorff(atoms, match_pct, ref, dopt, match_ref);
      }
      for (const auto& p : m.probes)
        probes.push_back({{"voxel", p.voxel}, {"value", p.value}, {"vertices", p.vertices}});
      clamped = m.clamped;
      opt.voxel = m.best.voxel;
      j["match"] = match_vertices > 0 ? "vertices" : "hausdorff_pct";
      j["target"] = match_vertices > 0 ? static_cast<double>(match_vertices) : match_pct;
      j["matched"] = m.value;
      if (!match_ref.empty()) j["reference"] = match_ref;
    }
    ev::VdbMesh mesh;
    const ev::StageTiming t = ev::time_stage(repeat, [&] { mesh = ev::vdb_mesh(atoms, opt); });
    result = std::move(mesh.mesh);
    j["method"] = "openvdb";
    j["input"] = atoms_path;
    j["output"] = output;
    j["atoms"] = atoms.atoms.size();
    j["voxel"] = mesh.voxel;
    j["dropped_spheres"] = mesh.dropped_spheres;
    j["quads"] = mesh.quads;
    if (!probes.empty()) {
      j["probes"] = probes;
      j["clamped"] = clamped;
    }
    j.update(mesh_size_json(result));
    j["seconds"] = timing_json(t);
    text << "OpenVDB: " << mesh_size_text(result) << ", voxel " << std::setprecision(6)
         << mesh.voxel << ", " << mesh.dropped_spheres << " spheres under 1.5 voxels dropped, "
         << timing_text(t) << '\n';
    if (!probes.empty())
      text << "  voxel search: " << probes.size() << " probes, matched " << j["matched"].dump()
           << " for a target of " << j["target"].dump() << (clamped ? " (voxel clamped)" : "")
           << '\n';
  }
  mg::write_polygon_soup(result, output);
  (*skin ? skin_report : *onion ? union_report : vdb_report).emit(j, text.str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return mg::run_cli("evaluate", [&] { return evaluate_main(argc, argv); });
}
