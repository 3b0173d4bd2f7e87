// Open rims: a cup's rim is found and oriented out of the cup; loops that something crosses, or
// that nothing lies under (a torus's inner equator, a cylinder's rims), are not rims.

#include <gtest/gtest.h>

#include <cmath>

#include "surfacing/sketch/openings.h"
#include "tests/support/shapes.h"

namespace sketchsurf {
namespace {

using V3 = Eigen::Vector3d;

double degrees_between(const V3& a, const V3& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) * 180.0 / M_PI;
}

TEST(Openings, ACupRimIsFoundAndPointsOut) {
  const Sketch cup = testing::prepared_sketch(testing::cup_sketch());
  const auto found = find_openings(cup);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].stroke, 1u);  // the rim, not the bottom circle
  EXPECT_EQ(found[0].id, cup.strokes[1].id);
  EXPECT_LT(degrees_between(found[0].loop.plane.normal, V3::UnitZ()), 1.0);
  EXPECT_NEAR(found[0].loop.radius, 0.5, 0.01);
  EXPECT_NEAR(found[0].loop.center.z(), 0.8, 1e-3);
}

// The cup turned so that its axis is `axis` (y is up).
Sketch turned_cup(const V3& axis) {
  Sketch cup = testing::cup_sketch();
  const Eigen::Quaterniond turn = Eigen::Quaterniond::FromTwoVectors(V3::UnitZ(), axis);
  for (Stroke& s : cup.strokes)
    for (V3& p : s.points) p = turn * p;
  return testing::prepared_sketch(cup);
}

TEST(Openings, ASidewaysCupOpensSideways) {
  const auto found = find_openings(turned_cup(V3(1, 0, 0)));
  ASSERT_EQ(found.size(), 1u);
  EXPECT_LT(degrees_between(found[0].loop.plane.normal, V3::UnitX()), 1.0);
}

TEST(Openings, ALoopFacingDownIsABaseNotAnOpening) {
  // A sole or a base the object stands on: drawn as an outline with nothing across, like a rim.
  EXPECT_TRUE(find_openings(turned_cup(V3(0, -1, 0))).empty());
  EXPECT_EQ(find_openings(turned_cup(V3(0, 1, 0))).size(), 1u);
}

TEST(Openings, SectionsUnderTheRimAreNotRims) {
  Sketch cup = testing::cup_sketch();  // walls from radius 0.35 at z = 0 to 0.5 at z = 0.8
  for (double z : {0.2, 0.4, 0.6})
    cup.strokes.push_back(testing::sample_curve([z](double t) {
      const double r = 0.35 + 0.15 * z / 0.8;
      return V3(r * std::cos(t), r * std::sin(t), z);
    }, 0.0, 2 * M_PI, 0.0125));
  const auto found = find_openings(testing::prepared_sketch(cup));
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].stroke, 1u);
}

TEST(Openings, AStrokeAcrossTheRimClosesIt) {
  Sketch cup = testing::cup_sketch();
  cup.strokes.push_back(testing::sample_curve([](double t) { return V3(t, 0.1, 0.8); }, -0.45, 0.45, 0.01));
  EXPECT_TRUE(find_openings(testing::prepared_sketch(cup)).empty());
}

TEST(Openings, ClosedShapesHaveNone) {
  EXPECT_TRUE(find_openings(testing::prepared_sketch(testing::cylinder_sketch())).empty());  // strokes across the caps
  EXPECT_TRUE(find_openings(testing::prepared_sketch(testing::sphere_sketch())).empty());
  EXPECT_TRUE(find_openings(testing::prepared_sketch(testing::torus_sketch())).empty());     // nothing under the hole
  EXPECT_TRUE(find_openings(testing::prepared_sketch(testing::cube_sketch())).empty());
}

TEST(Openings, MarkedAndIgnoredStrokesAreLeftAlone) {
  Sketch cup = testing::prepared_sketch(testing::cup_sketch());
  cup.strokes[1].boundary = true;
  EXPECT_TRUE(find_openings(cup).empty());
  cup.strokes[1].boundary = false;
  cup.strokes[1].ignored = true;
  EXPECT_TRUE(find_openings(cup).empty());
}

TEST(Openings, LoopsAreClosedAndFlat) {
  const Stroke arc = testing::sample_curve([](double t) { return V3(std::cos(t), std::sin(t), 0); }, 0, 1.5 * M_PI, 0.01);
  EXPECT_FALSE(stroke_loop(arc.points));
  const Stroke saddle = testing::sample_curve(
      [](double t) { return V3(std::cos(t), std::sin(t), 0.5 * std::cos(2 * t)); }, 0, 2 * M_PI, 0.01);
  EXPECT_FALSE(stroke_loop(saddle.points));
  const Stroke circle = testing::sample_curve(
      [](double t) { return V3(std::cos(t), std::sin(t), 0.02 * std::cos(2 * t)); }, 0, 2 * M_PI, 0.01);
  const auto loop = stroke_loop(circle.points);
  ASSERT_TRUE(loop);
  EXPECT_NEAR(loop->radius, 1.0, 0.01);
  EXPECT_TRUE(loop->encloses(V3(0.5, 0.2, 3.0), 0.1));
  EXPECT_FALSE(loop->encloses(V3(0.95, 0.0, 0.0), 0.1));  // inside, but within the margin
  EXPECT_FALSE(loop->encloses(V3(1.5, 0.0, 0.0), 0.0));
}

}  // namespace
}  // namespace sketchsurf
