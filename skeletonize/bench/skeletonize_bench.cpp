// Benchmarks of skeletonize on a mesh file.
//   skeletonize_bench --mesh FILE [Google Benchmark options]
// Runs the mesh's vertices as samples, then the vertices plus random face points up to 100,000
// samples (the target: under 3 s on 2 cores).
#include "garbing/errors.h"
#include "garbing/mesh_io.h"
#include "skeletonize/poles.h"

#include <benchmark/benchmark.h>

#include <cstring>
#include <iostream>

namespace {

mg::PolygonSoup g_mesh;

void run(benchmark::State& state, std::size_t extra) {
  mg::skeletonize::SkeletonOptions opt;
  opt.random_samples = extra;
  for (auto _ : state) {
    const auto s = mg::skeletonize::skeletonize(g_mesh, opt, "bench");
    state.counters["samples"] = static_cast<double>(s.stats.samples);
    state.counters["atoms"] = static_cast<double>(s.stats.atoms);
  }
}

void vertices(benchmark::State& state) { run(state, 0); }
void hundred_thousand(benchmark::State& state) {
  std::size_t v = 0;
  std::vector<char> used(g_mesh.points.size(), 0);
  for (const auto& f : g_mesh.faces)
    for (int i : f) used[i] = 1;
  for (char u : used) v += u;
  run(state, v < 100000 ? 100000 - v : 0);
}

BENCHMARK(vertices)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(hundred_thousand)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  std::string path;
  std::vector<char*> rest = {argv[0]};
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--mesh") == 0 && i + 1 < argc)
      path = argv[++i];
    else
      rest.push_back(argv[i]);
  }
  if (path.empty()) {
    std::cerr << "usage: skeletonize_bench --mesh FILE [benchmark options]\n";
    return 2;
  }
  try {
    g_mesh = mg::read_polygon_soup(path);
  } catch (const mg::Error& e) {
    std::cerr << "skeletonize_bench: " << e.what() << '\n';
    return 2;
  }
  int n = static_cast<int>(rest.size());
  benchmark::Initialize(&n, rest.data());
  benchmark::RunSpecifiedBenchmarks();
  return 0;
}
