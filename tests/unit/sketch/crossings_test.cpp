// Strokes that meet no other stroke: a curve network (a cube's edges and sections) has none, or few
// when drawn over, a hatching scene (short parallel strokes in groups) is all of them; a stroke met
// only by strokes along it, or only farther than the reach, is unmet. Where strokes cross, the
// distance between them: exact for lines that meet, the offset for lines that pass each other.

#include <gtest/gtest.h>

#include <cmath>
#include <utility>

#include "surfacing/sketch/crossings.h"
#include "tests/support/shapes.h"

namespace sketchsurf {
namespace {

using V3 = Eigen::Vector3d;

constexpr double kReach = 0.01, kAngle = 30.0 * M_PI / 180.0;

Stroke two_point_stroke(const V3& a, const V3& b) { return testing::polyline_stroke({a, b}, false); }

Sketch two_lines(const V3& a0, const V3& a1, const V3& b0, const V3& b1) {
  Sketch sketch;
  sketch.strokes = {two_point_stroke(a0, a1), two_point_stroke(b0, b1)};
  return sketch;
}

TEST(Crossings, ANetworkMeetsItselfAndHatchingDoesNot) {
  EXPECT_EQ(unmet_share(testing::cube_sketch(), kReach, kAngle), 0.0);
  // Drawn three times over, the passes cut short by up to 15% at each end: some stop short of every
  // corner and meet nothing, far fewer than in a scene of hatching.
  EXPECT_LT(unmet_share(testing::over_sketched(testing::cube_sketch(), 3, 0.003, 7), kReach, kAngle), 0.2);
  EXPECT_EQ(unmet_share(testing::hatching_sketch(10, 3), kReach, kAngle), 1.0);
  EXPECT_EQ(unmet_share(Sketch{}, kReach, kAngle), 0.0);
}

TEST(Crossings, StrokesMeetCrosswiseWithinTheReach) {
  // Crossing at right angles, and one ending on the other (a T).
  EXPECT_EQ(unmet_share(two_lines(V3(-1, 0, 0), V3(1, 0, 0), V3(0, -1, 0), V3(0, 1, 0)), kReach, kAngle), 0.0);
  EXPECT_EQ(unmet_share(two_lines(V3(-1, 0, 0), V3(1, 0, 0), V3(0, 0.005, 0), V3(0, 1, 0)), kReach, kAngle),
            0.0);
  // Side by side (over-sketching, hatching): not a meeting, however near.
  EXPECT_EQ(
      unmet_share(two_lines(V3(-1, 0, 0), V3(1, 0, 0), V3(-1, 0.005, 0), V3(1, 0.005, 0)), kReach, kAngle),
      1.0);
  // Crosswise but apart by twice the reach (one above the other).
  EXPECT_EQ(unmet_share(two_lines(V3(-1, 0, 0), V3(1, 0, 0), V3(0, -1, 0.02), V3(0, 1, 0.02)), kReach, kAngle),
            1.0);
  // The share counts length: a long stroke met, a short one alone.
  Sketch sketch = two_lines(V3(-1, 0, 0), V3(1, 0, 0), V3(0, -1, 0), V3(0, 1, 0));
  sketch.strokes.push_back(two_point_stroke(V3(5, 5, 5), V3(5.4, 5, 5)));
  EXPECT_NEAR(unmet_share(sketch, kReach, kAngle), 0.4 / 4.4, 1e-3);
  sketch.strokes.back().ignored = true;
  EXPECT_EQ(unmet_share(sketch, kReach, kAngle), 0.0);
}

// Two long lines crossing at right angles, the second lifted by `lift` and turned by `turn`
// radians about the z axis, each a polyline of segments far longer than the reach.
Sketch crossing_pair(double lift, double turn) {
  return two_lines(V3(-1, 0, 0), V3(1, 0, 0), V3(std::sin(turn), -std::cos(turn), lift),
                   V3(-std::sin(turn), std::cos(turn), lift));
}

TEST(Crossings, TheGapWhereStrokesCrossIsTheirDistanceThere) {
  EXPECT_NEAR(crossing_gap(crossing_pair(0.0, 0.3), kReach, kAngle, 1), 0.0, 1e-15);
  EXPECT_NEAR(crossing_gap(crossing_pair(0.004, 0.3), kReach, kAngle, 1), 0.004, 1e-12);
  EXPECT_NEAR(crossing_gap(crossing_pair(-0.007, -0.5), kReach, kAngle, 1), 0.007, 1e-12);
  // Farther apart than the reach, or too few crossings: no measure.
  EXPECT_LT(crossing_gap(crossing_pair(0.02, 0.0), kReach, kAngle, 1), 0.0);
  EXPECT_LT(crossing_gap(crossing_pair(0.0, 0.0), kReach, kAngle, 2), 0.0);
  // Side by side (at 20 degrees, under the angle), or one ending on the other (a T): no crossing.
  EXPECT_LT(crossing_gap(crossing_pair(0.0, M_PI / 2.0 - 20.0 * M_PI / 180.0), kReach, kAngle, 1), 0.0);
  EXPECT_LT(crossing_gap(two_lines(V3(-1, 0, 0), V3(1, 0, 0), V3(0, 0, 0), V3(0, 1, 0)), kReach, kAngle, 1),
            0.0);
  // The median over the crossing pairs: three lines lifted 0.001, 0.002 and 0.006 across a fourth.
  Sketch sketch = crossing_pair(0.001, 0.0);
  for (const auto& [x, lift] : {std::pair{0.1, 0.002}, std::pair{0.3, 0.006}})
    sketch.strokes.push_back(two_point_stroke(V3(x, -1, lift), V3(x, 1, lift)));
  EXPECT_NEAR(crossing_gap(sketch, kReach, kAngle, 3), 0.002, 1e-12);
  sketch.strokes.back().ignored = true;
  EXPECT_LT(crossing_gap(sketch, kReach, kAngle, 3), 0.0);
}

TEST(Crossings, ACrossingWhereAStrokeTurnsACornerIsLeftOutWithABend) {
  // A stroke along x that turns a right-angled corner at the origin, cut short as a polyline cuts a
  // crease's corner, and a straight stroke across the cut at right angles, 0.004 above it. Without
  // a bend limit that is the gap; with one, the crossing is left out (the first stroke turns 90
  // degrees within the reach), and a crossing of straight strokes is not.
  Sketch corner;
  Stroke turning;
  turning.points = {V3(-1, 0, 0), V3(-0.003, 0, 0), V3(0, 0.003, 0), V3(0, 1, 0)};
  corner.strokes = {turning, two_point_stroke(V3(-1, 1, 0.004), V3(1, -1, 0.004))};
  EXPECT_NEAR(crossing_gap(corner, kReach, kAngle, 1), 0.004, 1e-12);
  EXPECT_LT(crossing_gap(corner, kReach, kAngle, 1, M_PI / 9.0), 0.0);
  EXPECT_NEAR(crossing_gap(crossing_pair(0.004, 0.3), kReach, kAngle, 1, M_PI / 9.0), 0.004, 1e-12);
}

}  // namespace
}  // namespace sketchsurf
