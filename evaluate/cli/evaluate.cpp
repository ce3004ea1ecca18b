// evaluate: distances, smoothness and validity checks, timed baselines.
//   evaluate distance MESH REFERENCE [--samples N] [--seed S] [--faces-only] [--json]
//   evaluate atoms MESH ATOMS.ma [--cones rt|all|edges|none] [--cone-filter F]
//                  [--cone-collar C] [--samples N] [--seed S] [--diagonal D] [--json]
//   evaluate normals MESH REFERENCE [--samples N] [--seed S] [--flat-reference] [--json]
//   evaluate check MESH [--json]
//   evaluate skin INPUT.ma -o OUT [--shrink F] [--subdivisions K] [--repeat K] [--json]
//   evaluate union INPUT.ma -o OUT [--subdivisions K] [--repeat K] [--json]
//   evaluate vdb INPUT.ma -o OUT [--voxel H | --match-vertices N | --match-hausdorff P REF]
//                [--samples N] [--repeat K] [--json]
// Every sub-command also takes --stats FILE (the JSON report, written atomically); --threads N
// limits the worker threads. Each sub-command is an add_X()/run_X() pair of commands.h.
#include "commands.h"

#include "core/cli_main.h"

#include <functional>
#include <stdexcept>
#include <utility>
#include <vector>

namespace {

namespace cli = mg::evaluate::cli;

int evaluate_main(int argc, char** argv) {
  CLI::App app{
      "Distances (Metro-style Hausdorff, RMS, mean), normal deviation, mesh checks, "
      "and the timed baselines (CGAL skin surface, union of balls, OpenVDB)."};
  app.option_defaults()->always_capture_default();
  app.require_subcommand(1);
  app.fallthrough();
  int threads = 0;
  app.add_option("--threads", threads, "worker threads (0 = all cores)")->check(mg::NonNegative);

  cli::DistanceArgs distance;
  cli::AtomsArgs atoms;
  cli::NormalsArgs normals;
  cli::CheckArgs check;
  cli::SkinArgs skin;
  cli::UnionArgs onion;
  cli::VdbArgs vdb;
  // In the order of --help.
  const std::vector<std::pair<CLI::App*, std::function<int()>>> commands = {
      {cli::add_distance(app, distance), [&] { return cli::run_distance(distance); }},
      {cli::add_atoms(app, atoms), [&] { return cli::run_atoms(atoms); }},
      {cli::add_normals(app, normals), [&] { return cli::run_normals(normals); }},
      {cli::add_check(app, check), [&] { return cli::run_check(check); }},
      {cli::add_skin(app, skin), [&] { return cli::run_skin(skin); }},
      {cli::add_union(app, onion), [&] { return cli::run_union(onion); }},
      {cli::add_vdb(app, vdb), [&] { return cli::run_vdb(vdb); }}};

  mg::parse_command_line(app, argc, argv);
  const auto limit = mg::limit_threads(threads);
  for (const auto& [sub, run] : commands)
    if (*sub) return run();
  throw std::logic_error("no sub-command parsed");  // require_subcommand(1) prevents it
}

}  // namespace

int main(int argc, char** argv) {
  return mg::run_cli("evaluate", [&] { return evaluate_main(argc, argv); });
}
