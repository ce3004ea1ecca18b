// Benchmarks of the garbing stages on a medial surface file.
//   garbing_bench --atoms FILE.ma [Google Benchmark options]
// Reports G (choosing the cone pairs, building the primitives and their hierarchy), octree + M1
// wrapping G (balls and cones: the default) and over the balls alone (cones:0), and the whole
// garbing (G + octree + M1 + M2: garb()).
#include "core/medial_surface.h"
#include "garbing/garb.h"

#include "bench_main.h"

namespace {

namespace gb = mg::garbing;

mg::MedialSurface g_atoms;

gb::TargetShape shape(const gb::ConeOptions& cones = {}) {
  return gb::make_target_shape(g_atoms, cones, gb::bounding_cube_frame(g_atoms));
}

void target_shape(benchmark::State& state) {
  for (auto _ : state) {
    const gb::TargetShape g = shape();
    benchmark::DoNotOptimize(g.cone_count());
    state.counters["cones"] = static_cast<double>(g.cone_count());
  }
}

void octree_and_m1(benchmark::State& state) {
  gb::ConeOptions cones;
  if (state.range(0) == 0) cones.source = gb::ConeSource::none;
  const gb::TargetShape g = shape(cones);
  for (auto _ : state) {
    const gb::Octree tree = gb::build_octree(g);
    const gb::CoarseMesh m1 = gb::extract_coarse_mesh(tree);
    benchmark::DoNotOptimize(m1.mesh.n_faces());
    state.counters["m1_faces"] = static_cast<double>(m1.mesh.n_faces());
    state.counters["leaves"] = static_cast<double>(tree.leaves.size());
  }
}

void whole_garbing(benchmark::State& state) {
  for (auto _ : state) {
    const gb::Garbing r = gb::garb(g_atoms);
    benchmark::DoNotOptimize(r.m2.mesh.n_faces());
    state.counters["m2_vertices"] = static_cast<double>(r.m2.mesh.n_vertices());
    state.counters["cones"] = static_cast<double>(r.g.cone_count());
    state.counters["folds_before_repair"] = static_cast<double>(r.m2.stats.intersecting_before);
  }
}

BENCHMARK(target_shape)->Unit(benchmark::kMillisecond)->UseRealTime();
// Argument: 1 = wrap G (cones rt, the default), 0 = the balls alone.
BENCHMARK(octree_and_m1)
    ->ArgName("cones")
    ->Arg(1)
    ->Arg(0)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(whole_garbing)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  return mg::bench::run_benchmarks(
      argc, argv, "garbing_bench", "--atoms", [](const std::string& path) {
        if (path.empty())
          throw mg::InvalidInput("usage: garbing_bench --atoms FILE.ma [benchmark options]");
        g_atoms = mg::read_medial_surface(path);
      });
}
