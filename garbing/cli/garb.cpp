// garb: medial surface garbing. Atoms in, closed triangle mesh out.
//   garb INPUT.ma -o OUTPUT_MESH [--m1 M1_MESH] [--min-depth D] [--max-depth D]
//        [--no-criterion N ...] [--primitives auto|ma|rt]
//        [--cones rt|all|edges|none] [--cone-filter F] [--cone-collar C]
//        [--spheres-only] [--tolerance F] [--thinning cover|contain] [--refine K] [--no-dual]
//        [--max-travel T]
//        [--repair-rounds N]
//        [--max-gap F] [--check-topology] [--stats FILE.json] [--threads N]
#include "garbing/garb.h"
#include "core/cli_main.h"
#include "core/medial_surface.h"
#include "core/mesh_io.h"
#include "core/mesh_topology.h"
#include "core/timer.h"
#include "skeletonize/union_topology.h"

#include <algorithm>
#include <iostream>
#include <map>
#include <optional>

namespace {

namespace gb = mg::garbing;
using Json = nlohmann::ordered_json;

/// The keys M1 and M2 share: size and genus.
Json mesh_json(const mg::Mesh& mesh, const mg::MeshTopology& topo) {
  return {{"vertices", mesh.n_vertices()},
          {"faces", mesh.n_faces()},
          {"components", topo.components},
          {"euler", topo.euler},
          {"genus", topo.genus}};
}

/// The octree: its frame and depths, the splits, and the leaves per level (active ones, and
/// those active through a cone or slab only: a crease fill, a waist, a slab's prism).
Json octree_json(const gb::Octree& tree, const std::vector<int>& criteria_off, bool pruned_lists) {
  std::map<int, long> per_level, active_per_level;
  long active = 0, crease_only = 0;
  std::size_t listed_balls = 0, listed_hulls = 0, most_balls = 0;
  for (int c : tree.leaves) {
    ++per_level[tree.cells[c].level];
    if (tree.cells[c].is_active()) {
      ++active;
      listed_balls += tree.cells[c].spheres.size();
      listed_hulls += tree.cells[c].cones.size() + tree.cells[c].slabs.size();
      most_balls = std::max(most_balls, tree.cells[c].spheres.size());
      if (tree.cells[c].spheres.empty()) ++crease_only;
      ++active_per_level[tree.cells[c].level];
    }
  }
  Json levels = Json::array();
  for (const auto& [level, n] : per_level)
    levels.push_back({{"level", level}, {"leaves", n}, {"active", active_per_level[level]}});
  Json j;
  j["rc"] = tree.rc;
  j["root_side"] = tree.root_side;
  j["min_depth"] = tree.min_depth;
  j["max_depth"] = tree.max_depth;
  j["depth"] = tree.depth;
  j["hit_max_depth"] = tree.hit_max_depth;
  j["depth_stopped_cells"] = tree.depth_stopped;
  j["criteria_off"] = criteria_off;
  j["pruned_lists"] = pruned_lists;
  j["splits_by_criterion"] = tree.splits;
  j["leaves_per_level"] = levels;
  j["leaves"] = tree.leaves.size();
  j["active_leaves"] = active;
  j["crease_leaves"] = crease_only;  // active through a cone or slab only
  // The active leaves' lists: what the criteria and the migration read per leaf.
  j["listed_per_active_leaf"] = {
      {"balls_mean", active ? double(listed_balls) / double(active) : 0.0},
      {"balls_max", most_balls},
      {"cones_and_slabs_mean", active ? double(listed_hulls) / double(active) : 0.0}};
  return j;
}

/// M2: the mesh, then G's cones and the refinement options, then what migration, gap
/// splitting and fold repair did.
Json m2_json(const mg::MedialSurface& atoms, const gb::Garbing& r, const gb::GarbOptions& opt,
             const std::string& cone_source) {
  const bool envelope = gb::resolve(opt.primitives, atoms) == gb::PrimitiveSet::envelope;
  const mg::MeshTopology topo = mg::mesh_topology(mg::soup_from_mesh(r.m2.mesh));
  const gb::RefineStats& s = r.m2.stats;
  Json j = mesh_json(r.m2.mesh, topo);
  j.update(Json{{"closed", topo.closed}, {"oriented", topo.oriented}});
  // G's cones and the refinement options.
  j.update(Json{{"primitives", envelope ? "ma" : "rt"},
                {"cones", r.g.cone_count()},
                {"slabs", r.g.slab_count()}});
  if (envelope) {
    const gb::EnvelopeCounts& e = r.g.envelope_counts();
    j["envelope"] = {{"edges", e.edges},
                     {"repeated_edges", e.repeated_edges},
                     {"edges_in_a_ball", e.edges_in_a_ball},
                     {"faces", e.faces},
                     {"repeated_faces", e.repeated_faces},
                     {"collinear_faces", e.collinear_faces},
                     {"slabs_without_tangent_triangles", e.slabs_without_tangent_triangles}};
  } else {
    j.update(Json{{"cone_source", cone_source},
                  {"cone_filter", opt.cones.min_circle_ratio},
                  {"cone_collar", opt.cones.max_collar}});
  }
  j.update(Json{{"dual", opt.refine.dual}, {"subdivisions", opt.refine.subdivisions}});
  // Migration: the vertices moved onto G, and those that fell back to the closest point.
  j.update(Json{{"vertices_migrated", s.vertices_migrated},
                {"fallback_zero_direction", s.fallback_zero_direction},
                {"fallback_missed", s.fallback_missed},
                {"fallback_too_far", s.fallback_too_far},
                {"collapsed_digons", s.collapsed_digons}});
  // Gap splitting.
  j.update(Json{{"max_gap", opt.refine.max_gap},
                {"gap_splits", s.gap_splits},
                {"gap_splits_undone", s.gap_undone}});
  // Fold repair: the defects before and after it, and what it moved.
  j.update(Json{{"intersecting_pairs_before_repair", s.intersecting_before},
                {"degenerate_before_repair", s.degenerate_before},
                {"intersecting_pairs_after_repair", s.intersecting_after},
                {"degenerate_after_repair", s.degenerate_after},
                {"repaired_vertices", s.repaired_vertices},
                {"pull_back_steps", s.pulled_back},
                {"left_off_g_after_repair", s.left_off_g}});
  return j;
}

/// --check-topology: M2's components and Euler characteristic against the union of the balls'.
struct TopologyCheck {
  mg::skeletonize::UnionTopology union_of_balls;
  std::size_t components = 0;  ///< M2's
  long euler = 0;
  double seconds = 0;
  bool matches() const {
    return union_of_balls.components == components && union_of_balls.euler == euler;
  }
};

/// The --stats report: the octree's census, M1, M2 and their statistics, memory and seconds.
Json stats_json(const std::string& input, const mg::MedialSurface& atoms, const gb::Garbing& r,
                const gb::GarbOptions& opt, const std::vector<int>& criteria_off,
                const std::string& cone_source, const std::optional<TopologyCheck>& check,
                double seconds_read, double seconds_write, double seconds_total) {
  Json m1 = mesh_json(r.m1.mesh, mg::mesh_topology(mg::soup_from_mesh(r.m1.mesh)));
  m1["hanging_corners"] = r.m1.hanging_corners;
  m1["split_vertices"] = r.m1.split_vertices;
  const Json m2 = m2_json(atoms, r, opt, cone_source);
  std::vector<int> owners;
  for (const auto& f : r.m1.faces) owners.push_back(f.owner);
  std::sort(owners.begin(), owners.end());
  owners.erase(std::unique(owners.begin(), owners.end()), owners.end());
  const double peak_mb = mg::peak_memory_mb();  // after the topologies of M1 and M2

  Json j = {{"input", input}, {"atoms", atoms.atoms.size()}};
  j.update(octree_json(r.tree, criteria_off, opt.octree.prune_lists && !r.g.is_envelope()));
  if (opt.tolerance > 0)
    j["thinning"] = {{"tolerance_leaf_sides", opt.tolerance},
                     {"method", opt.thinning == gb::ThinMethod::cover ? "cover" : "contain"},
                     {"slack", r.thinning.slack},
                     {"atoms_kept", r.thinning.kept},
                     {"atoms_dropped", r.thinning.dropped},
                     {"atoms_covered", r.thinning.covered},
                     {"seconds", r.thinning.seconds}};
  j["boundary_leaves"] = owners.size();
  j["m1"] = m1;
  j["m2"] = m2;
  if (check)
    j["topology_check"] = {{"union_components", check->union_of_balls.components},
                           {"union_euler", check->union_of_balls.euler},
                           {"m2_components", check->components},
                           {"m2_euler", check->euler},
                           {"matches", check->matches()},
                           {"seconds", check->seconds}};
  j["peak_memory_mb"] = peak_mb;
  j["peak_memory_mb_by_phase"] = {{"cones", r.peak_mb.target_shape},
                                  {"octree", r.peak_mb.octree},
                                  {"m1", r.peak_mb.m1},
                                  {"m2", r.peak_mb.m2}};
  j["seconds"] = {{"read", seconds_read},
                  {"octree", r.seconds.octree},
                  {"m1", r.seconds.m1},
                  {"cones", r.seconds.target_shape},
                  {"migration", r.m2.stats.seconds_migration},
                  {"repair", r.m2.stats.seconds_repair},
                  {"m2", r.seconds.m2},
                  {"garbing", r.seconds.total()},
                  {"write", seconds_write},
                  {"total", seconds_total}};
  return j;
}

int garb_main(int argc, char** argv) {
  CLI::App app{"Medial surface garbing: a closed mesh of the object described by medial atoms."};
  app.option_defaults()->always_capture_default();
  std::string input, output, m1_path, stats_path;
  gb::GarbOptions opt;
  std::vector<int> off;
  int threads = 0;
  app.add_option("input", input, "medial surface (.ma, or x y z r lines)")->required();
  app.add_option("-o,--output", output, "output mesh M2 (.off .obj .ply .stl)")->required();
  app.add_option("--m1", m1_path, "also write the coarse mesh M1 here");
  bool full_lists = false;
  app.add_flag("--full-lists", full_lists,
               "the paper's cell lists: every ball meeting a cell (default: leave out the balls "
               "another ball covers in the cell; full lists are slower and larger on dense atoms)");
  app.add_option("--min-depth", opt.octree.min_depth,
                 "minimal active depth d (0 = automatic: side <= rc/8)")
      ->check(mg::NonNegative);
  app.add_option("--max-depth", opt.octree.max_depth, "safety stop on the octree depth")
      ->check(CLI::Range(1, 20));
  app.add_option("--no-criterion", off, "switch a subdivision criterion off (1-4, repeatable)")
      ->check(CLI::Range(1, 4));
  std::string primitives = "auto", cones = "rt", thinning = "cover";
  bool spheres_only = false, no_dual = false;
  app.add_option("--primitives", primitives,
                 "G's primitives: ma (the envelope: balls, a cone per edge, a slab per face), rt "
                 "(balls and the cones of --cones), auto (ma when the file has edges or faces and "
                 "no cone option is given)")
      ->check(CLI::IsMember({"auto", "ma", "rt"}));
  app.add_option("--cones", cones, "cone pairs: rt (regular triangulation), all, edges (.ma), none")
      ->check(CLI::IsMember({"rt", "all", "edges", "none"}));
  app.add_option("--cone-filter", opt.cones.min_circle_ratio,
                 "keep a cone if the intersection circle radius >= F * the smaller radius")
      ->check(CLI::Range(0.0, 1.0));
  app.add_option("--cone-collar", opt.cones.max_collar,
                 "keep a cone if it stands off its spheres' crease by <= C * rc / 8 (0: no limit)")
      ->check(mg::NonNegative);
  app.add_flag("--spheres-only", spheres_only, "no cones: G is the union of the spheres");
  app.add_option("--tolerance", opt.tolerance,
                 "thin dense atoms first: leave out balls so that the union of the balls moves "
                 "by at most F leaf sides at depth d (--thinning says how); 0: every atom")
      ->check(mg::NonNegative);
  app.add_option("--thinning", thinning,
                 "with --tolerance: cover (a ball goes when nearby kept balls together cover "
                 "it: the kept count is set by F) or contain (only when one kept ball contains "
                 "it: more atoms kept, the same bound)")
      ->check(CLI::IsMember({"cover", "contain"}));
  app.add_option("--refine", opt.refine.subdivisions, "rounds of 1-to-4 subdivision + migration")
      ->check(mg::NonNegative);
  app.add_flag("--no-dual", no_dual, "migrate M1 itself, triangulated (ablation)");
  app.add_option("--max-travel", opt.refine.max_travel,
                 "longest migration, in leaf sides, before the closest-point fallback")
      ->check(mg::Positive);
  app.add_option("--repair-rounds", opt.refine.repair_rounds,
                 "rounds of each fold repair stage (0: no repair, folds are only counted)")
      ->check(mg::NonNegative);
  app.add_option(
         "--max-gap", opt.refine.max_gap,
         "split an edge whose midpoint is provably farther than F leaf sides from G (0: off)")
      ->check(mg::NonNegative);
  bool check_topology = false;
  app.add_flag("--check-topology", check_topology,
               "compare M2's components and Euler characteristic with the union of the balls' "
               "(atoms alone; warns on a mismatch)");
  app.add_option("--stats", stats_path, "write statistics as JSON");
  app.add_option("--threads", threads, "worker threads (0 = all cores)")->check(mg::NonNegative);
  mg::parse_command_line(app, argc, argv);

  const std::vector<std::string> inputs = {input};
  mg::check_mesh_output_path(output, inputs);
  if (!m1_path.empty()) {
    mg::check_mesh_output_path(m1_path, inputs);
    if (mg::same_file(m1_path, output))
      throw mg::InvalidInput(m1_path + ": --m1 names the output file");
  }
  if (!stats_path.empty()) {
    mg::check_output_path(stats_path, inputs);
    for (const std::string& other : {output, m1_path})
      if (!other.empty() && mg::same_file(stats_path, other))
        throw mg::InvalidInput(stats_path + ": --stats names the mesh file " + other);
  }
  for (int k : off) opt.octree.criteria[k - 1] = false;
  opt.octree.prune_lists = !full_lists;
  opt.cones.source = spheres_only ? gb::ConeSource::none : gb::parse_cone_source(cones);
  opt.primitives = gb::parse_primitive_set(primitives);
  opt.thinning = thinning == "contain" ? gb::ThinMethod::contain : gb::ThinMethod::cover;
  if (app.count("--thinning") > 0 && !(opt.tolerance > 0))
    throw mg::InvalidInput("--thinning chooses how --tolerance thins: give --tolerance F > 0");
  const bool cone_options = app.count("--cones") + app.count("--cone-filter") +
                                app.count("--cone-collar") + app.count("--spheres-only") >
                            0;
  if (cone_options && opt.primitives == gb::PrimitiveSet::envelope)
    throw mg::InvalidInput(
        "--cones, --cone-filter, --cone-collar and --spheres-only choose the "
        "cones of --primitives rt, not ma");
  if (cone_options) opt.primitives = gb::PrimitiveSet::atoms;
  opt.refine.dual = !no_dual;
  const auto limit = mg::limit_threads(threads);

  mg::Stopwatch clock;
  const mg::MedialSurface atoms = mg::read_medial_surface(input);
  const double seconds_read = clock.seconds();
  if (gb::resolve(opt.primitives, atoms) == gb::PrimitiveSet::atoms)
    for (std::size_t i = 0; i < atoms.atoms.size(); ++i)
      if (!(atoms.atoms[i].radius > 0))
        throw mg::InvalidInput(input + ": atom " + std::to_string(i) +
                               " has radius 0: the balls alone (--primitives rt) need radii > 0; "
                               "only a medial mesh's envelope (edges or faces) takes them");
  const bool envelope = gb::resolve(opt.primitives, atoms) == gb::PrimitiveSet::envelope;
  if (check_topology && envelope)
    throw mg::InvalidInput(input +
                           ": --check-topology compares with the union of the balls: a medial "
                           "mesh's envelope needs --primitives rt");
  // What garb() refuses (options, the atoms' extent) is said of this file.
  const gb::Garbing result = [&] {
    try {
      return gb::garb(atoms, opt);
    } catch (const mg::InvalidInput& e) {
      throw mg::InvalidInput(input + ": " + e.what());
    }
  }();
  std::optional<TopologyCheck> check;
  if (check_topology) {
    const mg::Stopwatch check_clock;
    const mg::MeshTopology m2 = mg::mesh_topology(mg::soup_from_mesh(result.m2.mesh));
    check = TopologyCheck{mg::skeletonize::union_topology(atoms), m2.components, m2.euler, 0};
    check->seconds = check_clock.seconds();
  }
  // M1, M2 and the statistics appear together or not at all ("write" times the meshes).
  const mg::Stopwatch write_clock;
  mg::write_files_together(
      {{m1_path,
        [&](std::ostream& out) {
          mg::format_polygon_soup(out, mg::soup_from_mesh(result.m1.mesh), m1_path);
        }},
       {output,
        [&](std::ostream& out) {
          mg::format_polygon_soup(out, mg::soup_from_mesh(result.m2.mesh), output);
        }},
       {stats_path, [&](std::ostream& out) {
          const double seconds_write = write_clock.seconds();
          mg::print_json(out, stats_json(input, atoms, result, opt, off, cones, check, seconds_read,
                                         seconds_write, clock.seconds()));
        }}});
  // The promise (M2 has the union's topology) may break: say so, in one line each.
  if (result.tree.hit_max_depth)
    std::cerr << "garb: warning: " << input << ": the octree's depth stop (level "
              << result.tree.max_depth << ") kept " << result.tree.depth_stopped
              << " cell(s) from splitting, likely near-tangent or nearly coincident balls: M2 may "
                 "not have the union's topology\n";
  if (check && !check->matches())
    std::cerr << "garb: warning: " << input << ": M2 has " << check->components
              << " component(s) and Euler characteristic " << check->euler
              << ", the union of the balls " << check->union_of_balls.components << " and "
              << check->union_of_balls.euler << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return mg::run_cli("garb", [&] { return garb_main(argc, argv); });
}
