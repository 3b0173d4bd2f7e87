#include "surfacing/sketch/sketch.h"

#include <gtest/gtest.h>

#include <cmath>

namespace sketchsurf {
namespace {

Stroke line_stroke(int n, double length) {
  Stroke s;
  for (int i = 0; i < n; ++i) s.points.emplace_back(length * i / (n - 1), 0.0, 0.0);
  return s;
}

TEST(Sketch, BoundingBoxAndDiagonal) {
  Sketch sketch;
  Stroke a;
  a.points = {{0, 0, 0}, {1, 2, 2}};
  sketch.strokes.push_back(a);
  const BoundingBox box = sketch.bounding_box();
  EXPECT_DOUBLE_EQ(box.diagonal(), 3.0);
  EXPECT_EQ(box.min, Eigen::Vector3d(0, 0, 0));
  EXPECT_EQ(box.max, Eigen::Vector3d(1, 2, 2));
  EXPECT_TRUE(Sketch{}.bounding_box().empty());
  EXPECT_EQ(Sketch{}.bounding_box().diagonal(), 0.0);
}

TEST(Sketch, LengthAndCounts) {
  Sketch sketch;
  sketch.strokes = {line_stroke(3, 2.0), line_stroke(5, 1.0)};
  EXPECT_EQ(sketch.point_count(), 8u);
  EXPECT_DOUBLE_EQ(sketch.total_length(), 3.0);
}

TEST(Sketch, AssignIdsKeepsExistingOnesUnique) {
  Sketch sketch;
  sketch.strokes.resize(3);
  sketch.strokes[1].id = 7;
  sketch.assign_ids();
  EXPECT_EQ(sketch.strokes[0].id, 8);
  EXPECT_EQ(sketch.strokes[1].id, 7);
  EXPECT_EQ(sketch.strokes[2].id, 9);
}

TEST(Clean, RemovesNonFiniteDuplicatesAndShortStrokes) {
  Sketch sketch;
  Stroke s = line_stroke(4, 3.0);
  s.pressures = {0.1f, 0.2f, 0.3f, 0.4f};
  s.points.insert(s.points.begin() + 1, s.points[0]);  // duplicate
  s.pressures.insert(s.pressures.begin() + 1, 0.15f);
  s.points[3].x() = std::nan("");
  sketch.strokes.push_back(s);
  Stroke lonely;
  lonely.points = {{1, 1, 1}, {1, 1, 1}};
  sketch.strokes.push_back(lonely);

  const CleanReport report = clean(sketch);
  EXPECT_EQ(report.duplicate_points, 2u);  // one in each stroke
  EXPECT_EQ(report.non_finite_points, 1u);
  EXPECT_EQ(report.short_strokes, 1u);
  EXPECT_EQ(report.messages.size(), 3u);
  ASSERT_EQ(sketch.strokes.size(), 1u);
  const Stroke& out = sketch.strokes[0];
  EXPECT_EQ(out.points.size(), 3u);
  EXPECT_TRUE(out.attributes_consistent());
  EXPECT_EQ(out.pressures, (std::vector<float>{0.1f, 0.2f, 0.4f}));
}

TEST(Clean, CleanSketchIsUnchanged) {
  Sketch sketch;
  sketch.strokes = {line_stroke(10, 1.0)};
  const Sketch before = sketch;
  EXPECT_FALSE(clean(sketch).changed());
  EXPECT_EQ(sketch.strokes[0].points, before.strokes[0].points);
}

TEST(Resample, UniformSpacingKeepsEndpointsAndShape) {
  Stroke s;
  // A quarter circle of radius 1, unevenly sampled.
  for (double t : {0.0, 0.05, 0.1, 0.5, 0.9, 1.0}) s.points.emplace_back(std::cos(t * M_PI / 2), std::sin(t * M_PI / 2), 0.0);
  s.timestamps_ms = {0, 10, 20, 100, 180, 200};
  const Stroke r = resample(s, 0.01);
  ASSERT_GT(r.points.size(), 100u);
  EXPECT_EQ(r.points.front(), s.points.front());
  EXPECT_EQ(r.points.back(), s.points.back());
  EXPECT_TRUE(r.attributes_consistent());
  const double expected = s.length() / static_cast<double>(r.points.size() - 1);
  // Arc-length spacing is exact; a chord across a corner of the input
  // polyline (here turning by 36 degrees) is at least cos(18 deg) = 0.951 times as long.
  for (std::size_t i = 1; i < r.points.size(); ++i) {
    const double chord = (r.points[i] - r.points[i - 1]).norm();
    EXPECT_LE(chord, expected + 1e-12);
    EXPECT_GE(chord, 0.95 * expected);
  }
  EXPECT_NEAR(r.length(), s.length(), 1e-3 * s.length());
  for (std::size_t i = 1; i < r.timestamps_ms.size(); ++i)
    EXPECT_LE(r.timestamps_ms[i - 1], r.timestamps_ms[i]);
}

TEST(Resample, InvariantUnderScaling) {
  const Stroke s = line_stroke(7, 1.0);
  for (double scale : {1e-3, 1e3}) {
    Stroke scaled = s;
    for (auto& p : scaled.points) p *= scale;
    const Stroke a = resample(s, 0.1), b = resample(scaled, 0.1 * scale);
    ASSERT_EQ(a.points.size(), b.points.size());
    for (std::size_t i = 0; i < a.points.size(); ++i)
      EXPECT_NEAR((a.points[i] * scale - b.points[i]).norm(), 0.0, 1e-12 * scale);
  }
}

TEST(Resample, RejectsBadSpacing) {
  EXPECT_THROW(resample(line_stroke(3, 1.0), 0.0), std::exception);
  EXPECT_THROW(resample(line_stroke(3, 1.0), std::nan("")), std::exception);
}

}  // namespace
}  // namespace sketchsurf
