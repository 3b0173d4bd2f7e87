// The drawing aids (engine/session/drawing_plane.h, stroke_aids.h, pattern.h) on strokes with known
// answers, and through the session driven by a ScriptedController replaying a track: the plane
// guide, the plane through three clicks, end snapping, over-sketching, mirror and rotation
// patterns, smoothing, straight lines; one undo step per stroke, whatever the aids did.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "engine/input/scripted.h"
#include "engine/session/actions.h"
#include "engine/session/drawing_plane.h"
#include "engine/session/pattern.h"
#include "engine/session/session.h"
#include "engine/session/stroke_aids.h"
#include "surfacing/error.h"
#include "surfacing/sketch/io/sketch_io.h"
#include "tests/support/cli_run.h"

namespace sketchsurf::session {
namespace {

using input::Button;
using input::ControllerState;
using input::Track;
using input::TrackEvent;

/// A track being written: strokes as controller samples 10 ms apart, and actions.
struct TrackBuilder {
  Track track;
  double t = 0.0;
  void action(const input::TrackAction& a) { track.events.push_back({t += 0.01, std::nullopt, a}); }
  void sample(const Eigen::Vector3d& p, bool draw) {
    ControllerState s;
    s.time_s = (t += 0.01);
    s.pose.position = p;
    s.set(Button::Draw, draw);
    s.trigger = draw ? 1.0f : 0.0f;
    track.events.push_back({s.time_s, s, std::nullopt});
  }
  /// A stroke through `points` (trigger down at the first, up after the last).
  void stroke(const std::vector<Eigen::Vector3d>& points) {
    for (const auto& p : points) sample(p, true);
    sample(points.back(), false);
  }
  /// A click (press and release) at p.
  void click(const Eigen::Vector3d& p) {
    sample(p, true);
    sample(p, false);
  }
};

/// Replays the track into the session through a ScriptedController, as the studio does.
void replay(SketchSession& session, const Track& track) {
  input::ScriptedController controller(track);
  for (double now = 0.0; !controller.finished(); now += 1.0 / 60.0)
    for (const TrackEvent& e : controller.poll_events(now)) {
      if (e.state) session.apply(*e.state);
      if (e.action) apply_action(session, *e.action);
    }
}

std::vector<Eigen::Vector3d> polyline(const std::function<Eigen::Vector3d(double)>& f, int n) {
  std::vector<Eigen::Vector3d> out;
  for (int i = 0; i < n; ++i) out.push_back(f(double(i) / (n - 1)));
  return out;
}

SessionOptions no_autosave() {
  SessionOptions o;
  o.drawing.min_spacing = 0.0;
  return o;
}

TEST(DrawingAids, AStrokeDrawnNearThePlaneLandsOnItAndOneFarAwayStaysFree) {
  SketchSession s(no_autosave());
  TrackBuilder b;
  const Plane plane = plane_through({0, 0, 0.5}, {1, 0, 0.6}, {0, 1, 0.45});  // a tilted plane
  b.action(plane_action(plane));
  b.action(aid_action("plane_guide", 1));
  // Within the band (0.03 of the reference size 1): wobbling up to 0.02 off the plane.
  b.stroke(polyline([&](double u) {
    const Eigen::Vector3d on(u, 0.5 * std::sin(3 * u), 0.0);
    const Eigen::Vector3d p = on - (plane.signed_distance(on)) * plane.normal;
    return Eigen::Vector3d(p + 0.02 * std::sin(40 * u) * plane.normal);
  }, 80));
  // 0.2 away: not the plane's stroke.
  b.stroke(polyline([&](double u) { return Eigen::Vector3d(u, 0, 0.5 + 0.1 * u + 0.2); }, 20));
  replay(s, b.track);
  ASSERT_EQ(s.sketch().strokes.size(), 2u);
  for (const auto& p : s.sketch().strokes[0].points) EXPECT_LT(std::abs(plane.signed_distance(p)), 1e-9);
  for (const auto& p : s.sketch().strokes[1].points) EXPECT_GT(std::abs(plane.signed_distance(p)), 0.1);
}

TEST(DrawingAids, ThreeClicksPlaceThePlaneAndFacingAndAxisPlanesAreRight) {
  SketchSession s(no_autosave());
  TrackBuilder b;
  b.action(tool_action(Tool::PlacePlane));
  b.click({0, 0, 1});
  b.click({1, 0, 2});
  EXPECT_TRUE(s.plane_points().empty());
  b.click({0, 1, 1});
  replay(s, b.track);
  EXPECT_EQ(s.tool(), Tool::Draw);
  EXPECT_TRUE(s.drawing().plane_guide);
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(1, 0, 2), Eigen::Vector3d(0, 1, 1)})
    EXPECT_NEAR(s.drawing().plane.signed_distance(p), 0.0, 1e-12);
  EXPECT_NEAR(std::abs(s.drawing().plane.normal.dot(Eigen::Vector3d(-1, 0, 1).normalized())), 1.0, 1e-12);

