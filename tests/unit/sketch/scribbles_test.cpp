// Scribbles: the ink a stroke lays without retracing itself, in units of its extent, separates
// curves (lines, circles, circles retraced as over-sketching does) from strokes that wind over an
// area; the share of scribbled ink counts stroke length, not strokes, and skips ignored strokes.

#include <gtest/gtest.h>

#include <cmath>

#include "surfacing/sketch/scribbles.h"
#include "tests/support/shapes.h"

namespace sketchsurf {
namespace {

using V3 = Eigen::Vector3d;

Stroke circle(double radius, double turns, double wobble) {
  return testing::sample_curve(
      [&](double t) {
        const double r = radius * (1.0 + wobble * std::sin(3.0 * t / turns));
        return V3(r * std::cos(t), r * std::sin(t), 0.0);
      },
      0.0, 2 * M_PI * turns, 0.002);
}

// A stroke that sweeps back and forth over a square (a Lissajous figure): a scribbled fill.
Stroke scribble(double half) {
  return testing::sample_curve(
      [&](double t) { return V3(half * std::sin(7.0 * t), half * std::sin(11.0 * t + 0.3), 0.0); }, 0.0,
      2 * M_PI, 0.002);
}

TEST(Scribbles, CurvesFillLittleScribblesMuch) {
  const Stroke line = testing::sample_curve([](double t) { return V3(t, 0.3 * t, 0.1 * t); }, 0.0, 1.0, 0.002);
  EXPECT_NEAR(stroke_fill(line), 1.2, 0.2);
  EXPECT_NEAR(stroke_fill(circle(0.5, 1.0, 0.0)), 2.8, 0.3);
  // Over-sketching: the same circle three times, each pass a little off.
  EXPECT_LT(stroke_fill(circle(0.5, 3.0, 0.03)), 3.5);
  EXPECT_GT(stroke_fill(scribble(0.5)), 6.0);
  // The measure is relative to the stroke's extent: the same scribble ten times smaller.
  EXPECT_NEAR(stroke_fill(scribble(0.05)), stroke_fill(scribble(0.5)), 0.5);
}

TEST(Scribbles, TheShareCountsInkAndSkipsIgnoredStrokes) {
  Sketch sketch;
  sketch.strokes.push_back(circle(0.5, 1.0, 0.0));
  sketch.strokes.push_back(scribble(0.5));
  const double ink_circle = sketch.strokes[0].length(), ink_scribble = sketch.strokes[1].length();
  EXPECT_NEAR(scribbled_share(sketch, 5.0), ink_scribble / (ink_circle + ink_scribble), 1e-12);
  sketch.strokes[1].ignored = true;
  EXPECT_EQ(scribbled_share(sketch, 5.0), 0.0);
  EXPECT_EQ(scribbled_share(Sketch{}, 5.0), 0.0);
  // Strokes without extent (one point repeated) lay no scribble.
  Stroke dot;
  dot.points = {V3(1, 1, 1), V3(1, 1, 1)};
  EXPECT_EQ(stroke_fill(dot), 0.0);
}

TEST(Scribbles, OverSketchedCurveNetworksAreNotScribbles) {
  EXPECT_EQ(scribbled_share(testing::over_sketched(testing::cube_sketch(), 3, 0.01, 7), 5.0), 0.0);
  EXPECT_EQ(scribbled_share(testing::over_sketched(testing::torus_sketch(), 3, 0.01, 7), 5.0), 0.0);
}

}  // namespace
}  // namespace sketchsurf
