// sketchsurf-studio in a real window (issue 16 "Done when"), run by CTest under xvfb-run (Debian's
// xvfb; lavapipe presents to it): the cube replay presents its frames with no validation message
// and its last frame matches the golden image (and the headless one: one renderer, two
// targets); a click injected with xdotool reaches the panel; a resize mid-run recreates the
// swapchain and the run goes on; SIGTERM ends it like closing the window.

#include "engine/input/track.h"
#include "surfacing/sketch/io/sketch_io.h"
#include "tests/render/render_support.h"
#include "tests/studio/studio_run.h"

namespace sketchsurf::testing {
namespace {

/// Runs a shell command; true when it exits 0. Its output goes to `out` when given.
bool shell(const std::string& command, std::string* out = nullptr) {
  const std::string full = command + " 2>&1";
  FILE* pipe = popen(full.c_str(), "r");
  if (!pipe) return false;
  std::string text;
  char buffer[256];
  while (fgets(buffer, sizeof buffer, pipe)) text += buffer;
  const int status = pclose(pipe);
  if (out) *out = text;
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

bool no_validation_messages(const std::string& log) {
  return log.find("validation error") == std::string::npos &&
         log.find("validation warning") == std::string::npos &&
         log.find("validation: 0 messages") != std::string::npos;
}

TEST(StudioWindow, CubeReplayPresentsItsFramesAndMatchesTheGolden) {
  ASSERT_NE(std::getenv("DISPLAY"), nullptr) << "run under xvfb-run (CTest does)";
  const auto dir = scratch_dir("studio_window_");
  const std::string common = "--replay " + quoted(data_file("cube.track.json")) +
                             " --frames 24 --size 640x480 --msaa 4 --no-autosave --validation";
  const CliRun window = run_studio(common + " --no-vsync --screenshot " + quoted(dir / "window.png") +
                                       " --save " + quoted(dir / "window.json"),
                                   dir);
  ASSERT_EQ(window.exit_code, 0) << window.err;
  EXPECT_NE(window.err.find("presented 24 frames"), std::string::npos) << window.err;
  EXPECT_TRUE(no_validation_messages(window.err)) << window.err;
  const CliRun headless = run_studio(common + " --headless --screenshot " + quoted(dir / "headless.png") +
                                         " --save " + quoted(dir / "headless.json"),
                                     dir);
  ASSERT_EQ(headless.exit_code, 0) << headless.err;
  EXPECT_TRUE(no_validation_messages(headless.err)) << headless.err;
  EXPECT_EQ(read_text(dir / "window.json"), read_text(dir / "headless.json"));
  const render::RgbaImage shot = render::read_png(dir / "window.png");
  expect_golden(shot, "studio_window_cube");
  // One renderer, two targets: the window's picture is the headless one (the panel's frame time
  // aside).
  const auto cmp = render::compare_images(render::read_png(dir / "headless.png"), shot, 8);
  EXPECT_TRUE(cmp.same_size);
  EXPECT_LT(cmp.fraction, 0.01) << cmp.differing << " pixels differ";
}

TEST(StudioWindow, ClickReachesThePanelResizeSurvivesSigtermEndsCleanly) {
  ASSERT_NE(std::getenv("DISPLAY"), nullptr) << "run under xvfb-run (CTest does)";
  const auto dir = scratch_dir("studio_click_");
  StudioProcess studio({"-v", "--validation", "--no-vsync", "--size", "400x300", "--no-autosave", "--record",
                        (dir / "rec.track.json").string(), "--save", (dir / "out.json").string()},
                       dir / "log.txt");
  ASSERT_TRUE(studio.wait_for("panel: 'Mirror' at ", 60.0)) << studio.log();
  int x = 0, y = 0;
  {
    const std::string log = studio.log();
    const auto at = log.find("panel: 'Mirror' at ");
    std::istringstream(log.substr(at + 19)) >> x >> y;
  }
  std::string wid;
  ASSERT_TRUE(shell("xdotool search --sync --name '^sketchsurf studio$' | head -1", &wid)) << wid;
  wid.erase(wid.find_last_not_of("\n ") + 1);
  ASSERT_FALSE(wid.empty());
  // A real pointer move and click (XTEST), on the panel's Mirror checkbox.
  std::string out;
  ASSERT_TRUE(shell("xdotool mousemove --window " + wid + " " + std::to_string(x) + " " + std::to_string(y) +
                        " sleep 0.2 click 1",
                    &out))
      << out;
  EXPECT_TRUE(studio.wait_for("mirror on", 20.0)) << studio.log();
  // Resize mid-run: the swapchain is recreated and frames go on.
  ASSERT_TRUE(shell("xdotool windowsize " + wid + " 520 360", &out)) << out;
  EXPECT_TRUE(studio.wait_for("swapchain recreated: 520x360", 20.0)) << studio.log();
  const std::size_t before = studio.log().size();
  std::this_thread::sleep_for(std::chrono::milliseconds(300));
  EXPECT_EQ(studio.stop(SIGTERM), 0) << studio.log();
  const std::string log = studio.log();
  EXPECT_GT(log.size(), before);
  EXPECT_NE(log.find("presented "), std::string::npos) << log;
  EXPECT_TRUE(no_validation_messages(log)) << log;
  // The click was an action of the session: in the sketch and in the recording.
  EXPECT_TRUE(read_sketch(dir / "out.json").mirror.has_value());
  const input::Track recorded = input::read_track(dir / "rec.track.json");
  bool mirror = false;
  for (const auto& e : recorded.events) mirror |= e.action && e.action->name == "mirror";
  EXPECT_TRUE(mirror);
}

}  // namespace
}  // namespace sketchsurf::testing
