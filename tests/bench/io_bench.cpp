// Reading a generated 1,000,000-point sketch as .tilt and as .json (issue 2: under 1 s and under
// 200 MB each). The first run writes the files into the temp directory; measure a later run, one
// benchmark per process, so that peak RSS is the reader's own:
//   io_bench --benchmark_filter=WriteTilt      (makes the files)
//   /usr/bin/time -v io_bench --benchmark_filter=ReadTilt   ("Maximum resident set size")
//   /usr/bin/time -v io_bench --benchmark_filter=ReadJson

#include <benchmark/benchmark.h>

#include <cmath>
#include <filesystem>

#include "surfacing/sketch/io/json.h"
#include "surfacing/sketch/io/tilt.h"

namespace sketchsurf {
namespace {

namespace fs = std::filesystem;

/// 1,000 smooth strokes of 1,000 points with orientations, pressures and 90 Hz timestamps, about
/// a metre across: what an Open Brush session of that size holds.
Sketch million_point_sketch() {
  Sketch sketch;
  sketch.strokes.reserve(1000);
  std::uint32_t time = 0;
  for (int s = 0; s < 1000; ++s) {
    Stroke stroke;
    stroke.width = 0.004;
    stroke.brush = "429ed64a-4e97-4466-84d3-145a861ef684";
    stroke.layer = static_cast<std::uint32_t>(s % 3);
    const double phase = 0.37 * s, height = 0.8 + 0.0005 * s;
    for (int i = 0; i < 1000; ++i) {
      const double t = i / 999.0;
      stroke.points.emplace_back(0.5 * std::cos(phase + 6 * t), height + 0.1 * t,
                                 0.5 * std::sin(phase + 6 * t));
      stroke.orientations.emplace_back(Eigen::AngleAxisd(phase + 6 * t, Eigen::Vector3d::UnitY()));
      stroke.pressures.push_back(static_cast<float>(0.5 + 0.5 * std::sin(9 * t)));
      stroke.timestamps_ms.push_back(time += 11);
    }
    sketch.strokes.push_back(std::move(stroke));
  }
  return sketch;
}

fs::path bench_file(const char* extension) {
  return fs::temp_directory_path() / (std::string("sketchsurf-io-bench-1M") + extension);
}

void ensure_files() {
  if (fs::exists(bench_file(".tilt")) && fs::exists(bench_file(".json"))) return;
  const Sketch sketch = million_point_sketch();
  write_tilt(sketch, bench_file(".tilt"));
  write_json(sketch, bench_file(".json"));
}

void WriteTilt(benchmark::State& state) {
  const Sketch sketch = million_point_sketch();
  for (auto _ : state) write_tilt(sketch, bench_file(".tilt"));
  if (!fs::exists(bench_file(".json"))) write_json(sketch, bench_file(".json"));
  state.counters["MB"] = static_cast<double>(fs::file_size(bench_file(".tilt"))) / 1e6;
}
BENCHMARK(WriteTilt)->Unit(benchmark::kMillisecond)->Iterations(1)->Repetitions(5)
    ->ReportAggregatesOnly(true);

template <Sketch (*Read)(const fs::path&, Warnings*)>
void read_file(benchmark::State& state, const char* extension) {
  ensure_files();
  for (auto _ : state) {
    const Sketch sketch = Read(bench_file(extension), nullptr);
    benchmark::DoNotOptimize(sketch.strokes.data());
    state.counters["points"] = static_cast<double>(sketch.point_count());
  }
  state.counters["MB"] = static_cast<double>(fs::file_size(bench_file(extension))) / 1e6;
}
void ReadTilt(benchmark::State& state) { read_file<read_tilt>(state, ".tilt"); }
void ReadJson(benchmark::State& state) { read_file<read_json>(state, ".json"); }
BENCHMARK(ReadTilt)->Unit(benchmark::kMillisecond)->Iterations(1)->Repetitions(7)
    ->ReportAggregatesOnly(true);
BENCHMARK(ReadJson)->Unit(benchmark::kMillisecond)->Iterations(1)->Repetitions(7)
    ->ReportAggregatesOnly(true);

}  // namespace
}  // namespace sketchsurf

BENCHMARK_MAIN();
