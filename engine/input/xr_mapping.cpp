#include "engine/input/xr_mapping.h"

#include <algorithm>
#include <cmath>

namespace sketchsurf::input {

bool XrMappingOptions::valid(std::string* why) const {
  const auto fail = [&](const std::string& text) {
    if (why) *why = text;
    return false;
  };
  if (!(std::isfinite(scale) && scale > 0.0)) return fail("scale must be a positive number");
  if (!offset.allFinite()) return fail("offset must be finite");
  if (!(press > 0.0f && press <= 1.0f)) return fail("press must be in (0, 1]");
  if (!(release >= 0.0f && release <= press)) return fail("release must be in [0, press]");
  if (!(pad_dead_zone >= 0.0f && pad_dead_zone < 1.0f)) return fail("pad_dead_zone must be in [0, 1)");
  return true;
}

Eigen::Quaterniond to_quaternion(const XrQuaternionf& q) {
  Eigen::Quaterniond out(q.w, q.x, q.y, q.z);
  const double n = out.norm();
  if (!(n > 0.0) || !std::isfinite(n)) return Eigen::Quaterniond::Identity();
  out.coeffs() /= n;
  return out;
}

Pose to_pose(const XrPosef& pose, const XrMappingOptions& options) {
  Pose out;
  out.position =
      options.offset + options.scale * Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  out.orientation = to_quaternion(pose.orientation);
  return out;
}

ControllerState map_controller(const XrControllerSample& sample, const ControllerState& previous,
                               const XrMappingOptions& options) {
  ControllerState state;
  state.time_s = std::max(sample.time_s, previous.time_s);
  state.tracked = sample.aim_valid || sample.grip_valid;
  state.pose = sample.aim_valid    ? to_pose(sample.aim, options)
               : sample.grip_valid ? to_pose(sample.grip, options)
                                   : previous.pose;
  const float trigger = std::isfinite(sample.trigger) ? std::clamp(sample.trigger, 0.0f, 1.0f) : 0.0f;
  state.trigger = trigger;
  const bool held = previous.pressed(Button::Draw);
  state.set(Button::Draw, trigger >= options.press || (held && trigger >= options.release));
  state.set(Button::Grab, sample.squeeze);
  const bool pad = sample.pad_click && std::isfinite(sample.pad_x);
  state.set(Button::Undo, sample.undo || (pad && sample.pad_x <= -options.pad_dead_zone));
  state.set(Button::Redo, sample.redo || (pad && sample.pad_x >= options.pad_dead_zone));
  state.set(Button::Menu, sample.menu);
  return state;
}

}  // namespace sketchsurf::input
