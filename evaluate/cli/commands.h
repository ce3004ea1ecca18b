#pragma once
/// \file commands.h
/// The sub-commands of the evaluate program. Each has a plain struct of its command-line
/// arguments (defaults as on the command line), an add_X() that registers them on a new
/// CLI11 sub-command of `app` and returns it, and a run_X() that does the work and prints the
/// report (0 on success; failures are thrown, and mapped to exit codes by mg::run_cli).
/// distance_commands.cpp: distance, atoms, normals, check; baseline_commands.cpp: skin, union,
/// vdb; evaluate.cpp: the program, which registers them all and runs the one given.

#include "core/atomic_file.h"
#include "core/cli_main.h"
#include "evaluate/baselines.h"
#include "garbing/target_shape.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cstddef>
#include <cstdint>
#include <iostream>
#include <string>
#include <vector>

namespace mg::evaluate::cli {

using Json = nlohmann::ordered_json;

/// What every sub-command shares: --json (the report on stdout instead of text) and --stats.
struct ReportArgs {
  bool json = false;
  std::string stats;  ///< also write the JSON report to this file (empty: no file)
};

inline void add_report_options(CLI::App& sub, ReportArgs& report) {
  sub.add_flag("--json", report.json, "print the report as JSON");
  sub.add_option("--stats", report.stats, "also write the JSON report to this file");
}

/// Refuses a --stats path that would overwrite an input, before any work. @throws InvalidInput
inline void check_report_path(const ReportArgs& report, const std::vector<std::string>& inputs) {
  if (!report.stats.empty()) check_output_path(report.stats, inputs);
}

/// Writes the --stats file (atomically), then prints the JSON or the text report.
/// @throws IoError
inline void emit_report(const ReportArgs& report, const Json& j, const std::string& text) {
  if (!report.stats.empty()) write_json(j, report.stats);
  if (report.json)
    print_json(std::cout, j);
  else
    std::cout << text;
}

// --- distance_commands.cpp ----------------------------------------------------------------

/// What distance and normals share: MESH judged against REFERENCE, by samples.
struct MeshPairArgs {
  std::string mesh, reference;
  std::size_t samples = 0;  ///< 0 = max(1e6, 10 (V_mesh + V_reference))
  std::uint64_t seed = 1;   ///< of the sampling
  ReportArgs report;
};

/// `evaluate distance MESH REFERENCE`: Metro-style two-sided distances.
struct DistanceArgs {
  MeshPairArgs pair;        ///< samples per side
  bool faces_only = false;  ///< sample faces only (default: vertices, edges and faces)
};
CLI::App* add_distance(CLI::App& app, DistanceArgs& args);
int run_distance(const DistanceArgs& args);

/// `evaluate atoms MESH ATOMS.ma`: two-sided distances between MESH and G.
struct AtomsArgs {
  std::string mesh, atoms;
  std::string primitives = "auto";  ///< auto | ma | rt, as garb --primitives
  std::string cones = "rt";         ///< rt | all | edges | none, as garb --cones
  bool cone_options_given = false;  ///< --cones, --cone-filter or --cone-collar given: rt
  double cone_filter = garbing::ConeOptions{}.min_circle_ratio;
  double cone_collar = garbing::ConeOptions{}.max_collar;
  std::size_t samples = 0;  ///< per side; 0 = max(1e5, 10 V_mesh)
  std::uint64_t seed = 1;
  double diagonal = 0;  ///< for the percentages, model units; 0 = MESH's bounding box
  ReportArgs report;
};
CLI::App* add_atoms(CLI::App& app, AtomsArgs& args);
int run_atoms(const AtomsArgs& args);

/// `evaluate normals MESH REFERENCE`: angles between MESH's and REFERENCE's normals.
struct NormalsArgs {
  MeshPairArgs pair;            ///< samples on MESH
  bool flat_reference = false;  ///< REFERENCE's facet normals, not its vertex normals
};
CLI::App* add_normals(CLI::App& app, NormalsArgs& args);
int run_normals(const NormalsArgs& args);

/// `evaluate check MESH`: topology, self-intersections, degenerate triangles.
struct CheckArgs {
  std::string mesh;
  ReportArgs report;
};
CLI::App* add_check(CLI::App& app, CheckArgs& args);
int run_check(const CheckArgs& args);

// --- baseline_commands.cpp ----------------------------------------------------------------

/// What skin, union and vdb share: atoms in, a mesh out, the algorithm timed without I/O.
struct BaselineArgs {
  std::string input;   ///< medial atoms (.ma, or x y z r lines)
  std::string output;  ///< output mesh (.off .obj .ply .stl)
  int repeat = 1;      ///< timed runs (min, median, max)
  ReportArgs report;
};

/// `evaluate skin INPUT.ma -o OUT`: CGAL skin surface.
struct SkinArgs {
  BaselineArgs baseline;
  SkinOptions skin;  ///< shrink factor and refinement rounds
};
CLI::App* add_skin(CLI::App& app, SkinArgs& args);
int run_skin(const SkinArgs& args);

/// `evaluate union INPUT.ma -o OUT`: CGAL union of balls.
struct UnionArgs {
  BaselineArgs baseline;
  int subdivisions = 0;  ///< CGAL refinement rounds
};
CLI::App* add_union(CLI::App& app, UnionArgs& args);
int run_union(const UnionArgs& args);

/// `evaluate vdb INPUT.ma -o OUT`: OpenVDB level set, meshed; the voxel given or searched.
struct VdbArgs {
  BaselineArgs baseline;
  double voxel = 0;                          ///< model units; 0 = diagonal / 400
  std::size_t match_vertices = 0;            ///< search the voxel giving about N vertices
  std::vector<std::string> match_hausdorff;  ///< P REF: search the voxel giving P % Hausdorff
  /// Search the voxel giving a two-sided Hausdorff distance to G of P % of `diagonal` (0: none)
  double match_envelope = 0;
  double diagonal = 0;      ///< --match-envelope's diagonal, model units; 0 = the spheres' box
  std::size_t samples = 0;  ///< --match-hausdorff, --match-envelope: samples per side
  std::string primitives = "auto";  ///< auto | ma (the envelope's distance) | rt (the spheres)
};
CLI::App* add_vdb(CLI::App& app, VdbArgs& args);
int run_vdb(const VdbArgs& args);

}  // namespace mg::evaluate::cli
