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

constexpr double kRadius = 0.5, kHalfHeight = 0.3;

// A drawn cylinder's outlines on a rounded-cylinder proxy of the same size, its side labelled 0
// (x^2 + y^2 = r^2) and its caps 1 and 2 (planes). When `slab`, label 1 takes the bottom cap's
// part beyond x = 0.6 r as well and its model is z^2 = h^2: the two parallel planes a quadric
// fits to a thin plate's faces, with the strokes of one face and a few of the other's.
std::vector<std::vector<PlaneOutline>> cylinder_outlines(bool slab) {
  LabeledMesh mesh;
  mesh.mesh = rounded_cylinder_mesh(4, kRadius, kHalfHeight, 0.02);
  for (auto v : mesh.mesh.vertices()) {
    const Eigen::Vector3d p = to_eigen(mesh.mesh.point(v));
    const double rho = std::hypot(p.x(), p.y());
    const bool top = p.z() > 0 || (slab && p.x() > 0.6 * kRadius);
    mesh.labels.push_back({rho / kRadius > std::abs(p.z()) / kHalfHeight ? 0 : (top ? 1 : 2)});
  }
  mesh.source_vertex.assign(mesh.mesh.n_vertices(), -1);
  ImplicitModel side;
  side.degree = 2;
  side.coefficients = Eigen::VectorXd::Zero(10);
  side.coefficients << -kRadius * kRadius, 0, 0, 0, 1, 0, 0, 1, 0, 0;
  std::vector<ImplicitModel> models{side};
  if (slab) {
    ImplicitModel faces = side;
    faces.coefficients << -kHalfHeight * kHalfHeight, 0, 0, 0, 0, 0, 0, 0, 0, 1;
    models.push_back(faces);
  } else {
    models.push_back(plane_model({0, 0, 1}, kHalfHeight));
  }
  models.push_back(plane_model({0, 0, -1}, kHalfHeight));
  const Sketch sketch = cylinder_sketch(kRadius, 2 * kHalfHeight);
  const double diagonal = sketch.bounding_box().diagonal();
  return plane_outlines(mesh, models, stroke_segments(sketch, false), diagonal, {});
}

// A cap's outline: round its rim circle, drawn all round.
void expect_rim(const PlaneOutline& o) {
  EXPECT_GT(o.hull.size(), 12u);
  for (std::size_t e = 0; e < o.drawn.size(); ++e)
    EXPECT_TRUE(o.drawn[e]) << "edge " << e << " of " << o.drawn.size();
  for (const Eigen::Vector2d& h : o.hull) {
    const Eigen::Vector3d p = o.origin + h.x() * o.u + h.y() * o.v;
    // The rim, and the ends of the cap's cross stroke (a chord at y = 0.2 r, x = +-r).
    EXPECT_GE(std::hypot(p.x(), p.y()), kRadius - 1e-3);
    EXPECT_LE(std::hypot(p.x(), p.y()), std::hypot(kRadius, 0.2 * kRadius) + 1e-6);
    EXPECT_NEAR(std::abs(p.z()), kHalfHeight, 1e-3);
  }
}

TEST(PlaneOutline, EachFlatCapOfACylinderHasItsRimAsADrawnOutline) {
  const auto outlines = cylinder_outlines(false);
  ASSERT_EQ(outlines.size(), 3u);
  EXPECT_TRUE(outlines[0].empty()) << "the side is curved";
  for (int cap : {1, 2}) {
    ASSERT_EQ(outlines[cap].size(), 1u) << cap;
    expect_rim(outlines[cap][0]);
  }
}

// A slab model over the top cap and part of the bottom one: each of its two planes gets its own
// rim as an outline, so that a proxy's bulge past either rim is pulled back (a thin plate's
// corner); the rest of the bottom cap keeps its own.
TEST(PlaneOutline, BothPlanesOfASlabModelHaveTheirRimsAsOutlines) {
  const auto outlines = cylinder_outlines(true);
  ASSERT_EQ(outlines.size(), 3u);
  EXPECT_TRUE(outlines[0].empty()) << "the side is curved";
  ASSERT_EQ(outlines[1].size(), 2u);
  expect_rim(outlines[1][0]);
  expect_rim(outlines[1][1]);
  EXPECT_NEAR(outlines[1][0].origin.z() + outlines[1][1].origin.z(), 0.0, 1e-3) << "z = h and z = -h";
  ASSERT_EQ(outlines[2].size(), 1u);
  expect_rim(outlines[2][0]);
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
