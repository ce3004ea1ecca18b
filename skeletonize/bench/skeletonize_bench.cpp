// Benchmarks of skeletonize and of the union-of-balls topology.
//   skeletonize_bench [--mesh FILE] [Google Benchmark options]
// Default mesh: the reference bumpy torus (126 x 126 grid, 15,876 vertices). Cases: its
// vertices as samples; vertices plus random face points up to 100,000 samples (the issue's
// target: under 3 s on 2 cores); each at 1 and 2 threads (same run: compare the ratio). Then
// union_topology of the vertex skeleton's atoms. Then simplify_medial_mesh of the vertex poles
// with connectivity (--merge-tol 0 --clamp-radius: 15,772 poles on the bumpy torus) down to
// 100, 300, 1,000 and 3,000 atoms at 2 threads, and 300 at 1 (issue 19's target: 300 in under
// 2 s on 2 cores); counters: the phases' seconds. The union's dual complex comes with the
// skeleton (skeletonize builds it from its own regular triangulation), as in
// `skeletonize --simplify`.
#include "core/errors.h"
#include "core/mesh_io.h"
#include "core/shapes.h"
#include "skeletonize/poles.h"
#include "skeletonize/simplify.h"
#include "skeletonize/union_topology.h"

#include <tbb/global_control.h>
#include "bench_main.h"

#include <cstring>
#include <iostream>

namespace {

mg::PolygonSoup g_mesh;

std::size_t used_vertices(const mg::PolygonSoup& mesh) {
  std::vector<char> used(mesh.points.size(), 0);
  for (const auto& f : mesh.faces)
    for (int i : f) used[i] = 1;
  return static_cast<std::size_t>(std::count(used.begin(), used.end(), 1));
}

/// Args: total samples (0: the vertices only), threads.
void skeletonize(benchmark::State& state) {
  mg::skeletonize::SkeletonOptions opt;
  const auto total = static_cast<std::size_t>(state.range(0));
  const std::size_t vertices = used_vertices(g_mesh);
  opt.random_samples = total > vertices ? total - vertices : 0;
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<std::size_t>(state.range(1)));
  mg::skeletonize::SkeletonStats stats;
  for (auto _ : state) stats = mg::skeletonize::skeletonize(g_mesh, opt, "bench").stats;
  state.counters["samples"] = static_cast<double>(stats.samples);
  state.counters["atoms"] = static_cast<double>(stats.atoms);
  state.counters["delaunay_s"] = stats.seconds_delaunay;
  state.counters["poles_s"] = stats.seconds_poles;
  state.counters["merge_s"] = stats.seconds_merge;
  state.counters["distances_s"] = stats.seconds_distances;
}

void union_topology(benchmark::State& state) {
  const auto atoms = mg::skeletonize::skeletonize(g_mesh, {}, "bench").atoms;
  for (auto _ : state) benchmark::DoNotOptimize(mg::skeletonize::union_topology(atoms));
  state.counters["atoms"] = static_cast<double>(atoms.atoms.size());
}

/// Args: target atoms, threads. The skeleton is built once, outside the timing.
void simplify(benchmark::State& state) {
  static const mg::skeletonize::Skeleton skeleton = [] {
    mg::skeletonize::SkeletonOptions opt;
    opt.merge_tol = 0;
    opt.clamp_radius = true;
    opt.connectivity = true;
    return mg::skeletonize::skeletonize(g_mesh, opt, "bench");
  }();
  mg::skeletonize::SimplifyOptions opt;
  opt.target_atoms = static_cast<std::size_t>(state.range(0));
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                            static_cast<std::size_t>(state.range(1)));
  mg::skeletonize::SimplifyStats stats;
  for (auto _ : state)
    stats = mg::skeletonize::simplify_medial_mesh(g_mesh, skeleton.atoms, skeleton.cells, opt,
                                                  skeleton.samples, skeleton.atom_of_sample,
                                                  &*skeleton.union_complex)
                .stats;
  state.counters["poles"] = static_cast<double>(stats.atoms_before);
  state.counters["atoms"] = static_cast<double>(stats.atoms_after);
  state.counters["setup_s"] = stats.seconds_setup;
  state.counters["collapse_s"] = stats.seconds_collapse;
}

BENCHMARK(skeletonize)
    ->ArgNames({"samples", "threads"})
    ->Args({0, 1})
    ->Args({0, 2})
    ->Args({100000, 1})
    ->Args({100000, 2})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(union_topology)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(simplify)
    ->ArgNames({"atoms", "threads"})
    ->Args({100, 2})
    ->Args({300, 2})
    ->Args({1000, 2})
    ->Args({3000, 2})
    ->Args({300, 1})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

int main(int argc, char** argv) {
  return mg::bench::run_benchmarks(
      argc, argv, "skeletonize_bench", "--mesh", [](const std::string& path) {
        g_mesh = path.empty() ? mg::make_bumpy_torus(126, 126, 1.0, 0.35, 0.1, 12, 6)
                              : mg::read_polygon_soup(path);
      });
}
