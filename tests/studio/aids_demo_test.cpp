// The drawing aids' demo (tools/sketchsurf-studio/demo/aids_demo.sh) end to end: the studio
// headless replays the demo track, surfaces the object, and the turntable is written; the sketch
// is the one the aids promise (six profiles and three closed rings, the rotation stored), and the
// surface's first turntable frame matches its golden image. The golden frame is rendered without
// region colours: how PEARL splits a smooth egg into regions has no single answer, and it changed
// with the last bits of the C library's exp and log (another CPU, another split), while the shape
// does not.

#include <gtest/gtest.h>

#include "engine/render/image.h"
#include "engine/session/stroke_aids.h"
#include "surfacing/sketch/io/sketch_io.h"
#include "tests/render/render_support.h"
#include "tests/studio/studio_run.h"

namespace sketchsurf::testing {
namespace {

TEST(AidsDemo, DrawsSurfacesAndTurnsTheObject) {
  const auto dir = scratch_dir("aids_demo_");
  const std::string command = "SKETCHSURF_STUDIO=" + quoted(SKETCHSURF_STUDIO) +
                              " SKETCHSURF=" + quoted(SKETCHSURF_CLI) + " timeout 600 " +
                              quoted(std::filesystem::path(SKETCHSURF_TESTS_DIR).parent_path() /
                                     "tools/sketchsurf-studio/demo/aids_demo.sh") +
                              " " + quoted(dir) + " > " + quoted(dir / "log.txt") + " 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << read_text(dir / "log.txt");
  for (int i = 0; i < 12; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "turntable_%03d.png", i);
    EXPECT_TRUE(std::filesystem::exists(dir / name)) << name;
  }

  // 6 profiles and 6 arcs at each of 3 heights; the pattern is in the file.
  const Sketch sketch = read_sketch(dir / "aids_demo.json");
  ASSERT_EQ(sketch.strokes.size(), 24u);
  ASSERT_TRUE(sketch.rotation.has_value());
  EXPECT_EQ(sketch.rotation->count, 6);
  const std::vector<Stroke> profiles(sketch.strokes.begin(), sketch.strokes.begin() + 6);
  for (const Stroke& p : profiles) {
    EXPECT_NEAR(p.points.front().y(), -1.0, 1e-12);  // pole to pole
    EXPECT_NEAR(p.points.back().y(), 1.0, 1e-12);
  }
  for (std::size_t k = 6; k < 24; ++k) {
    const Stroke& arc = sketch.strokes[k];
    // Snapped: both ends on a profile, exactly.
    for (const auto& end : {arc.points.front(), arc.points.back()}) {
      double nearest = 1e9;
      for (const Stroke& p : profiles) nearest = std::min(nearest, session::distance_to_stroke(end, p));
      EXPECT_LT(nearest, 1e-12) << "arc " << k;
    }
    // Guided and snapped where the profiles cross the plane: every point on the arc's plane.
    const double y = arc.points[arc.points.size() / 2].y();
    for (const auto& p : arc.points) EXPECT_NEAR(p.y(), y, 1e-9);
  }
  const std::string shape = quoted(SKETCHSURF_CLI) + " render " + quoted(dir / "aids_demo.json") +
                            " --mesh " + quoted(dir / "aids_demo.ply") +
                            " --turntable 12 --size 480x480 --quiet -o " + quoted(dir / "shape.png") + " > " +
                            quoted(dir / "render_log.txt") + " 2>&1";
  ASSERT_EQ(std::system(shape.c_str()), 0) << read_text(dir / "render_log.txt");
  expect_golden(render::read_png(dir / "shape_000.png"), "studio_aids_demo");
}

}  // namespace
}  // namespace sketchsurf::testing
