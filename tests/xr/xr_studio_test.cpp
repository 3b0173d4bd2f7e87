// sketchsurf-studio --xr through the test OpenXR runtime (tests/xr/test_runtime.cpp) with the
// OpenXR core validation layer and the Vulkan validation layer on: the session goes through its
// life cycle to FOCUSED and ends cleanly, a scripted controller draws a stroke that ends up in the
// sketch with the track's points, each eye's image shows it where an independent pinhole model
// puts it, and nothing is reported by either layer. Without a runtime or a headset: a one-line
// message and the desktop studio (headless here).

#include <openxr/openxr.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>

#include "engine/input/track.h"
#include "surfacing/sketch/io/sketch_io.h"
#include "tests/render/render_support.h"
#include "tests/studio/studio_run.h"

namespace sketchsurf::testing {
namespace {

using input::Button;
using input::ControllerState;

/// The test runtime's head and eyes (test_runtime.cpp, xrLocateViews).
struct EyeModel {
  double x;                      // eye position (x, 1.6, 0), looking down -z
  double left, right, up, down;  // field of view, radians
};
const EyeModel kEyes[2] = {{-0.032, -0.80, 0.70, 0.72, -0.78}, {0.032, -0.70, 0.80, 0.72, -0.78}};
constexpr int kWidth = 512, kHeight = 448;

/// A track that moves the controller in, draws one stroke of 17 samples at 64 Hz (every
/// coordinate exact in float) and lets go; the stroke's expected points come out in `stroke`.
input::Track stroke_track(std::vector<Eigen::Vector3d>* stroke) {
  input::Track track;
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitX()));
  Eigen::Quaterniond q(float(turn.w()), float(turn.x()), float(turn.y()), float(turn.z()));
  for (int k = 0; k < 28; ++k) {
    ControllerState s;
    s.time_s = k / 64.0;
    const int i = std::clamp(k - 4, 0, 20);
    s.pose.position = {-0.25 + i / 32.0, 1.5 + (i % 2) / 64.0, -0.5 - i / 128.0};
    s.pose.orientation = q;
    const bool draw = k >= 4 && k < 21;
    s.trigger = draw ? 0.8f : 0.0f;
    s.set(Button::Draw, draw);
    if (draw || k == 21) stroke->push_back(s.pose.position);  // the release sample ends the stroke
    track.events.push_back({s.time_s, s, std::nullopt});
  }
  return track;
}

struct Ppm {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
};

Ppm read_ppm(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::string magic;
  int max = 0;
  Ppm p;
  in >> magic >> p.width >> p.height >> max;
  in.get();
  p.rgb.resize(std::size_t(p.width) * p.height * 3);
  in.read(reinterpret_cast<char*>(p.rgb.data()), std::streamsize(p.rgb.size()));
  EXPECT_EQ(magic, "P6");
  EXPECT_TRUE(in.good()) << file;
  return p;
}

/// Where the independent pinhole model of eye `e` puts `p`, in pixels from the top-left.
Eigen::Vector2d project(const EyeModel& e, const Eigen::Vector3d& p) {
  const double depth = -p.z();
  const double tx = (p.x() - e.x) / depth, ty = (p.y() - 1.6) / depth;
  return {(tx - std::tan(e.left)) / (std::tan(e.right) - std::tan(e.left)) * kWidth,
          (std::tan(e.up) - ty) / (std::tan(e.up) - std::tan(e.down)) * kHeight};
}

/// True when a stroke pixel (dark grey on the white background) lies within `r` pixels of `at`.
bool dark_near(const Ppm& image, const Eigen::Vector2d& at, int r) {
  for (int dy = -r; dy <= r; ++dy)
    for (int dx = -r; dx <= r; ++dx) {
      const int x = int(std::floor(at.x())) + dx, y = int(std::floor(at.y())) + dy;
      if (x < 0 || y < 0 || x >= image.width || y >= image.height) continue;
      const std::uint8_t* px = &image.rgb[(std::size_t(y) * image.width + x) * 3];
      if (px[0] < 90 && px[1] < 90 && px[2] < 90) return true;
    }
  return false;
}

