#pragma once
// From an OpenXR controller to the studio's ControllerState: the poses and action states that
// XrController (xr_controller.h) reads after xrSyncActions, as plain values, so that the mapping
// is a function tested without a runtime or a session.
//
// Axes: OpenXR's reference spaces are right-handed, +y up, -z forward, in metres; sketches are
// right-handed and +y up too, so a pose maps by a uniform scale and an offset, no axis swap. The
// aim pose's -z is the pointing ray (Pose's convention): it gives the controller's pose; the grip
// pose stands in while the aim pose is not tracked.

#include <openxr/openxr.h>

#include <string>

#include "engine/input/controller.h"

namespace sketchsurf::input {

/// One controller as the runtime reports it for one frame.
struct XrControllerSample {
  double time_s = 0.0;                   ///< seconds since the session began
  XrPosef aim{{0, 0, 0, 1}, {0, 0, 0}};  ///< aim pose in the reference space
  bool aim_valid = false;  ///< position and orientation of `aim` are valid (tracked or inferred)
  XrPosef grip{{0, 0, 0, 1}, {0, 0, 0}};  ///< grip pose in the reference space
  bool grip_valid = false;                ///< likewise for `grip`
  float trigger = 0.0f;                   ///< the trigger's value in [0, 1] (a click reads as 0 or 1)
  bool squeeze = false;                   ///< grip button or squeeze past its click: Grab
  bool undo = false;                      ///< A (Touch, Index)
  bool redo = false;                      ///< B (Touch, Index)
  bool menu = false;                      ///< menu button
  bool pad_click = false;                 ///< trackpad pressed (Vive): left half undo, right half redo
  float pad_x = 0.0f;                     ///< trackpad x in [-1, 1] (Vive), right positive
};

/// How the reference space maps to the sketch and when the trigger counts as pressed.
struct XrMappingOptions {
  double scale = 1.0;                                ///< sketch units per metre, > 0
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  ///< sketch position of the space's origin
  float press = 0.5f;                                ///< trigger value at which Draw goes down, in (0, 1]
  float release = 0.4f;        ///< value below which a held Draw comes up, in [0, press]: the gap keeps
                               ///< a trigger resting near one threshold from breaking a stroke
  float pad_dead_zone = 0.2f;  ///< |pad_x| below this: a trackpad click is neither undo nor redo

  /// False (with the reason in `why`) when a value is out of its range or not finite.
  bool valid(std::string* why) const;
};

/// OpenXR's (x, y, z, w) quaternion as Eigen's, normalised (a runtime's is unit only to float
/// precision); the identity for a zero quaternion.
Eigen::Quaterniond to_quaternion(const XrQuaternionf& q);
/// An OpenXR pose (reference space, metres) as a Pose in sketch units.
Pose to_pose(const XrPosef& pose, const XrMappingOptions& options);

/// The ControllerState of `sample`, given the previous state (for the trigger's hysteresis and to
/// keep the last pose while tracking is lost). Draw: the trigger at or above `press`, or held and
/// not below `release`; pressure is the trigger value. Undo and redo are held as long as their
/// buttons (the session acts on the press edge).
ControllerState map_controller(const XrControllerSample& sample, const ControllerState& previous,
                               const XrMappingOptions& options);

}  // namespace sketchsurf::input
