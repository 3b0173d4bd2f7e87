#include "surfacing/segment/crease_guides.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "surfacing/error.h"
#include "surfacing/mesh.h"
#include "tests/support/shapes.h"

namespace sketchsurf {
namespace {

using V3 = Eigen::Vector3d;

using testing::polyline_stroke;

// Rectangular sections of a box at each x, corners at y = +-0.1, z = +-0.15.
Sketch sections(const std::vector<double>& xs) { return testing::box_sections_sketch(V3(0.3, 0.1, 0.15), xs); }

TEST(StrokeCorners, AnLTurnIsOneCornerWhoseAxisIsTheNormalOfItsPlane) {
  Sketch sketch;
  sketch.strokes.push_back(polyline_stroke({V3(0, 0, 0), V3(0.3, 0, 0), V3(0.3, 0.3, 0)}, false));
  const auto corners = stroke_corners(sketch, 1.0);
  ASSERT_EQ(corners.size(), 1u);
  EXPECT_LT((corners[0].position - V3(0.3, 0, 0)).norm(), 0.003);
  EXPECT_GT(std::abs(corners[0].axis.z()), 0.999);
}

TEST(StrokeCorners, ASectionHasFourCornersAcrossItsClosingPoint) {
  const Sketch sketch = sections({0.0});
  const auto corners = stroke_corners(sketch, 1.0);
  ASSERT_EQ(corners.size(), 4u);  // one of them is where the stroke starts and ends
  for (const auto& c : corners) {
    EXPECT_NEAR(std::abs(c.position.y()), 0.1, 0.003);
    EXPECT_NEAR(std::abs(c.position.z()), 0.15, 0.003);
    EXPECT_GT(std::abs(c.axis.x()), 0.999);
  }
}

TEST(StrokeCorners, TightArcsHairpinsAndStraightLinesHaveNone) {
  Sketch sketch;
  // A circle of radius 0.015: turns 76 degrees over the window everywhere, but only half of that
  // within half the window.
  sketch.strokes.push_back(testing::sample_curve(
      [](double t) { return V3(0.015 * std::cos(t), 0.015 * std::sin(t), 0.0); }, 0.0, 2 * M_PI, 0.0005));
  sketch.strokes.push_back(polyline_stroke({V3(0, 0.2, 0), V3(0.3, 0.2, 0), V3(0, 0.2005, 0)}, false));
  sketch.strokes.push_back(polyline_stroke({V3(0, 0.4, 0), V3(0.5, 0.45, 0.1)}, false));
  EXPECT_TRUE(stroke_corners(sketch, 1.0).empty());
}

TEST(CreaseGuides, CornersOfNeighbouringSectionsAreJoinedAlongTheBoxEdges) {
  Sketch sketch = sections({-0.2, 0.0, 0.2});
  const auto guides = crease_guides(sketch, 1.0);
  // Four edges, each joined between neighbouring sections only (never -0.2 to 0.2 directly).
  ASSERT_EQ(guides.size(), 8u);
  for (const auto& g : guides) {
    EXPECT_NEAR((g[1] - g[0]).norm(), 0.2, 0.006);
    EXPECT_GT(std::abs((g[1] - g[0]).normalized().x()), 0.999);
    EXPECT_NEAR(std::abs(g[0].y()), 0.1, 0.003);
  }
  CreaseGuideOptions off;
  off.enabled = false;
  EXPECT_TRUE(crease_guides(sketch, 1.0, off).empty());
  // Scale: the same sketch ten times larger, lengths given as fractions of its diagonal.
  for (auto& s : sketch.strokes)
    for (auto& p : s.points) p *= 10.0;
  EXPECT_EQ(crease_guides(sketch, 10.0).size(), 8u);
}

TEST(CreaseGuides, SectionsTooFarApartOrTurnedAreNotJoined) {
  Sketch sketch = sections({0.0, 0.35});  // beyond max_gap
  Stroke turned = sketch.strokes[0];
  for (auto& p : turned.points) p = V3(p.y(), p.x() - 0.25, p.z());  // axis along y
  sketch.strokes.push_back(turned);
  EXPECT_TRUE(crease_guides(sketch, 1.0).empty());
}

// A stroke round a plate's thin side at x = 0.5: along the top face (y = y0 + 0.02) to the side,
// down it, back along the bottom face (y = y0 - 0.02), in the plane z.
Stroke round_thin_side(double z, double y0) {
  return polyline_stroke({V3(0.2, y0 + 0.02, z), V3(0.5, y0 + 0.02, z), V3(0.5, y0 - 0.02, z), V3(0.2, y0 - 0.02, z)},
                         false);
}

TEST(CreaseGuides, CornersRoundAThinSideJoinTopToTopAndBottomToBottom) {
  // The second stroke is drawn 0.03 higher: its bottom corner lies nearer the first's top corner
  // (and within the alignment) than its own top corner does, but points the other way.
  Sketch sketch;
  sketch.strokes.push_back(round_thin_side(0.0, 0.0));
  sketch.strokes.push_back(round_thin_side(0.15, 0.03));
  const auto corners = stroke_corners(sketch, 1.0);
  ASSERT_EQ(corners.size(), 4u);
  for (const auto& c : corners) EXPECT_NEAR(std::abs(c.apex.y()), std::sqrt(0.5), 1e-3);
  auto joins_top_to_top = [](const std::array<V3, 2>& g) {
    const double y0 = g[0].z() < g[1].z() ? g[0].y() : g[1].y(), y1 = g[0].z() < g[1].z() ? g[1].y() : g[0].y();
    return std::abs(y1 - y0 - 0.03) < 1e-3;
  };
  const auto guides = crease_guides(sketch, 1.0);
  ASSERT_EQ(guides.size(), 2u);
  for (const auto& g : guides) EXPECT_TRUE(joins_top_to_top(g));
  // By distance alone the first stroke's top corner joins the second's bottom corner.
  CreaseGuideOptions nearest_only;
  nearest_only.same_way = 180;
  const auto crossed = crease_guides(sketch, 1.0, nearest_only);
  ASSERT_EQ(crossed.size(), 1u);
  EXPECT_FALSE(joins_top_to_top(crossed[0]));
}

TEST(CreaseGuides, ACornerWithNoSameWayPartnerJoinsItsNearest) {
  // Two L turns along z whose tips point 90 degrees apart: each is the other's only candidate.
  Sketch sketch;
  sketch.strokes.push_back(polyline_stroke({V3(0.2, 0, 0), V3(0.5, 0, 0), V3(0.5, 0.3, 0)}, false));
  sketch.strokes.push_back(polyline_stroke({V3(0.2, 0, 0.15), V3(0.5, 0, 0.15), V3(0.5, -0.3, 0.15)}, false));
  const auto corners = stroke_corners(sketch, 1.0);
  ASSERT_EQ(corners.size(), 2u);
  EXPECT_NEAR(corners[0].apex.dot(corners[1].apex), 0.0, 1e-3);
  EXPECT_EQ(crease_guides(sketch, 1.0).size(), 1u);
}

TEST(CreaseGuides, OnlyJoinsAlongWhichTheSurfaceFoldsAreKept) {
  // A rounded box: a join along one of its edges is kept; one across a flat face (corners that
  // line up by chance), one diagonal over a narrow face reaching its rounded edges, and one
  // along the middle of a face are not.
  const V3 half(0.3, 0.1, 0.15);
  const TriMesh mesh = testing::rounded_box_mesh(4, half, 0.02);
  const Eigen::MatrixX3d V = vertex_matrix(mesh);
  const Eigen::MatrixX3d N = vertex_normals(V, face_matrix(mesh));
  const std::vector<std::array<V3, 2>> guides{
      {V3(-0.2, 0.1, 0.15), V3(0.2, 0.1, 0.15)},     // the edge y = 0.1, z = 0.15
      {V3(-0.2, -0.05, 0.15), V3(0.2, 0.05, 0.15)},  // across the front face
      {V3(-0.3, -0.1, -0.05), V3(-0.3, 0.1, 0.05)},  // diagonal over the narrow end face
      {V3(-0.2, 0.0, 0.15), V3(0.2, 0.0, 0.15)}};    // along the middle of the front face
  const auto kept = guides_on_folds(guides, V, N, 2.0 * half.norm());
  ASSERT_EQ(kept.size(), 1u);
  EXPECT_EQ(kept[0][0], guides[0][0]);
  EXPECT_EQ(kept[0][1], guides[0][1]);
}

TEST(CreaseGuides, InvalidOptionsAreUsageErrors) {
  const Sketch sketch = sections({0.0});
  const std::vector<std::function<void(CreaseGuideOptions&)>> breakers{
      [](CreaseGuideOptions& o) { o.min_turn = 160; }, [](CreaseGuideOptions& o) { o.max_gap = 0.0; },
      [](CreaseGuideOptions& o) { o.alignment = 90; }, [](CreaseGuideOptions& o) { o.min_fold = 95; },
      [](CreaseGuideOptions& o) { o.same_way = 0; }, [](CreaseGuideOptions& o) { o.same_way = 181; }};
  for (const auto& breaker : breakers) {
    CreaseGuideOptions o;
    breaker(o);
    EXPECT_THROW(crease_guides(sketch, 1.0, o), Error);
  }
}

}  // namespace
}  // namespace sketchsurf