  EXPECT_THROW(plane_through({0, 0, 0}, {1, 1, 1}, {2, 2, 2}), Error);
  const Plane y = axis_plane(1, {3, 0.25, -2});
  EXPECT_EQ(y.signed_distance({7, 0.25, 9}), 0.0);
  render::Camera c;
  c.eye = {0, 0, 5};
  c.target = {1, 2, 0};
  const Plane f = plane_facing(c, {1, 2, 0.5});
  EXPECT_NEAR(f.normal.dot((c.eye - c.target).normalized()), 1.0, 1e-12);
  EXPECT_NEAR(f.signed_distance({1, 2, 0.5}), 0.0, 1e-12);
}

TEST(DrawingAids, AnEndWithinTheSnapRadiusMeetsTheOtherStrokeExactly) {
  SketchSession s(no_autosave());
  TrackBuilder b;
  b.action(aid_action("snap", 1));  // radius 0.02
  b.stroke(polyline([](double u) { return Eigen::Vector3d(u, 0, 0); }, 50));          // along x
  // Starts 0.015 above the middle of the first (not at a vertex: x = 0.503), ends 0.3 away.
  b.stroke(polyline([](double u) { return Eigen::Vector3d(0.503, 0.015 + 0.5 * u, 0.3 * u); }, 40));
  // Starts 0.012 from the end (1, 0, 0) of the first: meets that very point.
  b.stroke(polyline([](double u) { return Eigen::Vector3d(1.0 + 0.012, 0.0, 0.5 * u); }, 40));
  // Starts 0.05 away: beyond the radius, unchanged.
  b.stroke(polyline([](double u) { return Eigen::Vector3d(0.25, 0.05 + 0.3 * u, 0.0); }, 20));
  replay(s, b.track);
  const auto& st = s.sketch().strokes;
  ASSERT_EQ(st.size(), 4u);
  EXPECT_LE(distance_to_stroke(st[1].points.front(), st[0]), 1e-15);
  EXPECT_NEAR(st[1].points.front().x(), 0.503, 1e-12);
  EXPECT_EQ(st[1].points.back(), Eigen::Vector3d(0.503, 0.515, 0.3));  // the far end did not move
  EXPECT_EQ(st[2].points.front(), st[0].points.back());                // exactly the corner
  EXPECT_EQ(st[3].points.front(), Eigen::Vector3d(0.25, 0.05, 0.0));
  // One undo step per stroke, the snapped one included.
  EXPECT_EQ(s.undo_name(), "draw");
  ASSERT_TRUE(s.undo());
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(s.sketch().strokes.size(), 2u);

  // With the plane guide on, an end on the plane snaps to where a stroke crosses the plane: the
  // whole stroke stays on it (a slanted stroke's nearest point would be off the plane).
  SketchSession g(no_autosave());
  TrackBuilder gb;
  gb.action(aid_action("snap", 1));
  gb.action(plane_action({Eigen::Vector3d::UnitZ(), 0.0}));
  gb.stroke(polyline([](double u) { return Eigen::Vector3d(0.5 + 0.3 * (u - 0.5), 0.0, u - 0.5); }, 30));
  gb.action(aid_action("plane_guide", 1));
  gb.stroke(polyline([](double u) { return Eigen::Vector3d(0.515 - 0.5 * u, 0.01, 0.02 * u * (1 - u)); }, 30));
  replay(g, gb.track);
  const auto& gs = g.sketch().strokes;
  ASSERT_EQ(gs.size(), 2u);
  for (const auto& p : gs[1].points) EXPECT_LT(std::abs(p.z()), 1e-9);
  EXPECT_LT(distance_to_stroke(gs[1].points.front(), gs[0]), 1e-12);
  EXPECT_NEAR(gs[1].points.front().x(), 0.5, 1e-12);

  // With the mirror on, an end near the mirror plane (and no stroke) goes onto it: the stroke
  // meets its mirror image exactly.
  SketchSession m(no_autosave());
  TrackBuilder mb;
  mb.action(aid_action("snap", 1));
  mb.action(mirror_action({Eigen::Vector3d::UnitX(), 0.0}));
  mb.stroke(polyline([](double u) { return Eigen::Vector3d(0.4 - 0.388 * u, 0.3 * u, 0.1); }, 30));
  replay(m, mb.track);
  ASSERT_EQ(m.sketch().strokes.size(), 2u);
  EXPECT_EQ(m.sketch().strokes[0].points.back().x(), 0.0);
  EXPECT_EQ(m.sketch().strokes[0].points.back(), m.sketch().strokes[1].points.back());

  // A stroke whose end comes back within the radius of its start closes exactly.
  Stroke loop;
  loop.points = polyline([](double u) { return Eigen::Vector3d(std::cos(6.1 * u), std::sin(6.1 * u), 0); }, 60);
  const auto [start, end] = snap_ends(loop, {}, 0.2);
  EXPECT_FALSE(start.snapped);
  EXPECT_TRUE(end.snapped);
  EXPECT_EQ(loop.points.back(), loop.points.front());
}

