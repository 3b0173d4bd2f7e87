// Strokes that depict no surface: an antenna hanging by one end, a dot apart and a dot touching
// the object are found; the strokes of curve networks, with exact or imprecise junctions, short
// strokes longer than a dot and closed outlines are not.

#include <gtest/gtest.h>

#include "surfacing/sketch/decorations.h"
#include "tests/support/shapes.h"

namespace sketchsurf {
namespace {

using V3 = Eigen::Vector3d;

Stroke segment(const V3& a, const V3& b) {
  return testing::sample_curve([&](double t) { return V3(a + t * (b - a)); }, 0.0, 1.0, 0.005);
}

TEST(Decorations, CurveNetworksHaveNone) {
  EXPECT_TRUE(find_decorations(testing::prepared_sketch(testing::cube_sketch())).empty());
  EXPECT_TRUE(find_decorations(testing::prepared_sketch(testing::cylinder_sketch())).empty());
  EXPECT_TRUE(find_decorations(testing::prepared_sketch(testing::sphere_sketch())).empty());
  EXPECT_TRUE(find_decorations(testing::prepared_sketch(testing::torus_sketch())).empty());
}

TEST(Decorations, ImpreciseJunctionsAreNotAntennas) {
  // Every cube edge stops 3% of the side short of its corners, as hands draw in mid-air.
  Sketch cube = testing::cube_sketch(1.0, false);
  for (Stroke& s : cube.strokes) {
    const V3 a = s.points.front(), b = s.points.back(), d = 0.03 * (b - a).normalized();
    s = segment(a + d, b - d);
  }
  EXPECT_TRUE(find_decorations(testing::prepared_sketch(cube)).empty());
}

TEST(Decorations, AnAntennaHangingByOneEndIsFound) {
  Sketch sketch = testing::sphere_sketch(0.5, 4);
  sketch.strokes.push_back(segment(V3(0.5, 0, 0), V3(0.9, 0, 0)));
  const Sketch s = testing::prepared_sketch(sketch);
  const auto found = find_decorations(s);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].stroke, s.strokes.size() - 1);
  EXPECT_EQ(found[0].id, s.strokes.back().id);
  EXPECT_EQ(found[0].kind, DecorationKind::Dangling);
}

TEST(Decorations, AnEdgeOfAFaceWhoseNeighbouringEdgesAreMissingIsKept) {
  // A cube whose two bottom edges at one corner were left out: the vertical edge above that
  // corner touches the others by its top end only, and its free end is a side away from them.
  Sketch cube = testing::cube_sketch(1.0, false);
  const V3 corner(-0.5, -0.5, -0.5);
  const auto at_corner = [&](const Stroke& s) {
    return (s.points.front() - corner).norm() < 1e-9 || (s.points.back() - corner).norm() < 1e-9;
  };
  std::erase_if(cube.strokes, [&](const Stroke& s) { return at_corner(s) && s.points.back().y() < 0.0; });
  ASSERT_EQ(cube.strokes.size(), 10u);
  EXPECT_TRUE(find_decorations(testing::prepared_sketch(cube)).empty());

  // The same edge standing out of the box is an antenna.
  for (Stroke& s : cube.strokes)
    if (at_corner(s)) s = segment(V3(-0.5, 0.5, -0.5), V3(-1.1, -0.2, -1.1));
  const Sketch s = testing::prepared_sketch(cube);
  const auto found = find_decorations(s);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].kind, DecorationKind::Dangling);
}

TEST(Decorations, LineLegsAlongTheBoxTheyStretchAreNotFacesEdges) {
  // A slab on four legs drawn as single lines: each leg lies along two sides of the box that the
  // other three stretch down to their feet, but the box of the strokes that stay is the slab's.
  Sketch table = testing::cube_sketch(1.0, true);
  for (Stroke& s : table.strokes)
    for (V3& p : s.points) p.y() *= 0.15;
  for (double x : {-0.5, 0.5})
    for (double z : {-0.5, 0.5}) table.strokes.push_back(segment(V3(x, -0.075, z), V3(x, -0.8, z)));
  const auto found = find_decorations(testing::prepared_sketch(table));
  ASSERT_EQ(found.size(), 4u);
  for (const Decoration& d : found) EXPECT_EQ(d.kind, DecorationKind::Dangling);
}

// A sphere with a cable: a long curve hanging from it whose far end carries a plug (a small loop
// and a short stroke across it, touching only the cable).
Sketch sphere_with_cable() {
  Sketch sketch = testing::sphere_sketch(0.5, 4);
  sketch.strokes.push_back(testing::sample_curve(
      [](double t) { return V3(0.5 + t, -0.3 * std::sin(M_PI * t), 0.2 * t); }, 0.0, 1.0, 0.005));
  const V3 end(1.5, 0.0, 0.2);
  sketch.strokes.push_back(testing::sample_curve(
      [&](double t) { return V3(end + V3(0.04 + 0.04 * std::cos(t), 0.04 * std::sin(t), 0.0)); }, 0.0,
      2 * M_PI, 0.005));
  sketch.strokes.push_back(segment(end + V3(0.04, -0.06, 0.0), end + V3(0.04, 0.06, 0.0)));
  return sketch;
}

