// Segmentation pipeline at the scale: a rounded-cube proxy of 40,962 vertices (icosphere
// level 6; the issue asks for ~30,000) and the cube sketch resampled to ~10,000 stroke points.
// Stages: association (App. A), initialisation (association + App. C simplification + spectral
// clusterings + initial fits), one PEARL run with and without the simplification, 10 restarts
// (wall time, all threads).
// Real sketches (BM_Real/<name>): when SKETCHSURF_BENCH_PROXIES names a folder of proxies
// <name>.l3.ply (made by `sketchsurf proxy --lambda 1e-3 SKETCH -o <name>.l3.ply`), every CASSIE
// and VNS sketch of ../shared/data that has one is segmented as `sketchsurf segment` does (cleaned
// sketch, default options: 10 restarts, all threads). Counters: association + initialisation
// seconds (setup_s), PEARL seconds (pearl_s), total energy (Eq. 1) and regions. Skipped when the
// folder or the data is missing.
// Run: segment_bench [--benchmark_filter=...]; peak RSS with /usr/bin/time -v.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "surfacing/segment/pearl.h"
#include "surfacing/sketch/io/mesh_io.h"
#include "surfacing/sketch/io/sketch_io.h"
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

namespace fs = std::filesystem;

void BM_Real(benchmark::State& state, const fs::path& sketch_file, const fs::path& proxy_file) {
  Sketch sketch = read_sketch(sketch_file);
  clean(sketch);
  const TriMesh proxy = read_mesh(proxy_file);
  Segmentation s;
  double setup_s = 0.0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    Segmenter segmenter(sketch, proxy);
    setup_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    s = segmenter.run();
  }
  state.counters["proxy_vertices"] = static_cast<double>(proxy.n_vertices());
  state.counters["setup_s"] = setup_s;
  state.counters["pearl_s"] = s.summary.segmentation_s;
  state.counters["energy"] = s.summary.energy.total;
  state.counters["regions"] = static_cast<double>(s.models.size());
}

// One BM_Real per sketch of ../shared/data with a proxy in $SKETCHSURF_BENCH_PROXIES.
void register_real_sketches() {
  const char* proxies = std::getenv("SKETCHSURF_BENCH_PROXIES");
  const fs::path data = fs::path(__FILE__).parent_path() / "../../../shared/data";
  if (!proxies || !fs::is_directory(proxies) || !fs::is_directory(data)) return;
  for (const char* dir : {"cassie", "vns"}) {
    if (!fs::is_directory(data / dir)) continue;
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(data / dir))
      if (entry.path().extension() == ".curves" || entry.path().extension() == ".obj")
        files.push_back(entry.path());
    std::sort(files.begin(), files.end());
    for (const fs::path& file : files) {
      const fs::path proxy = fs::path(proxies) / (file.stem().string() + ".l3.ply");
      if (!fs::exists(proxy)) continue;
      benchmark::RegisterBenchmark(("BM_Real/" + file.stem().string()).c_str(), BM_Real, file, proxy)
          ->Unit(benchmark::kMillisecond)
          ->Iterations(1)
          ->UseRealTime();
    }
  }
}

}  // namespace
}  // namespace sketchsurf

int main(int argc, char** argv) {
  sketchsurf::register_real_sketches();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