TEST(DrawingAids, AnOversketchReplacesOnlyTheCoveredPart) {
  SketchSession s(no_autosave());
  TrackBuilder b;
  b.action(aid_action("oversketch", 1));
  const auto line = polyline([](double u) { return Eigen::Vector3d(u, 0, 0); }, 101);
  b.stroke(line);
  // Drawn backwards along x in [0.3, 0.7], its ends 0.005 off the line, a bump of 0.02 between.
  const auto bump = polyline([](double u) {
    const double x = 0.7 - 0.4 * u;
    return Eigen::Vector3d(x, 0.005 + 0.015 * std::sin(M_PI * u), 0.0);
  }, 60);
  b.stroke(bump);
  replay(s, b.track);
  ASSERT_EQ(s.sketch().strokes.size(), 1u);  // corrected, nothing added
  EXPECT_EQ(s.undo_name(), "over-sketch");
  const Stroke& r = s.sketch().strokes[0];
  EXPECT_EQ(r.points.front(), line.front());
  EXPECT_EQ(r.points.back(), line.back());
  std::size_t outside = 0, inside = 0;
  for (const auto& p : r.points) {
    if (p.x() < 0.3 - 1e-9 || p.x() > 0.7 + 1e-9) {
      // Outside the covered part: the old points, bit for bit.
      ++outside;
      EXPECT_EQ(p.y(), 0.0);
      EXPECT_EQ(p.x(), std::round(p.x() * 100.0) / 100.0);
    }
  }
  EXPECT_EQ(outside, 30u + 30u);
  // Between the blends, the new stroke's points exactly.
  for (const auto& q : bump) {
    const double u = (0.7 - q.x()) / 0.4;
    if (u < 0.16 || u > 0.84) continue;
    bool found = false;
    for (const auto& p : r.points) found = found || p == q;
    EXPECT_TRUE(found) << q.transpose();
    ++inside;
  }
  EXPECT_GT(inside, 30u);
  // The blend keeps it continuous: no step larger than the strokes' own spacing.
  for (std::size_t i = 1; i < r.points.size(); ++i) EXPECT_LT((r.points[i] - r.points[i - 1]).norm(), 0.012);
  ASSERT_TRUE(s.undo());
  EXPECT_EQ(s.sketch().strokes[0].points, line);
  ASSERT_TRUE(s.redo());
  EXPECT_EQ(s.sketch().strokes[0].points, r.points);
}

