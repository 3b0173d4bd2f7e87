// Over-sketching: passes of one curve are pulled onto their centre line; strokes that cross, run
// side by side a thin part's width apart, or are ignored stay where they are.

#include <gtest/gtest.h>

#include <cmath>

#include "surfacing/error.h"
#include "surfacing/sketch/consolidate.h"
#include "tests/support/shapes.h"

namespace sketchsurf {
namespace {

using V3 = Eigen::Vector3d;

Stroke line(const V3& a, const V3& b, double spacing = 0.005) {
  return testing::sample_curve([&](double t) -> V3 { return (1 - t) * a + t * b; }, 0.0, 1.0, spacing);
}

// A frame that sets the bounding-box diagonal near 1 (a far stroke the tests do not look at).
Sketch with_frame(std::vector<Stroke> strokes) {
  Sketch sketch;
  sketch.strokes.push_back(line(V3(0, 0.6, 0.6), V3(0.1, 0.6, 0.6)));
  for (auto& s : strokes) sketch.strokes.push_back(std::move(s));
  sketch.assign_ids();
  return sketch;
}

double max_move(const Stroke& a, const Stroke& b) {
  double m = 0.0;
  for (std::size_t i = 0; i < a.points.size(); ++i) m = std::max(m, (a.points[i] - b.points[i]).norm());
  return m;
}

TEST(Consolidate, TwoPassesOfALineMeetOnTheirCentreLine) {
  // Two passes 0.4% of the diagonal apart (one above the other), the second a bit shorter.
  const Sketch before = with_frame({line(V3(0, 0, 0), V3(0.8, 0, 0)), line(V3(0.1, 0.004, 0), V3(0.7, 0.004, 0))});
  Sketch after = before;
  const Consolidation c = consolidate_overdrawn(after);
  EXPECT_EQ(c.strokes, 2u);
  const Stroke& a = after.strokes[1];
  const Stroke& b = after.strokes[2];
  // Where both run (away from the second's ends by the taper), both lie on y = 0.002.
  for (const Stroke* s : {&a, &b}) {
    for (const V3& p : s->points) {
      if (p.x() > 0.2 && p.x() < 0.6) {
        EXPECT_NEAR(p.y(), 0.002, 1e-4) << p.transpose();
      }
    }
  }
  // Moves are across the strokes only: x (along) unchanged to first order, z unchanged.
  for (std::size_t k = 1; k <= 2; ++k)
    for (std::size_t i = 0; i < after.strokes[k].points.size(); ++i) {
      EXPECT_NEAR(after.strokes[k].points[i].x(), before.strokes[k].points[i].x(), 1e-4);  // 2% of the spacing
      EXPECT_NEAR(after.strokes[k].points[i].z(), 0.0, 1e-12);
    }
  // Beyond the overlap (and its taper) the longer pass is where it was drawn.
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    if (a.points[i].x() < 0.03 || a.points[i].x() > 0.77) {
        EXPECT_NEAR(a.points[i].y(), 0.0, 2e-4);
      }
  }
  EXPECT_NEAR(c.max_shift * after.bounding_box().diagonal(), 0.002, 2e-4);
}

TEST(Consolidate, ThreePassesDrawnBothWaysBecomeOne) {
  Sketch sketch = with_frame({line(V3(0, 0, 0), V3(0.8, 0, 0)), line(V3(0.8, 0.003, 0.003), V3(0, 0.003, 0.003)),
                              line(V3(0, -0.003, 0.003), V3(0.8, -0.003, 0.003))});
  consolidate_overdrawn(sketch);
  const V3 centre(0.0, 0.0, 0.002);
  for (std::size_t k = 1; k <= 3; ++k)
    for (const V3& p : sketch.strokes[k].points)
      if (p.x() > 0.1 && p.x() < 0.7) {
        EXPECT_NEAR(p.y(), centre.y(), 2e-4);
        EXPECT_NEAR(p.z(), centre.z(), 2e-4);
      }
}

TEST(Consolidate, ABackAndForthStrokeIsPulledOntoOneLine) {
  Stroke zigzag = line(V3(0, 0, 0), V3(0.8, 0, 0));
  const Stroke back = line(V3(0.8, 0.004, 0), V3(0, 0.004, 0));
  zigzag.points.insert(zigzag.points.end(), back.points.begin() + 1, back.points.end());
  Sketch sketch = with_frame({zigzag});
  const Consolidation c = consolidate_overdrawn(sketch);
  EXPECT_EQ(c.strokes, 1u);
  for (const V3& p : sketch.strokes[1].points) {
    if (p.x() > 0.1 && p.x() < 0.7) {
        EXPECT_NEAR(p.y(), 0.002, 2e-4);
      }
  }
}

TEST(Consolidate, CrossingStrokesThinPartsAndIgnoredStrokesStay) {
  // Crossing at right angles; two sides of a thin part 3% apart; a pass next to an ignored stroke.
  Stroke ignored = line(V3(0, 0.5, 0.004), V3(0.8, 0.5, 0.004));
  ignored.ignored = true;
  const Sketch before = with_frame({line(V3(0, 0, 0), V3(0.8, 0, 0)), line(V3(0.4, -0.4, 0), V3(0.4, 0.4, 0)),
                                    line(V3(0, 0.2, 0), V3(0.8, 0.2, 0)), line(V3(0, 0.23, 0), V3(0.8, 0.23, 0)),
                                    line(V3(0, 0.5, 0), V3(0.8, 0.5, 0)), ignored});
  Sketch after = before;
  const Consolidation c = consolidate_overdrawn(after);
  EXPECT_EQ(c.points, 0u);
  EXPECT_EQ(c.strokes, 0u);
  for (std::size_t k = 0; k < before.strokes.size(); ++k)
    EXPECT_EQ(max_move(before.strokes[k], after.strokes[k]), 0.0) << "stroke " << k;
}

TEST(Consolidate, TheSameSketchGivesTheSameResult) {
  Sketch a = with_frame({line(V3(0, 0, 0), V3(0.8, 0, 0)), line(V3(0.1, 0.004, 0.001), V3(0.7, 0.003, 0))});
  Sketch b = a;
  consolidate_overdrawn(a);
  consolidate_overdrawn(b);
  for (std::size_t k = 0; k < a.strokes.size(); ++k) EXPECT_EQ(a.strokes[k].points, b.strokes[k].points);
}

TEST(Consolidate, ZeroRadiusOrRoundsLeaveTheSketchAndBadOptionsAreRefused) {
  const Sketch before = with_frame({line(V3(0, 0, 0), V3(0.8, 0, 0)), line(V3(0, 0.004, 0), V3(0.8, 0.004, 0))});
  Sketch after = before;
  ConsolidateOptions off;
  off.radius = 0.0;
  EXPECT_EQ(consolidate_overdrawn(after, off).points, 0u);
  off = {};
  off.rounds = 0;
  EXPECT_EQ(consolidate_overdrawn(after, off).points, 0u);
  for (std::size_t k = 0; k < before.strokes.size(); ++k) EXPECT_EQ(max_move(before.strokes[k], after.strokes[k]), 0.0);

  std::string why;
  ConsolidateOptions bad;
  bad.parallel = 1.5;
  EXPECT_FALSE(bad.valid(&why));
  EXPECT_NE(why.find("parallel"), std::string::npos);
  EXPECT_THROW(consolidate_overdrawn(after, bad), Error);
}

}  // namespace
}  // namespace sketchsurf
