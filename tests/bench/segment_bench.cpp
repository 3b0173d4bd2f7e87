// Segmentation pipeline at the scale: a rounded-cube proxy of 40,962 vertices (icosphere
// level 6; the issue asks for ~30,000) and the cube sketch resampled to ~10,000 stroke points.
// Stages: association (App. A), initialisation (association + App. C simplification + spectral
// clusterings + initial fits), one PEARL run with and without the simplification, 10 restarts
// (wall time, all threads).
// Run: segment_bench [--benchmark_filter=...]; peak RSS with /usr/bin/time -v.

#include <benchmark/benchmark.h>

#include "surfacing/segment/pearl.h"
#include "tests/support/shapes.h"

namespace sketchsurf {
namespace {

struct Input {
  Sketch sketch;
  TriMesh proxy;
  Input() {
    sketch = testing::cube_sketch(1.0);
    resample(sketch, sketch.total_length() / 10000.0);
    proxy = testing::rounded_box_mesh(6, Eigen::Vector3d(0.5, 0.5, 0.5), 0.02);
  }
};

const Input& input() {
  static const Input in;
  return in;
}

void BM_Association(benchmark::State& state) {
  const Input& in = input();
  std::size_t points = 0;
  for (auto _ : state) {
    const StrokeGraph g = associate(in.sketch, in.proxy);
    points = g.association_count();
    benchmark::DoNotOptimize(points);
  }
  state.counters["proxy_vertices"] = static_cast<double>(in.proxy.n_vertices());
  state.counters["stroke_points"] = static_cast<double>(in.sketch.point_count());
  state.counters["associated"] = static_cast<double>(points);
}

void BM_Initialisation(benchmark::State& state) {
  const Input& in = input();
  for (auto _ : state) {
    Segmenter segmenter(in.sketch, in.proxy);
    benchmark::DoNotOptimize(&segmenter);
  }
}

void BM_Pearl(benchmark::State& state) {
  const Input& in = input();
  SegmentOptions options;
  options.restarts = static_cast<int>(state.range(0));
  options.simplify = state.range(1) != 0;
  Segmenter segmenter(in.sketch, in.proxy, options);
  Segmentation s;
  for (auto _ : state) s = segmenter.run();
  state.counters["regions"] = static_cast<double>(s.models.size());
  state.counters["iterations"] = s.summary.iterations;
  state.counters["graph_vertices"] = s.summary.graph_vertices;
  state.counters["initial_models"] = s.summary.initial_models;
}

BENCHMARK(BM_Association)->Unit(benchmark::kMillisecond)->Iterations(1)->Repetitions(3)
    ->ReportAggregatesOnly(true);
BENCHMARK(BM_Initialisation)->Unit(benchmark::kMillisecond)->Iterations(1)->Repetitions(3)
    ->ReportAggregatesOnly(true);
// Args: restarts, App. C simplification on/off.
BENCHMARK(BM_Pearl)->Args({1, 1})->Args({1, 0})->Args({10, 1})->Unit(benchmark::kMillisecond)->Iterations(1)->Repetitions(3)
    ->ReportAggregatesOnly(true)->UseRealTime();

}  // namespace
}  // namespace sketchsurf

BENCHMARK_MAIN();
