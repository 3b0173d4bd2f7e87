// Holes through a face drawn in: a plate pierced by a round hole, cut on its bottom face, has one
// hole there, closed by a membrane over it, unless a stroke draws the hole's rim.

#include "surfacing/proxy/face_holes.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>

namespace sketchsurf {
namespace {

constexpr double kHalf = 0.03, kHole = 0.1, kPlate = 0.35;  // a square plate in y, a hole round y

// Signed distance (to first order) of a square plate |y| <= kHalf, |x|, |z| <= kPlate, pierced by
// the cylinder of radius kHole round the y axis.
double plate(const Eigen::Vector3d& p) {
  const double slab = std::max({std::abs(p.y()) - kHalf, std::abs(p.x()) - kPlate, std::abs(p.z()) - kPlate});
  return std::max(slab, kHole - std::hypot(p.x(), p.z()));
}

Stroke circle(double radius, double y) {
  Stroke s;
  for (int i = 0; i <= 96; ++i) {
    const double t = 2.0 * std::numbers::pi * i / 96;
    s.points.emplace_back(radius * std::cos(t), y, radius * std::sin(t));
  }
  return s;
}

// The plate's outline on its bottom face and two strokes across it, passing by the hole.
Sketch plate_strokes(bool hole_rim) {
  Sketch sketch;
  Stroke outline;
  for (const auto& [x, z] : {std::array{-kPlate, -kPlate}, {kPlate, -kPlate}, {kPlate, kPlate}, {-kPlate, kPlate}, {-kPlate, -kPlate}})
    outline.points.emplace_back(x, -kHalf, z);
  sketch.strokes.push_back(outline);
  for (const double x : {-0.2, 0.2}) {
    Stroke across;
    for (int i = 0; i <= 20; ++i) across.points.emplace_back(x, -kHalf, -kPlate + 2.0 * kPlate * i / 20);
    sketch.strokes.push_back(across);
  }
  if (hole_rim) sketch.strokes.push_back(circle(kHole, -kHalf));
  return sketch;
}

FaceHoles holes_of(const Sketch& sketch) {
  Eigen::MatrixX3d points(0, 3);
  for (const Stroke& s : sketch.strokes)
    for (const Eigen::Vector3d& p : s.points) {
      points.conservativeResize(points.rows() + 1, 3);
      points.row(points.rows() - 1) = p.transpose();
    }
  const PointGrid grid(points);
  const Plane bottom{-Eigen::Vector3d::UnitY(), -kHalf};  // y = -kHalf, normal out of the plate
  BoundingBox box;
  box.extend(Eigen::Vector3d(-kPlate, -kHalf, -kPlate));
  box.extend(Eigen::Vector3d(kPlate, kHalf, kPlate));
  return face_holes(plate, bottom, box, sketch, grid, FaceHoleSearch{}, 2);
}

TEST(FaceHoles, AHoleThroughAFaceIsClosedByAMembraneOnTheFace) {
  const FaceHoles found = holes_of(plate_strokes(false));
  ASSERT_EQ(found.holes, 1u);
  ASSERT_FALSE(found.membranes.empty());
  // The membrane lies on the face and covers the hole: inside the plate's field lowered by it
  // just inside the face, all over the hole; the plate's top (y = kHalf) stays open.
  const auto lowered = [&](const Eigen::Vector3d& p) { return plate(p) - bumps_value(found.membranes, p, nullptr); };
  for (double r = 0.0; r < kHole; r += 0.02)
    for (int k = 0; k < 8; ++k) {
      const double t = 2.0 * std::numbers::pi * k / 8;
      const Eigen::Vector3d on(r * std::cos(t), -kHalf + 0.005, r * std::sin(t));
      EXPECT_LT(lowered(on), 0.0) << "r " << r;
      EXPECT_GT(lowered(on + Eigen::Vector3d(0.0, 2.0 * kHalf - 0.01, 0.0)), 0.0) << "the top, r " << r;
    }
  for (const Bump& b : found.membranes) {
    EXPECT_NEAR(b.centre.y(), -kHalf, 1e-12);
    EXPECT_LT(std::hypot(b.centre.x(), b.centre.z()), kHole + 0.03) << "no membrane far past the hole";
  }
}

TEST(FaceHoles, AHoleWhoseRimIsDrawnStaysOpen) {
  EXPECT_EQ(holes_of(plate_strokes(true)).holes, 0u);
}

TEST(FaceHoles, AFaceWithoutHolesHasNone) {
  const Plane top{Eigen::Vector3d::UnitY(), -kHalf};
  const auto solid = [](const Eigen::Vector3d& p) {
    return std::max({std::abs(p.y()) - kHalf, std::abs(p.x()) - kPlate, std::abs(p.z()) - kPlate});
  };
  const Sketch sketch = plate_strokes(false);
  Eigen::MatrixX3d points(1, 3);
  points.row(0) = Eigen::RowVector3d(kPlate, -kHalf, kPlate);
  BoundingBox box;
  box.extend(Eigen::Vector3d(-kPlate, -kHalf, -kPlate));
  box.extend(Eigen::Vector3d(kPlate, kHalf, kPlate));
  EXPECT_EQ(face_holes(solid, top, box, sketch, PointGrid(points), FaceHoleSearch{}, 1).holes, 0u);
}

}  // namespace
}  // namespace sketchsurf
