// Writing a 1,000,000-point sketch as .json with every attribute at full precision (reading it is
// in io_bench). Peak RSS: /usr/bin/time -v json_bench ("Maximum resident set size").

#include <benchmark/benchmark.h>

#include <filesystem>
#include <random>

#include "surfacing/sketch/io/json.h"

namespace sketchsurf {
namespace {

/// 1000 strokes of 1000 points, with what a converted .tilt carries: orientations, pressures,
/// timestamps, colour, brush.
Sketch million_point_sketch() {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Sketch sketch;
  for (int s = 0; s < 1000; ++s) {
    Stroke stroke;
    stroke.id = s;
    stroke.width = 0.01;
    stroke.brush = "{89d104cd-d012-426b-b5b3-bbaee63ac43c}";
    Eigen::Vector3d p(u(rng), u(rng), u(rng));
    for (int i = 0; i < 1000; ++i) {
      p += 0.001 * Eigen::Vector3d(u(rng), u(rng), u(rng));
      stroke.points.push_back(p);
      stroke.orientations.push_back(Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized());
      stroke.pressures.push_back(static_cast<float>(0.5 + 0.5 * u(rng)));
      stroke.timestamps_ms.push_back(static_cast<std::uint32_t>(s * 1000 + i));
    }
    sketch.strokes.push_back(std::move(stroke));
  }
  return sketch;
}

std::filesystem::path bench_file() {
  return std::filesystem::temp_directory_path() / "sketchsurf-bench-1M.json";
}

void WriteJson(benchmark::State& state) {
  const Sketch sketch = million_point_sketch();
  for (auto _ : state) write_json(sketch, bench_file());
  state.counters["MB"] = static_cast<double>(std::filesystem::file_size(bench_file())) / 1e6;
}
BENCHMARK(WriteJson)->Unit(benchmark::kMillisecond)->Repetitions(3)->ReportAggregatesOnly(true);

}  // namespace
}  // namespace sketchsurf

BENCHMARK_MAIN();
