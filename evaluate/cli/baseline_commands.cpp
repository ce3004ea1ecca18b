// evaluate skin, union and vdb: the timed baselines. Atoms in, a mesh out; the algorithm is
// timed without file input/output.
#include "commands.h"

#include "core/medial_surface.h"
#include "core/mesh_io.h"
#include "core/timer.h"
#include "evaluate/atoms_distance.h"
#include "evaluate/mesh_distance.h"
#include "evaluate/timing.h"
#include "evaluate/vdb_mesh.h"

#include <functional>
#include <iomanip>
#include <sstream>
#include <utility>

namespace mg::evaluate::cli {
namespace {

/// A sub-command with the options every baseline has: input, -o, --repeat.
CLI::App* add_baseline(CLI::App& app, const std::string& name, const std::string& description,
                       BaselineArgs& args) {
  auto* sub = app.add_subcommand(name, description);
  sub->add_option("input", args.input, "medial atoms (.ma, or x y z r lines)")->required();
  sub->add_option("-o,--output", args.output, "output mesh (.off .obj .ply .stl)")->required();
  sub->add_option("--repeat", args.repeat, "time the algorithm over K runs (min, median, max)")
      ->check(Positive);
  return sub;
}

/// Before any work: the output is a mesh path that overwrites no input, and --stats names
/// another file. @throws InvalidInput
void check_output_paths(const BaselineArgs& args, const std::vector<std::string>& inputs) {
  check_mesh_output_path(args.output, inputs);
  if (!args.report.stats.empty() && same_file(args.report.stats, args.output))
    throw InvalidInput(args.report.stats + ": --stats and --output name the same file");
}

/// The report's first keys: which method, on what, written where.
Json method_json(const char* method, const BaselineArgs& args, const MedialSurface& atoms) {
  return Json{{"method", method},
              {"input", args.input},
              {"output", args.output},
              {"atoms", atoms.atoms.size()}};
}

std::string mesh_size_text(const PolygonSoup& soup) {
  return "V " + std::to_string(soup.points.size()) + ", F " + std::to_string(soup.faces.size());
}

std::string timing_text(const StageTiming& t) {
  std::ostringstream s;
  s << std::setprecision(4);
  if (t.seconds.size() == 1)
    s << t.min << " s";
  else
    s << "min " << t.min << " s, median " << t.median << " s, max " << t.max << " s over "
      << t.seconds.size() << " runs";
  return s.str();
}

/// Ends the report with the mesh's size and the timing; writes the mesh, then the report.
/// @throws InvalidInput, IoError
int write_result(const BaselineArgs& args, const PolygonSoup& mesh, const StageTiming& t, Json j,
                 const std::string& text) {
  j["vertices"] = mesh.points.size();
  j["faces"] = mesh.faces.size();
  j["seconds"] = {{"min", t.min}, {"median", t.median}, {"max", t.max}, {"runs", t.seconds}};
  j["peak_memory_mb"] = peak_memory_mb();  // before the output is written, as garb's
  write_polygon_soup(mesh, args.output);
  emit_report(args.report, j, text);
  return 0;
}

/// skin and union: CGAL meshes the atoms; `options` are the method's own report keys.
int run_cgal(const BaselineArgs& args, const char* method, const char* name, const Json& options,
             const std::function<PolygonSoup(const MedialSurface&)>& mesher) {
  check_output_paths(args, {args.input});
  check_report_path(args.report, {args.input});
  const MedialSurface atoms = read_medial_surface(args.input);
  PolygonSoup mesh;
  const StageTiming t = time_stage(args.repeat, [&] { mesh = mesher(atoms); });
  Json j = method_json(method, args, atoms);
  j.update(options);
  return write_result(
      args, mesh, t, std::move(j),
      std::string(name) + ": " + mesh_size_text(mesh) + ", " + timing_text(t) + '\n');
}

}  // namespace

// --- skin ------------------------------------------------------------------------------------

CLI::App* add_skin(CLI::App& app, SkinArgs& args) {
  auto* sub = add_baseline(app, "skin", "CGAL skin surface of the atoms (make_skin_surface_mesh_3)",
                           args.baseline);
  sub->add_option("--shrink", args.skin.shrink, "shrink factor, in (0, 1)");
  sub->add_option("--subdivisions", args.skin.subdivisions, "CGAL refinement rounds");
  add_report_options(*sub, args.baseline.report);
  return sub;
}

int run_skin(const SkinArgs& args) {
  return run_cgal(args.baseline, "cgal_skin_surface", "skin surface",
                  {{"shrink", args.skin.shrink}, {"subdivisions", args.skin.subdivisions}},
                  [&](const MedialSurface& atoms) { return skin_surface_mesh(atoms, args.skin); });
}

// --- union -----------------------------------------------------------------------------------

CLI::App* add_union(CLI::App& app, UnionArgs& args) {
  auto* sub =
      add_baseline(app, "union", "CGAL union of balls (Union_of_balls_3 + mesh_union_of_balls_3)",
                   args.baseline);
  sub->add_option("--subdivisions", args.subdivisions, "CGAL refinement rounds");
  add_report_options(*sub, args.baseline.report);
  return sub;
}

int run_union(const UnionArgs& args) {
  return run_cgal(
      args.baseline, "cgal_union_of_balls", "union of balls", {{"subdivisions", args.subdivisions}},
      [&](const MedialSurface& atoms) { return union_of_balls_mesh(atoms, args.subdivisions); });
}

// --- vdb -------------------------------------------------------------------------------------

CLI::App* add_vdb(CLI::App& app, VdbArgs& args) {
  auto* sub = add_baseline(
      app, "vdb",
      "OpenVDB level set of the spheres, or of a medial mesh's envelope, meshed (volumeToMesh)",
      args.baseline);
  auto* voxel =
      sub->add_option("--voxel", args.voxel, "voxel size, model units (0 = diagonal / 400)");
  auto* vertices = sub->add_option("--match-vertices", args.match_vertices,
                                   "search the voxel giving about N vertices (at most 5 probes)");
  auto* hausdorff = sub->add_option("--match-hausdorff", args.match_hausdorff,
                                    "P REF: search the voxel giving a Hausdorff distance to REF "
                                    "of P % of REF's diagonal (at most 5 probes)")
                        ->expected(2);
  auto* envelope =
      sub->add_option("--match-envelope", args.match_envelope,
                      "P: search the voxel giving a Hausdorff distance to G (as `evaluate atoms`) "
                      "of P % of --diagonal (at most 5 probes)")
          ->check(Positive);
  sub->add_option("--diagonal", args.diagonal,
                  "--match-envelope: diagonal for the %, model units (0 = the spheres' "
                  "bounding box)")
      ->check(NonNegative)
      ->needs(envelope);
  sub->add_option("--samples", args.samples,
                  "--match-hausdorff, --match-envelope: samples per side (0 = default; raised "
                  "to twice the larger vertex count when below it)");
  sub->add_option(
      "--primitives", args.primitives,
      "what is meshed: auto, ma (a medial mesh's envelope: G's signed distance "
      "sampled) or rt (the spheres alone); auto is ma when the file has edges or faces");
  voxel->excludes(vertices)->excludes(hausdorff)->excludes(envelope);
  vertices->excludes(hausdorff)->excludes(envelope);
  hausdorff->excludes(envelope);
  add_report_options(*sub, args.baseline.report);
  return sub;
}

int run_vdb(const VdbArgs& args) {
  const BaselineArgs& b = args.baseline;
  std::vector<std::string> inputs = {b.input};
  check_output_paths(b, inputs);
  std::string match_ref;
  double match_pct = 0;
  if (!args.match_hausdorff.empty()) {
    std::istringstream p(args.match_hausdorff[0]);
    if (!(p >> match_pct) || !p.eof())
      throw InvalidInput("--match-hausdorff: '" + args.match_hausdorff[0] +
                         "' is not a percentage");
    match_ref = args.match_hausdorff[1];
    inputs.push_back(match_ref);
    check_mesh_output_path(b.output, inputs);
  }
  check_report_path(b.report, inputs);
  const garbing::PrimitiveSet primitives = garbing::parse_primitive_set(args.primitives);
  const MedialSurface atoms = read_medial_surface(b.input);

  // The voxel: given, or searched (the search's keys come first in the report).
  VdbOptions opt;
  opt.voxel = args.voxel;
  opt.primitives = primitives;
  Json j = Json::object();
  Json probes = Json::array();
  bool clamped = false, out_of_reach = false;
  std::string matched_what;  // for the text report: "vertices", "% Hausdorff to ..."
  if (args.match_vertices > 0 || !match_ref.empty() || args.match_envelope > 0) {
    VdbMatch m;
    double target = 0;
    if (args.match_vertices > 0) {
      m = vdb_match_vertices(atoms, args.match_vertices, /*max_probes=*/5, primitives);
      target = static_cast<double>(args.match_vertices);
      j["match"] = "vertices";
      matched_what = " vertices";
    } else if (!match_ref.empty()) {
      const PolygonSoup ref = read_polygon_soup(match_ref);
      MeshDistanceOptions dopt;
      dopt.samples = args.samples;
      m = vdb_match_hausdorff(atoms, match_pct, ref, dopt, match_ref, /*max_probes=*/5, primitives);
      target = match_pct;
      j["match"] = "hausdorff_pct";
      matched_what = " % Hausdorff to " + match_ref + " (of its diagonal)";
    } else {
      AtomsDistanceOptions dopt;
      dopt.primitives = primitives;
      dopt.samples = args.samples;
      m = vdb_match_envelope(atoms, args.match_envelope, args.diagonal, dopt, /*max_probes=*/5);
      target = args.match_envelope;
      const double diagonal = args.diagonal > 0 ? args.diagonal : spheres_bbox_diagonal(atoms);
      j["match"] = "envelope_hausdorff_pct";
      j["diagonal"] = diagonal;
      std::ostringstream w;
      w << std::setprecision(6) << " % Hausdorff to G (of the diagonal " << diagonal << ", "
        << (args.diagonal > 0 ? "given" : "the spheres' box") << ")";
      matched_what = w.str();
    }
    for (const auto& p : m.probes)
      probes.push_back({{"voxel", p.voxel}, {"value", p.value}, {"vertices", p.vertices}});
    clamped = m.clamped;
    out_of_reach = m.out_of_reach;
    opt.voxel = m.best.voxel;
    j["target"] = target;
    j["matched"] = m.value;
    if (!match_ref.empty()) j["reference"] = match_ref;
  }

  VdbMesh mesh;
  const StageTiming t = time_stage(b.repeat, [&] { mesh = vdb_mesh(atoms, opt); });
  j.update(method_json("openvdb", b, atoms));
  j["voxel"] = mesh.voxel;
  j["dropped_spheres"] = mesh.dropped_spheres;
  j["quads"] = mesh.quads;
  j["primitives"] = mesh.envelope ? "ma" : "rt";
  j["cones"] = mesh.cones;
  j["slabs"] = mesh.slabs;
  if (mesh.envelope) j["leaves"] = mesh.leaves;
  if (!probes.empty()) {
    j["probes"] = probes;
    j["clamped"] = clamped;
    j["out_of_reach"] = out_of_reach;
  }
  std::ostringstream text;
  if (mesh.envelope)
    text << "OpenVDB, envelope of " << mesh.cones << " cones and " << mesh.slabs
         << " slabs: " << mesh_size_text(mesh.mesh) << ", voxel " << std::setprecision(6)
         << mesh.voxel << ", " << timing_text(t) << '\n';
  else
    text << "OpenVDB: " << mesh_size_text(mesh.mesh) << ", voxel " << std::setprecision(6)
         << mesh.voxel << ", " << mesh.dropped_spheres << " spheres under 1.5 voxels dropped, "
         << timing_text(t) << '\n';
  if (!probes.empty())
    text << "  voxel search: " << probes.size() << " probes, matched " << j["matched"].dump()
         << matched_what << " for a target of " << j["target"].dump()
         << (clamped ? " (voxel clamped)" : "")
         << (out_of_reach ? " (out of reach: the measure stopped following the voxel)" : "")
         << '\n';
  return write_result(b, mesh.mesh, t, std::move(j), text.str());
}

}  // namespace mg::evaluate::cli
