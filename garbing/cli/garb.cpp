// garb: medial surface garbing. Atoms in, closed triangle mesh out.
//   garb INPUT.ma -o OUTPUT_MESH [--m1 M1_MESH] [--min-depth D] [--max-depth D]
//        [--no-criterion N ...] [--cones rt|all|edges|none] [--cone-filter F] [--cone-collar C] [--spheres-only]
//        [--refine K] [--no-dual] [--max-travel T] [--repair-rounds N] [--max-gap F] [--stats FILE.json]
//        [--threads N]
#include "garbing/atomic_file.h"
#include "garbing/cli_main.h"
#include "garbing/coarse_mesh.h"
#include "garbing/medial_surface.h"
#include "garbing/mesh_io.h"
#include "garbing/mesh_topology.h"
#include "garbing/octree.h"
#include "garbing/refine_mesh.h"

#include <sys/resource.h>

#include <nlohmann/json.hpp>
#include <tbb/global_control.h>

#include <chrono>
#include <fstream>
#include <iomanip>
#include <map>
#include <memory>

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

void write_json(const nlohmann::ordered_json& j, const std::string& path) {
  mg::write_file_atomically(path, [&](std::ostream& out) { out << std::setw(2) << j << '\n'; });
}

int garb_main(int argc, char** argv) {
  CLI::App app{"Medial surface garbing: a closed mesh of the object described by medial atoms."};
  app.option_defaults()->always_capture_default();
  std::string input, output, m1_path, stats_path;
  mg::OctreeOptions opt;
  std::vector<int> off;
  int threads = 0;
  app.add_option("input", input, "medial surface (.ma, or x y z r lines)")->required();
  app.add_option("-o,--output", output, "output mesh M2 (.off .obj .ply .stl)")->required();
  app.add_option("--m1", m1_path, "also write the coarse mesh M1 here");
  app.add_option("--min-depth", opt.min_depth, "minimal active depth d (0 = automatic: side <= rc/8)")
      ->check(mg::NonNegative);
  app.add_option("--max-depth", opt.max_depth, "safety stop on the octree depth")
      ->check(CLI::Range(1, 20));
  app.add_option("--no-criterion", off, "switch a subdivision criterion off (1-4, repeatable)")
      ->check(CLI::Range(1, 4));
  mg::RefineOptions refine;
  std::string cones = "rt";
  bool spheres_only = false, no_dual = false;
  app.add_option("--cones", cones, "cone pairs: rt (regular triangulation), all, edges (.ma), none")
      ->check(CLI::IsMember({"rt", "all", "edges", "none"}));
  app.add_option("--cone-filter", opt.cones.min_circle_ratio,
                 "keep a cone if the intersection circle radius >= F * the smaller radius")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--cone-collar", opt.cones.max_collar,
                 "keep a cone if it stands off its spheres' crease by <= C * rc / 8 (0: no limit)")
      ->check(mg::NonNegative);
  app.add_flag("--spheres-only", spheres_only, "no cones: G is the union of the spheres");
  app.add_option("--refine", refine.subdivisions, "rounds of 1-to-4 subdivision + migration")
      ->check(mg::NonNegative);
  app.add_flag("--no-dual", no_dual, "migrate M1 itself, triangulated (ablation)");
  app.add_option("--max-travel", refine.max_travel,
                 "longest migration, in leaf sides, before the closest-point fallback")
      ->check(mg::Positive);
  app.add_option("--repair-rounds", refine.repair_rounds,
                 "rounds of each fold repair stage (0: no repair, folds are only counted)")
      ->check(mg::NonNegative);
  app.add_option("--max-gap", refine.max_gap,
                 "split an edge whose midpoint is provably farther than F leaf sides from G (0: off)")
      ->check(mg::NonNegative);
  app.add_option("--stats", stats_path, "write statistics as JSON");
  app.add_option("--threads", threads, "worker threads (0 = all cores)")->check(mg::NonNegative);
  mg::parse_command_line(app, argc, argv);

  std::vector<std::string> inputs = {input};
  mg::check_output_path(output, inputs);
  if (!mg::has_mesh_extension(output))
    throw mg::InvalidInput(output + ": unknown mesh extension (expected .off, .obj, .ply or .stl)");
  if (!m1_path.empty()) {
    mg::check_output_path(m1_path, inputs);
    if (!mg::has_mesh_extension(m1_path))
      throw mg::InvalidInput(m1_path + ": unknown mesh extension (expected .off, .obj, .ply or .stl)");
  }
  if (!stats_path.empty()) mg::check_output_path(stats_path, inputs);
  for (int k : off) opt.criteria[k - 1] = false;
  opt.cones.source = spheres_only ? mg::ConeSource::none : mg::parse_cone_source(cones);
  refine.dual = !no_dual;
  std::unique_ptr<tbb::global_control> limit;
  if (threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                  static_cast<std::size_t>(threads));

  const auto t_start = Clock::now();
  const mg::MedialSurface atoms = mg::read_medial_surface(input);
  const double t_read = seconds_since(t_start);

  auto t0 = Clock::now();
  const mg::Octree tree = mg::build_octree(atoms, opt);
  const double t_octree = seconds_since(t0);
  t0 = Clock::now();
  const mg::CoarseMesh m1 = mg::extract_coarse_mesh(tree);
  const double t_m1 = seconds_since(t0);

  t0 = Clock::now();
  const mg::RefinedMesh m2 = mg::refine_mesh(m1, tree, atoms, refine);
  const double t_m2 = seconds_since(t0);
  const double t_garbing = seconds_since(t_start) - t_read;

  t0 = Clock::now();
  if (!m1_path.empty()) mg::write_mesh(m1.mesh, m1_path);
  mg::write_mesh(m2.mesh, output);
  const double t_write = seconds_since(t0);

  if (!stats_path.empty()) {
    const mg::MeshTopology topo = mg::mesh_topology(mg::soup_from_mesh(m1.mesh));
    const mg::MeshTopology topo2 = mg::mesh_topology(mg::soup_from_mesh(m2.mesh));
    const mg::RefineStats& r = m2.stats;
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    std::map<int, long> per_level, active_per_level;
    long active = 0, crease_only = 0;
    for (int c : tree.leaves) {
      ++per_level[tree.cells[c].level];
      if (tree.cells[c].is_active()) {
        ++active;
        if (tree.cells[c].spheres.empty()) ++crease_only;
        ++active_per_level[tree.cells[c].level];
      }
    }
    std::vector<int> owners;
    for (const auto& f : m1.faces) owners.push_back(f.owner);
    std::sort(owners.begin(), owners.end());
    owners.erase(std::unique(owners.begin(), owners.end()), owners.end());

    nlohmann::ordered_json j;
    j["input"] = input;
    j["atoms"] = atoms.atoms.size();
    j["rc"] = tree.rc;
    j["root_side"] = tree.root_side;
    j["min_depth"] = tree.min_depth;
    j["max_depth"] = tree.max_depth;
    j["depth"] = tree.depth;
    j["hit_max_depth"] = tree.hit_max_depth;
    j["criteria_off"] = off;
    j["splits_by_criterion"] = tree.splits;
    nlohmann::ordered_json levels = nlohmann::ordered_json::array();
    for (const auto& [level, n] : per_level)
      levels.push_back({{"level", level}, {"leaves", n}, {"active", active_per_level[level]}});
    j["leaves_per_level"] = levels;
    j["leaves"] = tree.leaves.size();
    j["active_leaves"] = active;
    j["crease_leaves"] = crease_only;  // active through a cone's crease fill only
    j["boundary_leaves"] = owners.size();
    j["m1"] = {{"vertices", m1.mesh.n_vertices()}, {"faces", m1.mesh.n_faces()},
               {"components", topo.components},   {"euler", topo.euler},
               {"genus", topo.genus},               {"hanging_corners", m1.hanging_corners},
               {"split_vertices", m1.split_vertices}};
    j["m2"] = {{"vertices", m2.mesh.n_vertices()},
               {"faces", m2.mesh.n_faces()},
               {"components", topo2.components},
               {"euler", topo2.euler},
               {"genus", topo2.genus},
               {"closed", topo2.closed},
               {"oriented", topo2.oriented},
               {"cones", r.cones},
               {"cone_source", cones},
               {"cone_filter", opt.cones.min_circle_ratio},
               {"cone_collar", opt.cones.max_collar},
               {"dual", refine.dual},
               {"subdivisions", refine.subdivisions},
               {"vertices_migrated", r.vertices_migrated},
               {"fallback_zero_direction", r.fallback_zero_direction},
               {"fallback_missed", r.fallback_missed},
               {"fallback_too_far", r.fallback_too_far},
               {"collapsed_digons", r.collapsed_digons},
               {"max_gap", refine.max_gap},
               {"gap_splits", r.gap_splits},
               {"gap_splits_undone", r.gap_undone},
               {"intersecting_pairs_before_repair", r.intersecting_before},
               {"degenerate_before_repair", r.degenerate_before},
               {"intersecting_pairs_after_repair", r.intersecting_after},
               {"degenerate_after_repair", r.degenerate_after},
               {"repaired_vertices", r.repaired_vertices},
               {"pull_back_steps", r.pulled_back},
               {"left_off_g_after_repair", r.left_off_g}};
    j["peak_memory_mb"] = usage.ru_maxrss / 1024.0;
    j["seconds"] = {{"read", t_read},
                    {"octree", t_octree - tree.seconds_cone_pairs},
                    {"m1", t_m1},
                    {"cones", tree.seconds_cone_pairs + r.seconds_cones},
                    {"migration", r.seconds_migration},
                    {"repair", r.seconds_repair},
                    {"m2", t_m2},
                    {"garbing", t_garbing},
                    {"write", t_write},
                    {"total", seconds_since(t_start)}};
    write_json(j, stats_path);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return mg::run_cli("garb", [&] { return garb_main(argc, argv); });
}
