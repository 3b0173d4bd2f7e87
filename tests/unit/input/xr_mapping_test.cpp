// The OpenXR pose/action mapping (engine/input/xr_mapping.h) on synthetic values.

#include <gtest/gtest.h>

#include <cmath>

#include "engine/input/xr_mapping.h"
#include "engine/session/session.h"

namespace sketchsurf::input {
namespace {

XrPosef pose(Eigen::Vector3d p, const Eigen::Quaterniond& q) {
  XrPosef out;
  out.position = {float(p.x()), float(p.y()), float(p.z())};
  out.orientation = {float(q.x()), float(q.y()), float(q.z()), float(q.w())};
  return out;
}

XrControllerSample aimed(const Eigen::Vector3d& p, const Eigen::Quaterniond& q, float trigger = 0.0f) {
  XrControllerSample s;
  s.aim = pose(p, q);
  s.aim_valid = true;
  s.trigger = trigger;
  return s;
}

TEST(XrMapping, QuaternionComponentsAreReorderedFromXyzw) {
  // 90 degrees about +y, as OpenXR writes it: (x, y, z, w) = (0, sin 45, 0, cos 45).
  const float h = float(std::sqrt(0.5));
  const Eigen::Quaterniond q = to_quaternion({0.0f, h, 0.0f, h});
  const Eigen::Quaterniond expected(Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitY()));
  EXPECT_LT(q.angularDistance(expected), 1e-6);
  // The rotation turns the pointing direction -z towards -x (right-handed, +y up).
  Pose p;
  p.orientation = q;
  EXPECT_LT((p.direction() - Eigen::Vector3d(-1, 0, 0)).norm(), 1e-6);
}

TEST(XrMapping, QuaternionIsNormalisedAndZeroIsIdentity) {
  const Eigen::Quaterniond q = to_quaternion({0.0f, 0.0f, 2.0f, 0.0f});  // 180 deg about z, scaled
  EXPECT_NEAR(q.norm(), 1.0, 1e-12);
  EXPECT_LT((q * Eigen::Vector3d::UnitX() - Eigen::Vector3d(-1, 0, 0)).norm(), 1e-12);
  EXPECT_TRUE(to_quaternion({0, 0, 0, 0}).isApprox(Eigen::Quaterniond::Identity()));
}

TEST(XrMapping, AxesAreKeptAndScaleAndOffsetApplied) {
  // OpenXR and the sketch are both right-handed, +y up, -z forward: no axis swap.
  const Eigen::Quaterniond q(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  XrMappingOptions options;
  options.scale = 2.0;
  options.offset = {10, 20, 30};
  const ControllerState s = map_controller(aimed({0.25, 1.5, -0.75}, q), {}, options);
  EXPECT_TRUE(s.tracked);
  EXPECT_LT((s.pose.position - Eigen::Vector3d(10.5, 23.0, 28.5)).norm(), 1e-6);
  EXPECT_LT(s.pose.orientation.angularDistance(q), 1e-6);
  // Rotation matrix columns are the controller's right, up and back axes in the sketch.
  const Eigen::Matrix3d r = s.pose.orientation.toRotationMatrix();
  EXPECT_LT((r - q.toRotationMatrix()).norm(), 1e-6);
}

TEST(XrMapping, GripStandsInForAimAndLostTrackingKeepsThePose) {
  XrControllerSample s;
  s.grip = pose({1, 2, 3}, Eigen::Quaterniond::Identity());
  s.grip_valid = true;
  const ControllerState a = map_controller(s, {}, {});
  EXPECT_TRUE(a.tracked);
  EXPECT_EQ(a.pose.position, Eigen::Vector3d(1, 2, 3));
  s.grip_valid = false;
  const ControllerState b = map_controller(s, a, {});
  EXPECT_FALSE(b.tracked);
  EXPECT_EQ(b.pose.position, a.pose.position);
}

TEST(XrMapping, TriggerThresholdHasHysteresis) {
  const XrMappingOptions o;  // press 0.5, release 0.4
  ControllerState s = map_controller(aimed({0, 0, 0}, Eigen::Quaterniond::Identity(), 0.45f), {}, o);
  EXPECT_FALSE(s.pressed(Button::Draw)) << "below press, from rest";
  EXPECT_FLOAT_EQ(s.trigger, 0.45f);
  s = map_controller(aimed({0, 0, 0}, Eigen::Quaterniond::Identity(), 0.5f), s, o);
  EXPECT_TRUE(s.pressed(Button::Draw)) << "at press";
  s = map_controller(aimed({0, 0, 0}, Eigen::Quaterniond::Identity(), 0.41f), s, o);
  EXPECT_TRUE(s.pressed(Button::Draw)) << "held, above release";
  EXPECT_FLOAT_EQ(s.trigger, 0.41f) << "pressure follows the trigger";
  s = map_controller(aimed({0, 0, 0}, Eigen::Quaterniond::Identity(), 0.39f), s, o);
  EXPECT_FALSE(s.pressed(Button::Draw)) << "below release";
  s = map_controller(aimed({0, 0, 0}, Eigen::Quaterniond::Identity(), 1.7f), s, o);
  EXPECT_FLOAT_EQ(s.trigger, 1.0f) << "clamped";
  s = map_controller(aimed({0, 0, 0}, Eigen::Quaterniond::Identity(), NAN), s, o);
  EXPECT_FALSE(s.pressed(Button::Draw));
  EXPECT_EQ(s.trigger, 0.0f);
}

TEST(XrMapping, ButtonsAndTrackpadHalves) {
  XrControllerSample s = aimed({0, 0, 0}, Eigen::Quaterniond::Identity());
  s.squeeze = true;
  s.menu = true;
  ControllerState c = map_controller(s, {}, {});
  EXPECT_TRUE(c.pressed(Button::Grab));
  EXPECT_TRUE(c.pressed(Button::Menu));
  EXPECT_FALSE(c.pressed(Button::Undo));
  s = aimed({0, 0, 0}, Eigen::Quaterniond::Identity());
  s.pad_click = true;
  s.pad_x = -0.8f;
  c = map_controller(s, c, {});
  EXPECT_TRUE(c.pressed(Button::Undo));
  EXPECT_FALSE(c.pressed(Button::Redo));
  EXPECT_FALSE(c.pressed(Button::Grab)) << "released";
  s.pad_x = 0.1f;  // the dead zone
  c = map_controller(s, c, {});
  EXPECT_FALSE(c.pressed(Button::Undo) || c.pressed(Button::Redo));
  s.pad_x = 0.9f;
  c = map_controller(s, c, {});
  EXPECT_TRUE(c.pressed(Button::Redo));
  s.pad_click = false;
  s.undo = true;
  c = map_controller(s, c, {});
  EXPECT_TRUE(c.pressed(Button::Undo));
  EXPECT_FALSE(c.pressed(Button::Redo));
}

TEST(XrMapping, AHeldUndoButtonUndoesOnceAndAStrokeIsDrawnWhileTheTriggerIsDown) {
  // The edges the session acts on: a stroke from trigger press to release; A held over many
  // frames undoes one edit.
  session::SketchSession session;
  ControllerState last;
  const auto feed = [&](XrControllerSample s) {
    last = map_controller(s, last, {});
    session.apply(last);
  };
  for (int i = 0; i < 2; ++i) {
    for (int k = 0; k <= 5; ++k) {
      XrControllerSample s =
          aimed({0.1 * k, 0.1 * i, 0}, Eigen::Quaterniond::Identity(), k < 5 ? 0.9f : 0.0f);
      s.time_s = 0.1 * (6 * i + k);
      feed(s);
    }
  }
  ASSERT_EQ(session.sketch().strokes.size(), 2u);
  EXPECT_EQ(session.sketch().strokes[0].points.size(), 6u);  // 5 held samples + the release point
  for (int k = 0; k < 4; ++k) {
    XrControllerSample s = aimed({0, 0, 0}, Eigen::Quaterniond::Identity());
    s.undo = true;
    s.time_s = 2.0 + 0.1 * k;
    feed(s);
  }
  EXPECT_EQ(session.sketch().strokes.size(), 1u);
}

TEST(XrMapping, OptionsAreValidated) {
  std::string why;
  EXPECT_TRUE(XrMappingOptions{}.valid(&why));
  XrMappingOptions o;
  o.release = 0.6f;
  EXPECT_FALSE(o.valid(&why));
  EXPECT_NE(why.find("release"), std::string::npos);
  o = {};
  o.scale = 0.0;
  EXPECT_FALSE(o.valid(&why));
  EXPECT_NE(why.find("scale"), std::string::npos);
}

}  // namespace
}  // namespace sketchsurf::input
