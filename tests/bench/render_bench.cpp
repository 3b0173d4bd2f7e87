// Renderer speed on lavapipe (or the machine's GPU): a 1024x1024 frame of 100,000 stroke points
// plus a 200,000-triangle mesh, readback included; start-up from instance to first frame; scene
// building and upload. Peak RSS: run under /usr/bin/time -v.

#include <benchmark/benchmark.h>

#include <cmath>

#include "engine/render/headless.h"
#include "tests/support/shapes.h"

namespace {

using namespace sketchsurf;

/// 200 helical strokes of 500 points wound around the torus (100,000 points).
Sketch helix_sketch() {
  Sketch sketch;
  for (int s = 0; s < 200; ++s) {
    Stroke stroke;
    const double phase = 2.0 * M_PI * s / 200.0;
    for (int i = 0; i < 500; ++i) {
      const double t = 2.0 * M_PI * i / 499.0;
      const double u = phase + t, v = 12.0 * t;
      const double r = 0.5 + 0.21 * std::cos(v);
      stroke.points.emplace_back(r * std::cos(u), r * std::sin(u), 0.21 * std::sin(v));
    }
    sketch.strokes.push_back(std::move(stroke));
  }
  return sketch;
}

struct BigScene {
  Sketch sketch = helix_sketch();
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

void BM_Frame1024(benchmark::State& state) {
  const auto& big = big_scene();
  const vk::Context context(quiet());
  render::HeadlessRenderer renderer(context, 1024, 1024);
  const auto geometry = render::build_scene(big.sketch, &big.mesh);
  renderer.set_scene(geometry);  // upload once, draw many
  const auto camera = render::fit_camera(geometry.bounds, render::View::Iso, 1.0);
  int frame = 0;
  for (auto _ : state) {
    auto image = renderer.render(render::orbit(camera, 0.01 * frame++));
    benchmark::DoNotOptimize(image.pixels.data());
  }
  state.counters["stroke_points"] = double(geometry.stroke_points);
  state.counters["triangles"] = double(geometry.mesh_indices.size() / 3);
  state.counters["msaa"] = double(renderer.samples());
}
BENCHMARK(BM_Frame1024)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(3.0);

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