TEST(DrawingAids, AMirroredStrokeIsTheExactReflection) {
  SketchSession s(no_autosave());
  TrackBuilder b;
  const Plane plane{Eigen::Vector3d(1, 1, 0).normalized(), -0.3};
  b.action(mirror_action(plane));
  b.stroke(polyline([](double u) { return Eigen::Vector3d(u, 0.2 * u * u, 0.1 + u); }, 30));
  replay(s, b.track);
  const auto& st = s.sketch().strokes;
  ASSERT_EQ(st.size(), 2u);
  for (std::size_t i = 0; i < st[0].points.size(); ++i) {
    const Eigen::Vector3d& p = st[0].points[i];
    EXPECT_EQ(st[1].points[i], s.sketch().mirror->reflect(p));
    EXPECT_NEAR(plane.signed_distance(st[1].points[i]), -plane.signed_distance(p), 1e-15);
  }
}

TEST(DrawingAids, SixFoldRotationGivesSixStrokesSixtyDegreesApartStoredInTheSketch) {
  SketchSession s(no_autosave());
  TrackBuilder b;
  RotationPattern r;
  r.center = {0.5, 0, 0.5};
  r.axis = {0, 2, 0};  // normalised by the session
  r.count = 6;
  b.action(rotation_action(r));
  b.stroke(polyline([](double u) { return Eigen::Vector3d(1.0, u, 0.5 + 0.1 * u); }, 25));
  replay(s, b.track);
  const auto& st = s.sketch().strokes;
  ASSERT_EQ(st.size(), 6u);
  ASSERT_TRUE(s.sketch().rotation.has_value());
  for (std::size_t k = 0; k < 6; ++k) {
    EXPECT_EQ(st[k].id, std::int64_t(k));
    for (std::size_t i = 0; i < st[0].points.size(); ++i) {
      const Eigen::Vector3d a = st[0].points[i] - r.center, c = st[k].points[i] - r.center;
      EXPECT_NEAR(c.y(), a.y(), 1e-12);  // same height along the axis
      const double angle = std::atan2(a.z() * c.x() - a.x() * c.z(), a.x() * c.x() + a.z() * c.z());
      double want = 60.0 * double(k);
      if (want > 180.0) want -= 360.0;
      EXPECT_NEAR(angle * 180.0 / M_PI, want, 1e-9) << "copy " << k;
      EXPECT_NEAR(std::hypot(c.x(), c.z()), std::hypot(a.x(), a.z()), 1e-12);
    }
  }
  // The pattern is stored in the .json and read back; one undo removes all six.
  const auto dir = testing::scratch_dir("aids_");
  s.save(dir / "r.json");
  const Sketch back = read_sketch(dir / "r.json");
  ASSERT_TRUE(back.rotation.has_value());
  EXPECT_EQ(back.rotation->count, 6);
  EXPECT_EQ(back.rotation->axis, Eigen::Vector3d::UnitY());
  EXPECT_EQ(back.rotation->center, r.center);
  ASSERT_TRUE(s.undo());
  EXPECT_TRUE(s.sketch().strokes.empty());
  ASSERT_TRUE(s.undo());  // the pattern itself
  EXPECT_FALSE(s.sketch().rotation.has_value());
  // Mirror and rotation together: 12 copies, the mirror images the reflections of the rotations.
  Stroke one;
  one.points = {{1, 0, 0}, {1, 1, 0}};
  const auto images = pattern_images(one, Plane{}, checked_rotation(r));
  ASSERT_EQ(images.size(), 11u);
  EXPECT_EQ(images[5].points[1], Plane{}.reflect(one.points[1]));
  EXPECT_EQ(images[6].points[0], Plane{}.reflect(images[0].points[0]));
}

