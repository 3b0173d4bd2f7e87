// Mirror planes: found within a degree on a sketch made symmetric about a tilted plane, also with
// hand noise; none on a sketch without symmetry. Half sketches: the plane their strokes stop on
// found within a degree, and completed by their mirror image; none on whole shapes.

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include <Eigen/Geometry>

#include "surfacing/sketch/symmetry.h"
#include "tests/support/shapes.h"

namespace sketchsurf {
namespace {

using V3 = Eigen::Vector3d;

// Wandering strokes on one side of the plane x = 0.1 (a fixed pseudo-random walk per stroke).
Sketch wandering(int strokes, unsigned seed) {
  std::mt19937 rng(seed);
  const auto uniform = [&]() { return static_cast<double>(rng() % 20001) / 10000.0 - 1.0; };
  Sketch sketch;
  for (int s = 0; s < strokes; ++s) {
    V3 p(0.2 + 0.4 * std::abs(uniform()), uniform(), uniform()), step(0, 0, 0);
    Stroke stroke;
    for (int i = 0; i < 60; ++i) {
      stroke.points.push_back(p);
      step = 0.8 * step + 0.01 * V3(uniform(), uniform(), uniform());
      p += step;
    }
    sketch.strokes.push_back(stroke);
  }
  return sketch;
}

TEST(Symmetry, APlaneIsFoundWithinADegree) {
  Plane truth;
  truth.normal = V3(1.0, 0.2, -0.1).normalized();
  truth.offset = -0.05;
  Sketch sketch = wandering(12, 3);
  const std::size_t n = sketch.strokes.size();
  for (std::size_t i = 0; i < n; ++i) {
    // Keep the stroke 0.3 or more on the positive side of the tilted plane, then add its mirror image.
    Stroke& s = sketch.strokes[i];
    for (V3& p : s.points) {
      const double d = truth.signed_distance(p);
      if (d < 0.3) p += (0.3 - d) * truth.normal;
    }
    Stroke mirrored = s;
    for (V3& p : mirrored.points) p = truth.reflect(p);
    sketch.strokes.push_back(mirrored);
  }
  testing::add_noise(sketch, 0.001, 7);
  const auto found = detect_mirror(sketch);
  ASSERT_TRUE(found.has_value());
  const double angle = std::acos(std::min(1.0, std::abs(found->plane.normal.dot(truth.normal)))) * 180 / M_PI;
  EXPECT_LT(angle, 1.0);
  const double sign = found->plane.normal.dot(truth.normal) > 0 ? 1.0 : -1.0;
  EXPECT_NEAR(sign * found->plane.offset, truth.offset, 0.01);
  EXPECT_LT(found->distance, 0.01);
}

TEST(Symmetry, NoPlaneWithoutSymmetry) {
  EXPECT_FALSE(detect_mirror(wandering(12, 5)).has_value());
}

TEST(Symmetry, TheBundledShapesAreSymmetric) {
  const auto cube = detect_mirror(testing::cube_sketch(1.0, false));
  ASSERT_TRUE(cube.has_value());
  EXPECT_LT(cube->distance, 1e-6);
  EXPECT_NEAR(cube->plane.normal.cwiseAbs().maxCoeff(), 1.0, 1e-6);  // an axis plane
}

// Half of a box 2 x 1 x 0.6 (x from 0 to 1): three sections, the four long edges and a stroke along
// the middle of each long face from x = 0 (where they stop, in the air) to the closed end at x = 1;
// turned and moved by `pose`.
Sketch half_box(const Eigen::Isometry3d& pose) {
  const V3 h(1.0, 0.5, 0.3);
  Sketch sketch = testing::box_sections_sketch(h, {0.3, 0.6, 1.0});
  for (double y : {-h.y(), 0.0, h.y()})
    for (double z : {-h.z(), 0.0, h.z()})
      if ((y == 0.0) != (z == 0.0))  // the middles of the faces
        sketch.strokes.push_back(testing::polyline_stroke({V3(0, y, z), V3(1, y, z)}, false));
      else if (y != 0.0)  // the edges
        sketch.strokes.push_back(testing::polyline_stroke({V3(0, y, z), V3(1, y, z)}, false));
  for (Stroke& s : sketch.strokes)
    for (V3& p : s.points) p = pose * p;
  sketch.assign_ids();
  return sketch;
}

Eigen::Isometry3d tilted() {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.rotate(Eigen::AngleAxisd(0.7, V3(0.3, 1.0, 0.2).normalized()));
  pose.pretranslate(V3(0.2, -0.4, 1.5));
  return pose;
}

TEST(Symmetry, TheMirrorPlaneOfAHalfSketchIsFoundWithinADegree) {
  const Eigen::Isometry3d pose = tilted();
  Sketch sketch = half_box(pose);
  testing::add_noise(sketch, 0.001, 11);
  const auto found = detect_half_mirror(sketch);
  ASSERT_TRUE(found.has_value());
  EXPECT_EQ(found->half_ends, 8);
  const V3 normal = pose.linear() * V3::UnitX();  // toward the strokes
  EXPECT_LT(std::acos(std::min(1.0, found->plane.normal.dot(normal))) * 180 / M_PI, 1.0);
  EXPECT_LT(std::abs(found->plane.signed_distance(pose * V3(0, 0.2, -0.1))), 0.01);

  // Completed: the three sections get their images as new strokes; the eight long strokes run on
  // through the plane into their images; a stroke in the plane is its own image.
  sketch.strokes.push_back(testing::polyline_stroke({pose * V3(0, -0.5, 0.3), pose * V3(0, 0.5, 0.3)}, false));
  sketch.strokes.back().id = 1000;
  const std::size_t n = sketch.strokes.size(), m = sketch.strokes[3].points.size();
  const V3 far_end = sketch.strokes[3].points.back();
  complete_half(sketch, found->plane, 0.01);
  ASSERT_EQ(sketch.strokes.size(), n + 3);
  EXPECT_FALSE(sketch.mirror.has_value());
  std::set<std::int64_t> ids;
  for (const Stroke& s : sketch.strokes) ids.insert(s.id);
  EXPECT_EQ(ids.size(), n + 3);
  EXPECT_LT((sketch.strokes[n].points[5] - found->plane.reflect(sketch.strokes[0].points[5])).norm(), 1e-12);
  const auto& through = sketch.strokes[3].points;
  ASSERT_EQ(through.size(), 2 * m - 1);
  EXPECT_LT((through.front() - found->plane.reflect(far_end)).norm(), 1e-9);
  EXPECT_LT((through.back() - far_end).norm(), 1e-12);
  EXPECT_LT(std::abs(found->plane.signed_distance(through[m - 1])), 1e-12);
  EXPECT_TRUE(detect_mirror(sketch).has_value());
  EXPECT_FALSE(detect_half_mirror(sketch).has_value());  // no free end left on the plane
}

TEST(Symmetry, WholeShapesAreNotHalves) {
  EXPECT_FALSE(detect_half_mirror(testing::cube_sketch()).has_value());
  EXPECT_FALSE(detect_half_mirror(testing::cylinder_sketch()).has_value());
  EXPECT_FALSE(detect_half_mirror(testing::sphere_sketch()).has_value());
  EXPECT_FALSE(detect_half_mirror(testing::torus_sketch()).has_value());
  EXPECT_FALSE(detect_half_mirror(testing::cup_sketch()).has_value());
  EXPECT_FALSE(detect_half_mirror(wandering(12, 5)).has_value());
  // A box's edges only: its side edges stop on the bottom's edges, not in the air.
  Sketch open_box = testing::cube_sketch(1.0, false);
  EXPECT_FALSE(detect_half_mirror(open_box).has_value());
  // Too few free ends on the plane: the half box with only two of its eight long strokes.
  Sketch few = half_box(Eigen::Isometry3d::Identity());
  few.strokes.resize(3 + 2);
  EXPECT_FALSE(detect_half_mirror(few).has_value());
}

}  // namespace
}  // namespace sketchsurf
