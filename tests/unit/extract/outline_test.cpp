#include "surfacing/extract/outline.h"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/support/shapes.h"
#include "tests/unit/extract/fixtures.h"

namespace sketchsurf {
namespace {

using namespace testing;

const Eigen::Vector3d kUp = Eigen::Vector3d::UnitZ();  // the surface's normal: along the plane's

// The unit square of the plane z = 0, counter-clockwise; edge i runs from corner i to corner i + 1.
PlaneOutline unit_square() {
  PlaneOutline square;
  square.u = Eigen::Vector3d::UnitX();
  square.v = Eigen::Vector3d::UnitY();
  square.hull = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  square.drawn = {1, 1, 1, 1};
  square.near = 0.05;
  square.least_cosine = std::cos(M_PI / 9.0);
  return square;
}

TEST(PlaneOutline, PullsAPointBackAcrossADrawnEdgeOntoTheOutline) {
  const PlaneOutline square = unit_square();
  const auto q = square.pull_back({1.5, 0.25, 0.01}, kUp, 0.02);
  ASSERT_TRUE(q.has_value());
  EXPECT_NEAR((*q - Eigen::Vector3d(1.0, 0.25, 0.0)).norm(), 0.0, 1e-12);
  const auto corner = square.pull_back({1.5, 1.5, 0.0}, kUp, 0.02);
  ASSERT_TRUE(corner.has_value());
  EXPECT_NEAR((*corner - Eigen::Vector3d(1.0, 1.0, 0.0)).norm(), 0.0, 1e-12);
}

TEST(PlaneOutline, LeavesPointsInsideWithinTheMarginOrOffThePlane) {
  const PlaneOutline square = unit_square();
  EXPECT_FALSE(square.pull_back({0.5, 0.5, 0.0}, kUp, 0.02));
  EXPECT_FALSE(square.pull_back({1.01, 0.5, 0.0}, kUp, 0.02)) << "within the margin";
  EXPECT_FALSE(square.pull_back({1.5, 0.5, 0.2}, kUp, 0.02)) << "farther from the plane than `near`";
  EXPECT_FALSE(square.pull_back({1.5, 0.5, 0.0}, Eigen::Vector3d(1, 0, 1), 0.02))
      << "a surface crossing the plane at 45 degrees";
  EXPECT_TRUE(square.pull_back({1.5, 0.5, 0.0}, Eigen::Vector3d(0.2, 0, -1), 0.02)) << "11 degrees, either side";
  EXPECT_FALSE(square.pull_back({1.5, 0.5, 0.0}, Eigen::Vector3d::Zero(), 0.02)) << "no normal: no direction";
}

TEST(PlaneOutline, AnUndrawnEdgeLimitsNothing) {
  PlaneOutline square = unit_square();
  square.drawn[1] = 0;  // x = 1
  EXPECT_FALSE(square.pull_back({1.5, 0.5, 0.0}, kUp, 0.02));
  EXPECT_FALSE(square.pull_back({1.5, 1.5, 0.0}, kUp, 0.02)) << "a corner of an undrawn edge";
  EXPECT_TRUE(square.pull_back({0.5, -0.5, 0.0}, kUp, 0.02)) << "edge 0 is drawn";
}

// A drawn cylinder's two caps, each labelled on a rounded-cylinder proxy of the same size: every
// cap gets an outline round its rim circle, drawn all round; the side has none.
TEST(PlaneOutline, EachFlatCapOfACylinderHasItsRimAsADrawnOutline) {
  const double radius = 0.5, half_height = 0.3;
  LabeledMesh mesh;
  mesh.mesh = rounded_cylinder_mesh(4, radius, half_height, 0.02);
  for (auto v : mesh.mesh.vertices()) {
    const Eigen::Vector3d p = to_eigen(mesh.mesh.point(v));
    const double rho = std::hypot(p.x(), p.y());
    mesh.labels.push_back({rho / radius > std::abs(p.z()) / half_height ? 0 : (p.z() > 0 ? 1 : 2)});
  }
  mesh.source_vertex.assign(mesh.mesh.n_vertices(), -1);
  ImplicitModel side;  // x^2 + y^2 - r^2
  side.degree = 2;
  side.coefficients = Eigen::VectorXd::Zero(10);
  side.coefficients << -radius * radius, 0, 0, 0, 1, 0, 0, 1, 0, 0;
  const std::vector<ImplicitModel> models{side, plane_model({0, 0, 1}, half_height),
                                          plane_model({0, 0, -1}, half_height)};
  const Sketch sketch = cylinder_sketch(radius, 2 * half_height);
  const double diagonal = sketch.bounding_box().diagonal();
  const auto outlines = plane_outlines(mesh, models, stroke_segments(sketch, false), diagonal, {});
  ASSERT_EQ(outlines.size(), 3u);
  EXPECT_FALSE(outlines[0].has_value()) << "the side is curved";
  for (int cap : {1, 2}) {
    ASSERT_TRUE(outlines[cap].has_value()) << cap;
    const PlaneOutline& o = *outlines[cap];
    EXPECT_GT(o.hull.size(), 12u);
    for (std::size_t e = 0; e < o.drawn.size(); ++e)
      EXPECT_TRUE(o.drawn[e]) << "cap " << cap << ", edge " << e << " of " << o.drawn.size();
    for (const Eigen::Vector2d& h : o.hull) {
      const Eigen::Vector3d p = o.origin + h.x() * o.u + h.y() * o.v;
      // The rim, and the ends of the cap's cross stroke (a chord at y = 0.2 r, x = +-r).
      EXPECT_GE(std::hypot(p.x(), p.y()), radius - 1e-3);
      EXPECT_LE(std::hypot(p.x(), p.y()), std::hypot(radius, 0.2 * radius) + 1e-6);
      EXPECT_NEAR(std::abs(p.z()), half_height, 1e-3);
    }
  }
}

TEST(OutlineOptions, RejectsInvalidValuesAndNamesTheParameter) {
  std::string why;
  EXPECT_TRUE(OutlineOptions{}.valid(&why)) << why;
  OutlineOptions o;
  o.margin = -0.1;
  EXPECT_FALSE(o.valid(&why));
  EXPECT_NE(why.find("extract.outline_margin"), std::string::npos) << why;
  o = {};
  o.flat_share = 1.5;
  EXPECT_FALSE(o.valid(&why));
  EXPECT_NE(why.find("extract.outline_flat_share"), std::string::npos) << why;
  o = {};
  o.reach = 0.0;
  EXPECT_FALSE(o.valid(&why));
  EXPECT_NE(why.find("extract.outline_reach"), std::string::npos) << why;
}

}  // namespace
}  // namespace sketchsurf