TEST(DrawingAids, SmoothingRemovesNoiseKeepsEndsAndLinesAndStraightLineMode) {
  // A zig-zag of amplitude 0.01 about the x axis: each round lowers it, the ends stay.
  Stroke z;
  z.points = polyline([](double u) { return Eigen::Vector3d(u, 0, 0); }, 41);
  for (std::size_t i = 1; i + 1 < z.points.size(); ++i) z.points[i].y() = (i % 2 ? 0.01 : -0.01);
  const auto deviation = [](const Stroke& st) {
    double m = 0.0;
    for (const auto& p : st.points) m = std::max(m, std::abs(p.y()));
    return m;
  };
  Stroke once = z, five = z;
  smooth_stroke(once, 1);
  smooth_stroke(five, 5);
  EXPECT_LT(deviation(once), 0.01);
  EXPECT_LT(deviation(five), 0.1 * 0.01);
  EXPECT_EQ(five.points.front(), z.points.front());
  EXPECT_EQ(five.points.back(), z.points.back());
  // Evenly spaced points on a line are a fixed point of the smoothing.
  Stroke line;
  line.points = polyline([](double u) { return Eigen::Vector3d(u, 2 * u, -u); }, 20);
  Stroke smoothed = line;
  smooth_stroke(smoothed, 10);
  for (std::size_t i = 0; i < line.points.size(); ++i)
    EXPECT_NEAR((smoothed.points[i] - line.points[i]).norm(), 0.0, 1e-14);

  // Through the session: smoothing 5 rounds, then straight-line mode.
  SketchSession s(no_autosave());
  TrackBuilder b;
  b.action(aid_action("smoothing", 5));
  b.stroke(z.points);
  b.action(aid_action("smoothing", 0));
  b.action(aid_action("straight", 1));
  const auto wobbly = polyline([](double u) { return Eigen::Vector3d(u, 0.3 * std::sin(7 * u), 1.0 + u); }, 30);
  b.stroke(wobbly);
  replay(s, b.track);
  ASSERT_EQ(s.sketch().strokes.size(), 2u);
  EXPECT_EQ(s.sketch().strokes[0].points, five.points);
  const Stroke& st = s.sketch().strokes[1];
  EXPECT_EQ(st.points.front(), wobbly.front());
  EXPECT_EQ(st.points.back(), wobbly.back());
  for (const auto& p : st.points) {
    const Eigen::Vector3d d = (wobbly.back() - wobbly.front()).normalized();
    EXPECT_LT(((p - wobbly.front()) - (p - wobbly.front()).dot(d) * d).norm(), 1e-12);
  }
  ASSERT_TRUE(s.undo());
  ASSERT_TRUE(s.undo());
  EXPECT_TRUE(s.sketch().strokes.empty());
}

TEST(DrawingAids, BadAidActionsAreUsageErrors) {
  SketchSession s(no_autosave());
  EXPECT_THROW(apply_action(s, aid_action("glue", 1)), Error);
  EXPECT_THROW(apply_action(s, aid_action("smoothing", -1)), Error);
  EXPECT_THROW(apply_action(s, aid_action("smoothing", 1.5)), Error);
  EXPECT_THROW(apply_action(s, plane_action({Eigen::Vector3d::Zero(), 0.0})), Error);
  RotationPattern r;
  r.count = 1;
  EXPECT_THROW(apply_action(s, rotation_action(r)), Error);
  r.count = 4;
  r.axis = Eigen::Vector3d::Zero();
  EXPECT_THROW(apply_action(s, rotation_action(r)), Error);
  EXPECT_FALSE(s.sketch().rotation.has_value());
}

}  // namespace
}  // namespace sketchsurf::session