std::size_t dark_pixels(const Ppm& image) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < image.rgb.size(); i += 3)
    n += image.rgb[i] < 90 && image.rgb[i + 1] < 90 && image.rgb[i + 2] < 90;
  return n;
}

/// The environment that points the loader at the test runtime with the core validation layer.
std::string xr_env(const std::filesystem::path& dir, const std::filesystem::path& track,
                   const std::string& extra = "") {
  return "env XR_RUNTIME_JSON=" + quoted(SKETCHSURF_TEST_XR_RUNTIME) +
         " XR_ENABLE_API_LAYERS=XR_APILAYER_LUNARG_core_validation XR_CORE_VALIDATION_EXPORT_TYPE=text"
         " XR_CORE_VALIDATION_FILE_NAME=" +
         quoted(dir / "xr_validation.txt") + " SKETCHSURF_TEST_XR_TRACK=" + quoted(track) +
         " SKETCHSURF_TEST_XR_OUT=" + quoted(dir) + " " + extra;
}

nlohmann::json read_report(const std::filesystem::path& dir) {
  return nlohmann::json::parse(read_text(dir / "report.json"));
}

void expect_no_xr_validation_messages(const std::filesystem::path& dir) {
  const std::string messages = read_text(dir / "xr_validation.txt");  // empty when not written
  EXPECT_EQ(messages.find("VUID"), std::string::npos) << messages;
  EXPECT_EQ(messages.find("rror"), std::string::npos) << messages;
}

TEST(StudioXr, TheCoreValidationLayerReportsMisuseToItsFile) {
  // The check the other tests rely on: with the layer enabled as they enable it, an invalid call
  // (a structure of the wrong type) lands in the file they read.
  const auto dir = scratch_dir("studio_xr_layer_");
  setenv("XR_RUNTIME_JSON", SKETCHSURF_TEST_XR_RUNTIME, 1);
  setenv("XR_ENABLE_API_LAYERS", "XR_APILAYER_LUNARG_core_validation", 1);
  setenv("XR_CORE_VALIDATION_EXPORT_TYPE", "text", 1);
  setenv("XR_CORE_VALIDATION_FILE_NAME", (dir / "xr_validation.txt").c_str(), 1);
  XrInstanceCreateInfo info{XR_TYPE_INSTANCE_CREATE_INFO};
  std::strcpy(info.applicationInfo.applicationName, "layer check");
  info.applicationInfo.apiVersion = XR_MAKE_VERSION(1, 0, 0);
  XrInstance instance = XR_NULL_HANDLE;
  ASSERT_EQ(xrCreateInstance(&info, &instance), XR_SUCCESS);
  XrSystemGetInfo wrong{XR_TYPE_SESSION_CREATE_INFO};  // should be XR_TYPE_SYSTEM_GET_INFO
  wrong.formFactor = XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY;
  XrSystemId system = XR_NULL_SYSTEM_ID;
  EXPECT_EQ(xrGetSystem(instance, &wrong, &system), XR_ERROR_VALIDATION_FAILURE);
  xrDestroyInstance(instance);
  EXPECT_NE(read_text(dir / "xr_validation.txt").find("VUID-XrSystemGetInfo-type-type"), std::string::npos)
      << read_text(dir / "xr_validation.txt");
}

