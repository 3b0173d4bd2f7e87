#include "surfacing/extract/tubes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <utility>

#include "surfacing/error.h"
#include "surfacing/proxy/proxy.h"

namespace sketchsurf {
namespace {

// A stroke along the quarter circle of radius 1 about the origin in z = 0, one point per 0.01.
Stroke quarter_circle() {
  Stroke s;
  for (int i = 0; i <= 157; ++i) {
    const double a = 0.5 * M_PI * i / 157.0;
    s.points.emplace_back(std::cos(a), std::sin(a), 0.0);
  }
  return s;
}

// Volume enclosed by a closed mesh (divergence theorem): positive when it faces outwards.
double volume(const TriMesh& mesh) {
  double v = 0.0;
  for (auto f : mesh.faces()) {
    auto it = mesh.cfv_iter(f);
    const Eigen::Vector3d a = to_eigen(mesh.point(*it++)), b = to_eigen(mesh.point(*it++)),
                          c = to_eigen(mesh.point(*it));
    v += a.dot(b.cross(c)) / 6.0;
  }
  return v;
}

TEST(StrokeTubes, AnArcGivesOneClosedOutwardTubeOfTheRadius) {
  Sketch sketch;
  sketch.strokes.push_back(quarter_circle());
  const double diagonal = 2.0, r = 0.004 * diagonal;
  const TriMesh tube = stroke_tubes(sketch, diagonal).mesh;
  const MeshTopology t = mesh_topology(tube);
  EXPECT_EQ(t.components, 1u);
  EXPECT_TRUE(t.closed());
  EXPECT_EQ(t.genus, 0);
  // Every ring vertex lies r from the arc (distance to the circle: sqrt((rho - 1)^2 + z^2)); the
  // two cone tips lie on the arc's tangents, r past its ends.
  std::size_t tips = 0;
  for (auto v : tube.vertices()) {
    const Eigen::Vector3d p = to_eigen(tube.point(v));
    const double off = std::hypot(std::hypot(p.x(), p.y()) - 1.0, p.z());
    if (off < 0.5 * r) {
      ++tips;
      EXPECT_NEAR(std::min((p - Eigen::Vector3d(1, 0, 0)).norm(), (p - Eigen::Vector3d(0, 1, 0)).norm()), r, 1e-9);
      continue;
    }
    EXPECT_NEAR(off, r, 0.01 * r);
  }
  EXPECT_EQ(tips, 2u);
  // Outward, and the volume of a 12-sided prism along the arc (area 12/2 sin(30 deg) r^2) plus the
  // two cones.
  const double length = 0.5 * M_PI, section = 3.0 * r * r;
  EXPECT_NEAR(volume(tube), section * length + 2.0 * section * r / 3.0, 0.01 * section * length);
}

TEST(StrokeTubes, WithAMirrorPlaneTheHalfTubeAndItsImage) {
  // A straight stroke from x = -0.3 to x = 0.6 and the plane x = 0.1: the tube of its part on the
  // positive side (x >= 0.1) and that tube's mirror image, which reaches x = -0.4.
  Sketch sketch;
  Stroke s;
  for (int i = 0; i <= 90; ++i) s.points.emplace_back(-0.3 + 0.01 * i, 0.2, 0.0);
  sketch.strokes.push_back(s);
  Plane plane;
  plane.normal = Eigen::Vector3d::UnitX();
  plane.offset = -0.1;
  sketch.mirror = plane;
  const double diagonal = 1.0, r = 0.004;
  const StrokeTubes made = stroke_tubes(sketch, diagonal);
  EXPECT_EQ(made.count, 2u);
  const TriMesh& tubes = made.mesh;
  const MeshTopology t = mesh_topology(tubes);
  EXPECT_EQ(t.components, 2u);
  EXPECT_TRUE(t.closed());
  double lo = std::numeric_limits<double>::infinity(), hi = -lo, worst = 0.0;
  for (auto v : tubes.vertices()) {
    const Eigen::Vector3d p = to_eigen(tubes.point(v));
    lo = std::min(lo, p.x());
    hi = std::max(hi, p.x());
    double nearest = std::numeric_limits<double>::infinity();
    for (auto u : tubes.vertices()) nearest = std::min(nearest, (to_eigen(tubes.point(u)) - plane.reflect(p)).norm());
    worst = std::max(worst, nearest);
    // Away from the cones (at the ends and at the plane), r from the stroke's line.
    if (std::abs(p.x() - 0.1) > 1.01 * r && p.x() < 0.6 - 1e-9 && p.x() > -0.4 + 1e-9) {
      EXPECT_NEAR(std::hypot(p.y() - 0.2, p.z()), r, 1e-9);
    }
  }
  EXPECT_NEAR(hi, 0.6 + r, 1e-9);
  EXPECT_NEAR(lo, -0.4 - r, 1e-9);
  EXPECT_LT(worst, 1e-9);  // symmetric
  EXPECT_GT(volume(tubes), 0.0);
}

TEST(StrokeTubes, AStrokeWithABrushWidthIsAsThickAsDrawnUpToTheCap) {
  // A straight stroke along x: drawn with a brush 0.03 wide its tube has radius 0.015; drawn 0.2
  // wide, the cap (2% of the diagonal 1); without a width, 0.4% of the diagonal.
  for (const auto& [width, radius] : {std::pair{0.03, 0.015}, std::pair{0.2, 0.02}, std::pair{0.0, 0.004}}) {
    Sketch sketch;
    Stroke s;
    for (int i = 0; i <= 50; ++i) s.points.emplace_back(0.01 * i, 0.0, 0.0);
    s.width = width;
    sketch.strokes.push_back(s);
    const TriMesh tube = stroke_tubes(sketch, 1.0).mesh;
    ASSERT_GT(tube.n_vertices(), 0u);
    for (auto v : tube.vertices()) {
      const Eigen::Vector3d p = to_eigen(tube.point(v));
      if (p.x() > 0.0 && p.x() < 0.5) {
        EXPECT_NEAR(std::hypot(p.y(), p.z()), radius, 1e-9) << width;
      }
    }
  }
}

TEST(StrokeTubes, AStrokeOnOnePointGivesNothingAndBadOptionsAreRefused) {
  Sketch sketch;
  Stroke dot;
  dot.points.assign(5, Eigen::Vector3d(0.1, 0.2, 0.3));
  sketch.strokes.push_back(dot);
  EXPECT_EQ(stroke_tubes(sketch, 1.0).count, 0u);
  EXPECT_EQ(stroke_tubes(sketch, 1.0).mesh.n_vertices(), 0u);
  TubeOptions options;
  options.sides = 2;
  EXPECT_THROW(stroke_tubes(sketch, 1.0, options), Error);
  options = {};
  options.radius = 0.0;
  EXPECT_THROW(stroke_tubes(sketch, 1.0, options), Error);
  EXPECT_THROW(stroke_tubes(sketch, std::nan(""), {}), Error);
}

}  // namespace
}  // namespace sketchsurf
