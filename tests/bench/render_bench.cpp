// Renderer speed on lavapipe (or the machine's GPU): a 1024x1024 frame of 100,000 stroke points
// (200 strokes) plus a 200,000-triangle mesh, readback included; start-up from instance to first frame; scene
// building and upload. Peak RSS: run under /usr/bin/time -v.

#include <benchmark/benchmark.h>

#include <cmath>
#include <ctime>

#include "engine/render/headless.h"
#include "tests/support/shapes.h"

namespace {

using namespace sketchsurf;

/// 200 strokes of 500 points (100,000 points), each a circle around the torus's tube, densely
/// sampled like a raw VR capture: the ribbons cover about 60% of the torus's area, as strokes
/// on a sketched surface do (a sketch's strokes are not a dense fill).
Sketch ring_sketch() { return testing::torus_ring_sketch(200, 500); }

struct BigScene {
  Sketch sketch = ring_sketch();
  TriMesh mesh = testing::torus_mesh(500, 200, 0.5, 0.2);  // 200,000 triangles
};

const BigScene& big_scene() {
  static const BigScene scene;
  return scene;
}

vk::ContextOptions quiet() {
  vk::ContextOptions options;
  options.validation = vk::Validation::Off;
  return options;
}

// Arguments: MSAA samples (1 or 4); what to draw (0 everything, 1 mesh only, 2 strokes only).
void BM_Frame1024(benchmark::State& state) {
  const auto& big = big_scene();
  const vk::Context context(quiet());
  render::HeadlessRenderer renderer(context, 1024, 1024,
                                    static_cast<VkSampleCountFlagBits>(state.range(0)));
  const auto geometry = render::build_scene(big.sketch, &big.mesh);
  renderer.set_scene(geometry);  // upload once, draw many
  const auto camera = render::fit_camera(geometry.bounds, render::View::Iso, 1.0);
  render::DrawOptions draw;
  draw.mesh = state.range(1) != 2;
  draw.strokes = state.range(1) != 1;
  int frame = 0;
  // CPU time of the whole process (lavapipe's worker threads included): on a loaded machine the
  // wall time says little, CPU time / cores is what an idle machine would take.
  const std::clock_t cpu_start = std::clock();
  for (auto _ : state) {
    auto image = renderer.render(render::orbit(camera, 0.01 * frame++), draw);
    benchmark::DoNotOptimize(image.pixels.data());
  }
  state.counters["process_cpu_ms"] = benchmark::Counter(
      1e3 * double(std::clock() - cpu_start) / CLOCKS_PER_SEC / double(state.iterations()));
  state.counters["ribbon_points"] = double(geometry.ribbon_points);
  state.counters["stroke_points"] = double(geometry.stroke_points);
  state.counters["triangles"] = double(geometry.mesh_indices.size() / 3);
}
BENCHMARK(BM_Frame1024)
    ->ArgsProduct({{4, 1}, {0, 1, 2}})
    ->ArgNames({"msaa", "draw"})
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime()
    ->MinTime(2.0);

void BM_StartupToFirstFrame(benchmark::State& state) {
  const auto geometry = render::build_scene(testing::cube_sketch());
  for (auto _ : state) {
    const vk::Context context(quiet());
    render::HeadlessRenderer renderer(context, 1024, 1024);
    renderer.set_scene(geometry);
    auto image = renderer.render(render::fit_camera(geometry.bounds, render::View::Iso, 1.0));
    benchmark::DoNotOptimize(image.pixels.data());
  }
}
BENCHMARK(BM_StartupToFirstFrame)->Unit(benchmark::kMillisecond)->UseRealTime()->Iterations(5);

void BM_BuildScene(benchmark::State& state) {
  const auto& big = big_scene();
  for (auto _ : state) {
    auto geometry = render::build_scene(big.sketch, &big.mesh);
    benchmark::DoNotOptimize(geometry.mesh_vertices.data());
  }
}
BENCHMARK(BM_BuildScene)->Unit(benchmark::kMillisecond)->UseRealTime();

void BM_Upload(benchmark::State& state) {
  const auto& big = big_scene();
  const vk::Context context(quiet());
  render::HeadlessRenderer renderer(context, 64, 64);
  const auto geometry = render::build_scene(big.sketch, &big.mesh);
  for (auto _ : state) renderer.set_scene(geometry);
}
BENCHMARK(BM_Upload)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
