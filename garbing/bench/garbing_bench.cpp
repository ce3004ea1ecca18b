// Benchmarks of the garbing stages on a medial surface file.
//   garbing_bench --atoms FILE.ma [Google Benchmark options]
// Reports octree + M1 wrapping G (balls and cones: the default), octree + M1 over the balls
// alone (--cones none: issue 4's measurement), and the whole garbing (octree + M1 + M2).
#include "garbing/coarse_mesh.h"
#include "garbing/errors.h"
#include "garbing/octree.h"
#include "garbing/refine_mesh.h"

#include <benchmark/benchmark.h>

#include <cstring>
#include <iostream>

namespace {

mg::MedialSurface g_atoms;

void octree_and_m1(benchmark::State& state) {
  mg::OctreeOptions opt;
  if (state.range(0) == 0) opt.cones.source = mg::ConeSource::none;
  for (auto _ : state) {
    const mg::Octree tree = mg::build_octree(g_atoms, opt);
    const mg::CoarseMesh m1 = mg::extract_coarse_mesh(tree);
    benchmark::DoNotOptimize(m1.mesh.n_faces());
    state.counters["m1_faces"] = static_cast<double>(m1.mesh.n_faces());
    state.counters["leaves"] = static_cast<double>(tree.leaves.size());
  }
}

void whole_garbing(benchmark::State& state) {
  mg::RefineOptions opt;
  for (auto _ : state) {
    const mg::Octree tree = mg::build_octree(g_atoms);
    const mg::CoarseMesh m1 = mg::extract_coarse_mesh(tree);
    const mg::RefinedMesh m2 = mg::refine_mesh(m1, tree, g_atoms, opt);
    benchmark::DoNotOptimize(m2.mesh.n_faces());
    state.counters["m2_vertices"] = static_cast<double>(m2.mesh.n_vertices());
    state.counters["cones"] = static_cast<double>(m2.stats.cones);
    state.counters["folds_before_repair"] = static_cast<double>(m2.stats.intersecting_before);
  }
}

// Argument: 1 = wrap G (cones rt, the default), 0 = the balls alone.
BENCHMARK(octree_and_m1)->ArgName("cones")->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(whole_garbing)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  std::string path;
  std::vector<char*> rest = {argv[0]};
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--atoms") == 0 && i + 1 < argc)
      path = argv[++i];
    else
      rest.push_back(argv[i]);
  }
  if (path.empty()) {
    std::cerr << "usage: garbing_bench --atoms FILE.ma [benchmark options]\n";
    return 2;
  }
  try {
    g_atoms = mg::read_medial_surface(path);
  } catch (const mg::Error& e) {
    std::cerr << "garbing_bench: " << e.what() << '\n';
    return 2;
  }
  int n = static_cast<int>(rest.size());
  benchmark::Initialize(&n, rest.data());
  benchmark::RunSpecifiedBenchmarks();
  return 0;
}
