// MouseController and OrbitCamera (engine/input/mouse.h, navigation.h): the mouse emulation under
// test, from synthetic cursor, button and wheel events.

#include <gtest/gtest.h>

#include <cmath>

#include "engine/input/mouse.h"
#include "engine/session/session.h"

namespace sketchsurf::input {
namespace {

constexpr int kWidth = 800, kHeight = 600;

/// Feeds every state the controller queued into the session.
void drain(MouseController& mouse, session::SketchSession& s, double now) {
  for (const auto& state : mouse.poll(now)) s.apply(state);
}

/// Drags with the left button from `a` to `b` (pixels) in `steps` moves.
void drag(MouseController& mouse, session::SketchSession& s, Eigen::Vector2d a, Eigen::Vector2d b,
          int steps, double& t, Modifiers mods = {}) {
  mouse.move(a.x(), a.y(), t += 0.01);
  mouse.button(MouseButton::Left, true, mods, t += 0.01);
  for (int i = 1; i <= steps; ++i) {
    const Eigen::Vector2d p = a + (b - a) * (double(i) / steps);
    mouse.move(p.x(), p.y(), t += 0.01);
  }
  mouse.button(MouseButton::Left, false, mods, t += 0.01);
  drain(mouse, s, t);
}

TEST(MouseController, DragOnTheFrontPlaneGivesAStrokeOnItWithTheExpectedLength) {
  MouseController mouse(kWidth, kHeight);  // front view from (0, 0, 3), plane z = 0
  session::SketchSession s;
  double t = 0.0;
  drag(mouse, s, {100, 300}, {700, 300}, 60, t);
  ASSERT_EQ(s.sketch().strokes.size(), 1u);
  const Stroke& stroke = s.sketch().strokes[0];
  EXPECT_GE(stroke.points.size(), 50u);
  for (const auto& p : stroke.points) {
    EXPECT_NEAR(p.z(), 0.0, 1e-6);
    EXPECT_NEAR(p.y(), 0.0, 1e-6);
  }
  // Pixel x -> ndc (2x/w - 1); at distance 3 the half height is 3 tan(17.5 deg), the half width
  // aspect times that: ndc -0.75 .. 0.75 spans 1.5 * (4/3) * 3 tan(17.5 deg).
  const double expected = 1.5 * (4.0 / 3.0) * 3.0 * std::tan(17.5 * M_PI / 180.0);
  EXPECT_NEAR(stroke.length(), expected, 1e-6);
  EXPECT_NEAR(stroke.points.front().x(), -expected / 2, 1e-6);
  EXPECT_NEAR(stroke.points.back().x(), expected / 2, 1e-6);
  // The attributes of a controller stroke: pressure 1 (left button), the view's orientation.
  ASSERT_EQ(stroke.pressures.size(), stroke.points.size());
  ASSERT_EQ(stroke.orientations.size(), stroke.points.size());
  for (float p : stroke.pressures) EXPECT_EQ(p, 1.0f);
  const Pose pose{stroke.points[0], stroke.orientations[0]};
  EXPECT_NEAR(pose.direction().dot(-Eigen::Vector3d::UnitZ()), 1.0, 1e-12);
}

TEST(MouseController, ObliqueViewStrokeLiesOnThePlaneUnderTheCursor) {
  MouseController mouse(kWidth, kHeight);
  mouse.view().look_from(render::View::Iso);
  mouse.view().target = {0.1, 0.2, 0.3};
  mouse.set_drawing_plane({Eigen::Vector3d(0, 0, 1), -0.3});  // z = 0.3
  session::SketchSession s;
  double t = 0.0;
  const Eigen::Vector2d a(150, 420), b(610, 130);
  drag(mouse, s, a, b, 40, t);
  ASSERT_EQ(s.sketch().strokes.size(), 1u);
  const Stroke& stroke = s.sketch().strokes[0];
  const render::Camera camera = mouse.camera();
  for (const auto& p : stroke.points) {
    EXPECT_NEAR(p.z(), 0.3, 1e-6);
    // Back to the window: on the segment dragged along.
    const Eigen::Vector3d px = camera.project(p, kWidth, kHeight);
    const Eigen::Vector2d q(px.x(), px.y());
    const Eigen::Vector2d d = (b - a).normalized();
    const double along = (q - a).dot(d);
    EXPECT_NEAR((q - a - along * d).norm(), 0.0, 1e-6);
  }
  const Eigen::Vector3d pa = camera.project(stroke.points.front(), kWidth, kHeight);
  const Eigen::Vector3d pb = camera.project(stroke.points.back(), kWidth, kHeight);
  EXPECT_NEAR((Eigen::Vector2d(pa.x(), pa.y()) - a).norm(), 0.0, 1e-6);
  EXPECT_NEAR((Eigen::Vector2d(pb.x(), pb.y()) - b).norm(), 0.0, 1e-6);
  // A straight drag is a straight stroke: its length is its chord.
  EXPECT_NEAR(stroke.length(), (stroke.points.back() - stroke.points.front()).norm(), 1e-9);
}

TEST(MouseController, AltLeftDragNavigatesInsteadOfDrawing) {
  MouseController mouse(kWidth, kHeight);
  session::SketchSession s;
  double t = 0.0;
  const double yaw = mouse.view().yaw;
  drag(mouse, s, {400, 300}, {500, 300}, 10, t, Modifiers{false, false, true});
  EXPECT_TRUE(s.sketch().strokes.empty());
  EXPECT_NE(mouse.view().yaw, yaw);
}

TEST(OrbitCamera, OrbitKeepsTheDistancePanFollowsTheCursorZoomApproaches) {
  MouseController mouse(kWidth, kHeight);
  mouse.view().look_from(render::View::Iso);
  double t = 0.0;
  const Eigen::Vector3d target = mouse.view().target;
  // Orbit: middle drag.
  mouse.move(400, 300, t += 0.01);
  mouse.button(MouseButton::Middle, true, {}, t += 0.01);
  EXPECT_TRUE(mouse.current().pressed(Button::Grab));
  mouse.move(480, 260, t += 0.01);
  mouse.button(MouseButton::Middle, false, {}, t += 0.01);
  EXPECT_NEAR((mouse.view().eye() - target).norm(), 3.0, 1e-12);
  EXPECT_EQ(mouse.view().target, target);
  EXPECT_NEAR(mouse.view().yaw, 35.0 * M_PI / 180 - 80 * 0.5 * M_PI / 180, 1e-12);
  // Pan: Shift+middle drag; the target moves with the cursor.
  const render::Camera before = mouse.camera();
  mouse.button(MouseButton::Middle, true, {true, false, false}, t += 0.01);
  mouse.move(430, 340, t += 0.01);
  mouse.button(MouseButton::Middle, false, {}, t += 0.01);
  const Eigen::Vector3d moved = mouse.camera().project(before.target, kWidth, kHeight);
  EXPECT_NEAR(moved.x(), 400 + (430 - 480), 1e-6);
  EXPECT_NEAR(moved.y(), 300 + (340 - 260), 1e-6);
  EXPECT_NEAR((mouse.view().eye() - mouse.view().target).norm(), 3.0, 1e-12);
  // Zoom: the wheel.
  mouse.scroll(2.0, {}, t += 0.01);
  EXPECT_NEAR(mouse.view().distance, 3.0 * 0.81, 1e-12);
  mouse.scroll(-2.0, {}, t += 0.01);
  EXPECT_NEAR(mouse.view().distance, 3.0, 1e-12);
  // Frame: the box fits.
  BoundingBox box;
  box.extend({-2, -1, -1});
  box.extend({4, 3, 1});
  mouse.view().frame(box, double(kWidth) / kHeight);
  for (int c = 0; c < 8; ++c) {
    const Eigen::Vector3d corner(c & 1 ? 4 : -2, c & 2 ? 3 : -1, c & 4 ? 1 : -1);
    const Eigen::Vector3d px = mouse.camera().project(corner, kWidth, kHeight);
    EXPECT_GT(px.x(), 0);
    EXPECT_LT(px.x(), kWidth);
    EXPECT_GT(px.y(), 0);
    EXPECT_LT(px.y(), kHeight);
  }
}

TEST(MouseController, RightDragTurnsTheController) {
  MouseController mouse(kWidth, kHeight);
  double t = 0.0;
  mouse.move(400, 300, t += 0.01);
  EXPECT_NEAR(mouse.current().pose.direction().dot(-Eigen::Vector3d::UnitZ()), 1.0, 1e-12);
  mouse.button(MouseButton::Right, true, {}, t += 0.01);
  mouse.move(700, 300, t += 0.01);  // 300 px at 0.3 degrees per pixel: a quarter turn right
  mouse.button(MouseButton::Right, false, {}, t += 0.01);
  EXPECT_NEAR(mouse.current().pose.direction().dot(Eigen::Vector3d::UnitX()), 1.0, 1e-9);
  EXPECT_FALSE(mouse.current().pressed(Button::Draw));
  mouse.button(MouseButton::Right, true, {}, t += 0.01);
  mouse.move(700, 0, t += 0.01);  // then 90 degrees up
  mouse.button(MouseButton::Right, false, {}, t += 0.01);
  EXPECT_NEAR(mouse.current().pose.direction().dot(Eigen::Vector3d::UnitY()), 1.0, 1e-9);
  // The position still comes from the cursor ray and the plane.
  EXPECT_NEAR(mouse.current().pose.position.z(), 0.0, 1e-12);
}

TEST(MouseController, WheelDepthAndModes) {
  MouseController mouse(kWidth, kHeight);
  double t = 0.0;
  mouse.move(400, 300, t += 0.01);
  EXPECT_NEAR(mouse.current().pose.position.norm(), 0.0, 1e-12);
  // Shift+wheel pushes the plane away from the eye by 2% of the view distance per notch.
  mouse.scroll(1.0, {true, false, false}, t += 0.01);
  EXPECT_NEAR(mouse.current().pose.position.z(), -0.06, 1e-12);
  EXPECT_NEAR(mouse.view().distance, 3.0, 1e-12);
  // Distance mode: a fixed distance from the eye along the ray.
  mouse.set_depth_mode(DepthMode::Distance);
  mouse.set_depth(2.0);
  mouse.move(400, 300, t += 0.01);
  EXPECT_NEAR(mouse.current().pose.position.z(), 1.0, 1e-12);
  mouse.scroll(2.0, {true, false, false}, t += 0.01);
  EXPECT_NEAR(mouse.depth(), 2.0 * 1.21, 1e-12);
  // Snap: the pick function's distance, the plane where it finds nothing.
  mouse.set_depth_mode(DepthMode::Snap);
  mouse.set_pick([](const Eigen::Vector3d&, const Eigen::Vector3d&, double r) -> std::optional<double> {
    EXPECT_GT(r, 0.0);
    return 1.5;
  });
  mouse.move(400, 300, t += 0.01);
  EXPECT_NEAR(mouse.current().pose.position.z(), 1.5, 1e-12);
  mouse.set_pick([](const Eigen::Vector3d&, const Eigen::Vector3d&, double) { return std::optional<double>(); });
  mouse.move(400, 300, t += 0.01);
  EXPECT_NEAR(mouse.current().pose.position.z(), -0.06, 1e-12);
  // A plane seen edge-on: no pose, nothing drawn.
  mouse.set_depth_mode(DepthMode::Plane);
  mouse.set_drawing_plane({Eigen::Vector3d::UnitY(), 0.0});
  mouse.move(400, 300, t += 0.01);
  EXPECT_FALSE(mouse.current().tracked);
  const auto states = mouse.poll(t);
  EXPECT_EQ(states.size(), 7u);
  for (std::size_t i = 1; i < states.size(); ++i) EXPECT_GE(states[i].time_s, states[i - 1].time_s);
  EXPECT_TRUE(mouse.poll(t).empty());
}

TEST(MouseController, SnapsToTheSessionsStrokes) {
  MouseController mouse(kWidth, kHeight);
  session::SketchSession s;
  Stroke stroke;
  stroke.points = {{-0.5, 0.0, 0.4}, {0.5, 0.0, 0.4}};
  s.add_stroke(stroke);
  mouse.set_depth_mode(DepthMode::Snap);
  mouse.set_pick([&s](const Eigen::Vector3d& o, const Eigen::Vector3d& d, double r) { return s.pick(o, d, r); });
  double t = 0.0;
  mouse.move(400, 300, t += 0.01);  // the stroke's point (0.5 .. -0.5 along x) is not under (0, 0)
  mouse.move(400 + 0.5 / (2.6 * std::tan(17.5 * M_PI / 180)) * 300, 300, t += 0.01);
  EXPECT_NEAR(mouse.current().pose.position.z(), 0.4, 1e-9);
}

}  // namespace
}  // namespace sketchsurf::input