TEST(Decorations, ACableIsFoundWithThePlugItCarries) {
  const Sketch s = testing::prepared_sketch(sphere_with_cable());
  const auto found = find_decorations(s);
  ASSERT_EQ(found.size(), 3u);
  const std::size_t cable = s.strokes.size() - 3;
  EXPECT_EQ(found[0].stroke, cable);
  EXPECT_EQ(found[0].kind, DecorationKind::Dangling);
  for (std::size_t k = 1; k < 3; ++k) {
    EXPECT_EQ(found[k].stroke, cable + k);
    EXPECT_EQ(found[k].kind, DecorationKind::SmallGroup);
  }
}

TEST(Decorations, AStrokeRunningBesideAnotherIsAThinPartsEdgeNotACable) {
  // A second stroke from the sphere runs along the cable's first 70%, 0.08 away (3% of the
  // diagonal): the two are the edges of a thin part (a leg, its foot ring the "plug").
  Sketch sketch = sphere_with_cable();
  sketch.strokes.push_back(testing::sample_curve(
      [](double t) { return V3(0.5 + t, -0.3 * std::sin(M_PI * t) + 0.08, 0.2 * t); }, 0.0, 0.7, 0.005));
  EXPECT_TRUE(find_decorations(testing::prepared_sketch(sketch)).empty());
}

TEST(Decorations, AStrokeCarryingALargeGroupIsNotACable) {
  // The same curve ending at a second sphere (a third of the sketch's diagonal across): an arm
  // holding a part, not a cable.
  Sketch sketch = testing::sphere_sketch(0.5, 4);
  sketch.strokes.push_back(testing::sample_curve(
      [](double t) { return V3(0.5 + t, -0.3 * std::sin(M_PI * t), 0.2 * t); }, 0.0, 1.0, 0.005));
  Sketch other = testing::sphere_sketch(0.25, 4);
  for (Stroke& stroke : other.strokes) {
    for (V3& p : stroke.points) p += V3(1.75, 0.0, 0.2);
    sketch.strokes.push_back(stroke);
  }
  EXPECT_TRUE(find_decorations(testing::prepared_sketch(sketch)).empty());
}

TEST(Decorations, ADotApartIsFoundAndAClosedOutlineOnAFaceIsNot) {
  Sketch sketch = testing::cube_sketch();
  sketch.strokes.push_back(segment(V3(1.0, 1.0, 1.0), V3(1.004, 1.0, 1.0)));  // a dot
  // A circle drawn on the top face, touching no other stroke.
  sketch.strokes.push_back(testing::sample_curve(
      [](double t) { return V3(0.25 + 0.1 * std::cos(t), 0.5, -0.25 + 0.1 * std::sin(t)); }, 0, 2 * M_PI, 0.005));
  const Sketch s = testing::prepared_sketch(sketch);
  const auto found = find_decorations(s);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].stroke, s.strokes.size() - 2);
  EXPECT_EQ(found[0].kind, DecorationKind::SmallGroup);
}

TEST(Decorations, ADotTouchingTheObjectIsFoundAndAShortStrokeIsNot) {
  // The cube's diagonal is sqrt(3): a dot is under 0.017 long. Both strokes start on the top
  // face's front edge, so they belong to the object's group.
  Sketch sketch = testing::cube_sketch();
  sketch.strokes.push_back(segment(V3(0.0, 0.5, 0.5), V3(0.0, 0.49, 0.49)));  // 0.014: a dot
  sketch.strokes.push_back(segment(V3(0.2, 0.5, 0.5), V3(0.2, 0.5, 0.47)));   // 0.03: a tick
  const Sketch s = testing::prepared_sketch(sketch);
  const auto found = find_decorations(s);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].stroke, s.strokes.size() - 2);
  EXPECT_EQ(found[0].kind, DecorationKind::Dot);
  DecorationOptions off;
  off.dot = 0.0;
  EXPECT_TRUE(find_decorations(s, off).empty());
}

TEST(Decorations, StrokesTheUserMarkedAreLeftAlone) {
  Sketch sketch = testing::sphere_sketch(0.5, 4);
  sketch.strokes.push_back(segment(V3(0.5, 0, 0), V3(0.9, 0, 0)));
  sketch.strokes.back().boundary = true;
  EXPECT_TRUE(find_decorations(testing::prepared_sketch(sketch)).empty());
  sketch.strokes.back().boundary = false;
  sketch.strokes.back().ignored = true;
  EXPECT_TRUE(find_decorations(testing::prepared_sketch(sketch)).empty());
  // A boundary stroke is never carried off with a cable.
  Sketch cable = sphere_with_cable();
  cable.strokes.back().boundary = true;
  EXPECT_TRUE(find_decorations(testing::prepared_sketch(cable)).empty());
}

TEST(Decorations, InvalidOptionsAreNamed) {
  DecorationOptions options;
  options.free_end = 0.01;  // below `touch`
  std::string why;
  EXPECT_FALSE(options.valid(&why));
  EXPECT_NE(why.find("free_end"), std::string::npos);
}

}  // namespace
}  // namespace sketchsurf
