// studio_bench: the studio's frame time (median, p95, max), headless, with a 50,000-point sketch
// and a 100,000-triangle surface in view, idle and while a surfacing job runs in the background;
// MSAA off and 4x. The frame is the studio's own (HeadlessStudio::frame: input, panel, view
// update, draw, wait, readback). Also: frames from trigger release to the stroke on screen.
// Then the headset's frame (HeadsetStudio::step: wait, controller, update, both eyes drawn and
// handed over) through the test OpenXR runtime of tests/xr, each eye WxH, the same scene in front
// of its head.
//
//   studio_bench [--frames N] [--size WxH] [--device NAME]      (defaults: 120, 1280x720)

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "tests/support/shapes.h"
#include "tools/sketchsurf-studio/run.h"

namespace {

using namespace sketchsurf;

/// 100 strokes of 500 points (50,000 points) around the tube of a torus, like a dense VR capture.
Sketch ring_sketch() { return testing::torus_ring_sketch(100, 500); }

/// A torus of 100,000 triangles, 8 regions around it.
SurfaceResult torus_surface() {
  SurfaceResult r;
  r.mesh = testing::torus_mesh(500, 100, 0.5, 0.2);
  for (auto v : r.mesh.vertices()) {
    const auto p = r.mesh.point(v);
    const double a = std::atan2(p[1], p[0]) + M_PI;
    r.labels.push_back(std::min(7, int(a / (2.0 * M_PI) * 8)));
  }
  return r;
}

struct Times {
  double median = 0, p95 = 0, max = 0;
  int over_100ms = 0;
  std::size_t frames = 0;
};

Times times(std::vector<double> ms) {
  Times t;
  if (ms.empty()) return t;
  std::sort(ms.begin(), ms.end());
  t.frames = ms.size();
  t.median = ms[ms.size() / 2];
  t.p95 = ms[std::min(ms.size() - 1, std::size_t(0.95 * double(ms.size())))];
  t.max = ms.back();
  t.over_100ms = int(std::count_if(ms.begin(), ms.end(), [](double v) { return v > 100.0; }));
  return t;
}

void print(const char* what, int msaa, const Times& t) {
  std::printf("%-34s MSAA %d  %4zu frames  median %7.2f ms  p95 %7.2f ms  max %7.2f ms  >100 ms: %d\n", what,
              msaa, t.frames, t.median, t.p95, t.max, t.over_100ms);
  std::fflush(stdout);
}

/// The headset's frame loop through the test runtime, on the scene moved in front of its head
/// (eyes at 1.6 m looking down -z): `frames` frames after 5 of warm-up, MSAA off.
void headset(studio::StudioOptions o, int frames, Sketch sketch, SurfaceResult surface) {
  if (!std::filesystem::exists(SKETCHSURF_TEST_XR_RUNTIME)) {
    std::printf("headset: skipped (no test runtime at %s)\n", SKETCHSURF_TEST_XR_RUNTIME);
    return;
  }
  setenv("XR_RUNTIME_JSON", SKETCHSURF_TEST_XR_RUNTIME, 1);
  setenv("SKETCHSURF_TEST_XR_FRAMES", "1000000", 1);
  setenv("SKETCHSURF_TEST_XR_SIZE", (std::to_string(o.width) + "x" + std::to_string(o.height)).c_str(), 1);
  const Eigen::Vector3d ahead(0.0, 1.5, -1.2);
  for (Stroke& stroke : sketch.strokes)
    for (auto& p : stroke.points) p += ahead;
  for (auto v : surface.mesh.vertices()) surface.mesh.point(v) += OpenMesh::Vec3d(ahead.x(), ahead.y(), ahead.z());
  o.msaa = 1;
  studio::Log log;
  log.quiet = true;
  studio::HeadsetStudio xr(o, log);
  auto& session = xr.studio().session();
  for (const Stroke& stroke : sketch.strokes) session.add_stroke(stroke);
  session.set_result(surface);
  std::vector<double> ms;
  for (int i = 0; i < frames + 5; ++i) {
    const std::size_t before = xr.frames();
    const auto start = std::chrono::steady_clock::now();
    if (!xr.step()) break;
    const double t = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (xr.frames() > before && i >= 5) ms.push_back(t);
  }
  std::printf("headset (test OpenXR runtime, 2 eyes of %dx%d):\n", o.width, o.height);
  print("idle, both eyes", 1, times(ms));
  xr.request_exit();
  while (xr.step()) {
  }
}

}  // namespace

int main(int argc, char** argv) {
  studio::StudioOptions o;
  o.headless = true;
  o.no_autosave = true;
  int frames = 120;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--frames")) frames = std::max(1, std::atoi(argv[i + 1]));
    if (!std::strcmp(argv[i], "--size")) std::sscanf(argv[i + 1], "%dx%d", &o.width, &o.height);
    if (!std::strcmp(argv[i], "--device")) o.device = argv[i + 1];
  }
  studio::Log log;
  log.quiet = true;
  const Sketch sketch = ring_sketch();
  const SurfaceResult surface = torus_surface();
  std::printf("studio_bench: %dx%d, %zu stroke points, %zu triangles, %u hardware threads\n", o.width,
              o.height, sketch.point_count(), std::size_t(surface.mesh.n_faces()),
              std::thread::hardware_concurrency());
  try {
    for (int msaa : {1, 4}) {
      o.msaa = msaa;
      studio::HeadlessStudio headless(o, log);
      studio::Studio& s = headless.studio();
      auto& session = s.session();
      for (const Stroke& stroke : sketch.strokes) session.add_stroke(stroke);
      session.set_result(surface);
      s.frame_all(o.width, o.height);
      double now = 0.0;
      const auto run = [&](int n, const auto& keep_going) {
        std::vector<double> ms;
        for (int i = 0; i < n && keep_going(); ++i) ms.push_back(1e3 * headless.frame(now += 1.0 / 60));
        return ms;
      };
      run(5, [] { return true; });  // warm-up: uploads, pipelines
      if (msaa == 1) std::printf("device: %s\n", headless.context().device_info().name.c_str());
      print("idle", msaa, times(run(frames, [] { return true; })));
      auto& view = s.view_options();
      view.strokes = false;
      print("idle, surface only", msaa, times(run(frames / 2, [] { return true; })));
      view.strokes = true;
      view.surface = false;
      print("idle, strokes only", msaa, times(run(frames / 2, [] { return true; })));
      view.surface = true;
      // A surfacing job on the same 50k-point sketch (VIPSS proxy, PEARL, ...): frames while it runs.
      session.surface();
      const auto running = [&] { return session.surface_status().state == session::JobState::Running; };
      print("while surfacing in the background", msaa, times(run(frames, running)));
      session.cancel_surface();
      session.wait_surface(120.0);
      // Trigger release to stroke on screen: the frame that takes the release draws the stroke.
      const std::size_t before = s.view().points();
      input::ControllerState c;
      for (int i = 0; i <= 20; ++i) {
        c.time_s = now + 0.001 * i;
        c.pose.position = {-0.3 + 0.03 * i, 0.0, 0.4};
        c.set(input::Button::Draw, true);
        c.trigger = 1.0f;
        session.apply(c);
      }
      c.set(input::Button::Draw, false);
      session.apply(c);
      headless.frame(now += 1.0 / 60);
      std::printf("release to stroke shown: %s\n",
                  s.view().points() > before ? "the same frame" : "LATER than the releasing frame");
    }
    headset(o, frames, sketch, surface);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "studio_bench: %s\n", e.what());
    return 1;
  }
  return 0;
}
