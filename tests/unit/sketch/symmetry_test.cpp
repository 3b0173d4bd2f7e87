// Mirror planes: found within a degree on a sketch made symmetric about a tilted plane, also with
// hand noise; none on a sketch without symmetry.

#include <gtest/gtest.h>

#include <cmath>
#include <random>

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

}  // namespace
}  // namespace sketchsurf
