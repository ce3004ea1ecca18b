// Benchmark of `evaluate distance`: two ~100k-face meshes at the default sample count
// (max(1e6, 10 (V_a + V_b)) per side). Target: under 2 s on 2 cores.
//   build/bench/evaluate_bench --benchmark_filter=Distance --benchmark_repetitions=3
#include "core/shapes.h"
#include "evaluate/mesh_distance.h"

#include <benchmark/benchmark.h>
#include <tbb/global_control.h>

namespace {

namespace ev = mg::evaluate;

/// A smooth torus (224 x 224: 100352 faces) and a bumpy one close to it (100352 faces).
const mg::PolygonSoup& torus() {
  static const mg::PolygonSoup t = mg::make_torus(224, 224, 1.0, 0.3);
  return t;
}
const mg::PolygonSoup& bumpy_torus() {
  static const mg::PolygonSoup t = mg::make_bumpy_torus(224, 224, 1.0, 0.3, 0.05, 12, 6);
  return t;
}

/// The whole `distance` computation without file input/output: sampling, two AABB trees,
/// both directions. Argument: worker threads (1, then 2: the ratio in one run).
void BM_DistanceDefaultSamples(benchmark::State& state) {
  const tbb::global_control threads(tbb::global_control::max_allowed_parallelism,
                                    static_cast<std::size_t>(state.range(0)));
  ev::MeshDistance r;
  for (auto _ : state) {
    r = ev::mesh_distance(torus(), bumpy_torus());
    benchmark::DoNotOptimize(r);
  }
  state.counters["faces_each"] = static_cast<double>(torus().faces.size());
  state.counters["samples_per_side"] = static_cast<double>(r.samples);
  state.counters["hausdorff_pct"] = ev::percent_of_diagonal(r.distance.hausdorff, r.diagonal);
}
BENCHMARK(BM_DistanceDefaultSamples)
    ->ArgName("threads")
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

/// The parts: building one AABB tree, and sampling one side.
void BM_BuildTriangleIndex(benchmark::State& state) {
  for (auto _ : state) {
    ev::TriangleIndex index(bumpy_torus());
    benchmark::DoNotOptimize(&index);
  }
}
BENCHMARK(BM_BuildTriangleIndex)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_SampleOneSide(benchmark::State& state) {
  ev::SamplingOptions opt;
  opt.count = ev::default_sample_count(torus(), bumpy_torus());
  for (auto _ : state) {
    ev::SurfaceSamples s = ev::sample_surface(torus(), opt, "torus");
    benchmark::DoNotOptimize(s);
  }
}
BENCHMARK(BM_SampleOneSide)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