TEST(StudioXr, ScriptedControllerDrawsAStrokeSeenByBothEyes) {
  const auto dir = scratch_dir("studio_xr_");
  std::vector<Eigen::Vector3d> expected;
  input::write_track(stroke_track(&expected), dir / "track.json");
  const CliRun run =
      run_studio("--xr --validation -v --no-autosave --msaa 1 --save " + quoted(dir / "sketch.json"), dir,
                 xr_env(dir, dir / "track.json"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("headset session FOCUSED"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("controller: /interaction_profiles/oculus/touch_controller"), std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find("validation: 0 messages"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find(", 1 haptic ticks"), std::string::npos) << run.err;
  // The layer announces itself on stdout (which run_studio logs too).
  EXPECT_NE(run.err.find("Core Validation output type: text"), std::string::npos)
      << "the layer ran: " << run.err;
  expect_no_xr_validation_messages(dir);

  // The life cycle, in order, and a clean end.
  const nlohmann::json report = read_report(dir);
  const std::vector<std::string> states = report["states"];
  const std::vector<std::string> cycle = {"IDLE",    "READY",        "SYNCHRONIZED", "VISIBLE", "FOCUSED",
                                          "VISIBLE", "SYNCHRONIZED", "STOPPING",     "IDLE",    "EXITING"};
  EXPECT_EQ(states, cycle);
  EXPECT_TRUE(report["stopped_by_runtime"]);
  EXPECT_TRUE(report["session_ended"]);
  EXPECT_TRUE(report["session_destroyed"]);
  EXPECT_TRUE(report["instance_destroyed"]);
  EXPECT_TRUE(report["errors"].empty()) << report["errors"];
  EXPECT_EQ(report["frames_with_layers"], report["frames_ended"]);
  EXPECT_GE(report["frames_ended"].get<int>(), 28);
  // One haptic tick, at the stroke's start (the 5th sample).
  ASSERT_EQ(report["haptics"], 1);
  EXPECT_DOUBLE_EQ(report["haptic_times"][0].get<double>(), 4.0 / 64.0);

  // The stroke: the track's points, exactly (every coordinate is a float).
  const Sketch sketch = read_sketch(dir / "sketch.json");
  ASSERT_EQ(sketch.strokes.size(), 1u);
  const Stroke& s = sketch.strokes[0];
  ASSERT_EQ(s.points.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_LE((s.points[i] - expected[i]).norm(), 1e-9) << i;
  ASSERT_EQ(s.pressures.size(), expected.size());
  EXPECT_FLOAT_EQ(s.pressures.front(), 0.8f);
  EXPECT_FLOAT_EQ(s.pressures.back(), 0.0f) << "the release sample";
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitX()));
  EXPECT_LT(s.orientations.front().angularDistance(turn), 1e-6);

  // Each eye's last image shows the stroke where the pinhole model of that eye puts it.
  ASSERT_EQ(report["images"].size(), 2u);
  for (int e = 0; e < 2; ++e) {
    const Ppm image = read_ppm(dir / ("eye_" + std::to_string(e) + ".ppm"));
    ASSERT_EQ(image.width, kWidth);
    ASSERT_EQ(image.height, kHeight);
    EXPECT_GT(dark_pixels(image), 100u) << "eye " << e;
    EXPECT_EQ(image.rgb[0], 255) << "white background, eye " << e;
    for (std::size_t i = 1; i + 1 < expected.size(); ++i) {
      const Eigen::Vector3d mid = 0.5 * (expected[i] + expected[i - 1]);
      EXPECT_TRUE(dark_near(image, project(kEyes[e], mid), 3)) << "eye " << e << ", segment " << i;
    }
    // Parallax: the other eye's projection of the stroke's start misses this eye's picture of it
    // (the eyes are 64 mm apart, the stroke 0.5 m away: about 20 pixels).
    const Eigen::Vector2d here = project(kEyes[e], expected.front()),
                          there = project(kEyes[1 - e], expected.front());
    EXPECT_GT((here - there).norm(), 10.0);
  }
}

TEST(StudioXr, EveryBoundControllerDrawsTheStroke) {
  for (const char* profile :
       {"/interaction_profiles/khr/simple_controller", "/interaction_profiles/valve/index_controller",
        "/interaction_profiles/htc/vive_controller"}) {
    const auto dir = scratch_dir("studio_xr_profile_");
    std::vector<Eigen::Vector3d> expected;
    input::write_track(stroke_track(&expected), dir / "track.json");
    const CliRun run =
        run_studio("--xr --no-autosave --msaa 1 --save " + quoted(dir / "sketch.json"), dir,
                   xr_env(dir, dir / "track.json", "SKETCHSURF_TEST_XR_PROFILE=" + std::string(profile)));
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_NE(run.err.find("controller: " + std::string(profile)), std::string::npos) << run.err;
    const Sketch sketch = read_sketch(dir / "sketch.json");
    ASSERT_EQ(sketch.strokes.size(), 1u) << profile;
    ASSERT_EQ(sketch.strokes[0].points.size(), expected.size()) << profile;
    for (std::size_t i = 0; i < expected.size(); ++i)
      EXPECT_LE((sketch.strokes[0].points[i] - expected[i]).norm(), 1e-9) << profile << " point " << i;
    expect_no_xr_validation_messages(dir);
  }
}

TEST(StudioXr, FramesEndTheSessionThroughAnExitRequestWithMultisampling) {
  const auto dir = scratch_dir("studio_xr_exit_");
  std::vector<Eigen::Vector3d> expected;
  input::write_track(stroke_track(&expected), dir / "track.json");
  // With 4x MSAA: the eyes' multisampled images resolve into the runtime's.
  const CliRun run =
      run_studio("--xr --frames 5 --no-autosave --msaa 4 --validation", dir, xr_env(dir, dir / "track.json"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(run.err.find("MSAA 4"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("validation: 0 messages"), std::string::npos) << run.err;
  const nlohmann::json report = read_report(dir);
  EXPECT_FALSE(report["stopped_by_runtime"]);
  EXPECT_TRUE(report["session_ended"]);
  EXPECT_TRUE(report["session_destroyed"]);
  EXPECT_GE(report["frames_ended"].get<int>(), 5);
  EXPECT_LT(report["frames_ended"].get<int>(), 28) << "ended before the runtime would have";
  expect_no_xr_validation_messages(dir);
}

TEST(StudioXr, NoRuntimeSaysSoInOneLineAndStartsTheDesktopStudio) {
  if (std::filesystem::exists("/etc/openxr/1/active_runtime.json"))
    GTEST_SKIP() << "an OpenXR runtime is installed on this machine";
  const auto dir = scratch_dir("studio_xr_none_");
  const CliRun run =
      run_studio("--xr --headless --frames 2 --no-autosave --save " + quoted(dir / "s.json"), dir,
                 "env -u XR_RUNTIME_JSON XDG_CONFIG_HOME=" + quoted(dir / "home") +
                     " XDG_CONFIG_DIRS=" + quoted(dir / "etc"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const std::string line =
      "studio: no OpenXR runtime: XR_RUNTIME_JSON unset and no active_runtime.json (looked for " +
      (dir / "home/openxr/1/active_runtime.json").string() + ", " +
      (dir / "etc/openxr/1/active_runtime.json").string() +
      ", /etc/openxr/1/active_runtime.json; install Monado, SteamVR or another runtime, or set "
      "XR_RUNTIME_JSON); "
      "starting the desktop studio\n";
  EXPECT_NE(run.err.find(line), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("studio: headless "), std::string::npos) << "the desktop studio ran: " << run.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "s.json"));
}

TEST(StudioXr, NoHeadsetSaysSoAndStartsTheDesktopStudio) {
  const auto dir = scratch_dir("studio_xr_nohmd_");
  std::vector<Eigen::Vector3d> expected;
  input::write_track(stroke_track(&expected), dir / "track.json");
  const CliRun run = run_studio("--xr --headless --frames 2 --no-autosave", dir,
                                xr_env(dir, dir / "track.json", "SKETCHSURF_TEST_XR_NO_HMD=1"));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_NE(
      run.err.find("studio: no headset: the OpenXR runtime 'sketchsurf test runtime 1.0.0' sees no "
                   "head-mounted display (XR_ERROR_FORM_FACTOR_UNAVAILABLE); starting the desktop studio\n"),
      std::string::npos)
      << run.err;
  EXPECT_NE(run.err.find("studio: headless "), std::string::npos) << run.err;
  expect_no_xr_validation_messages(dir);
}

}  // namespace
}  // namespace sketchsurf::testing
