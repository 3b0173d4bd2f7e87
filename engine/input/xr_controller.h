#pragma once
// XrController: an OpenXR motion controller as a Controller6DoF. One action set ("sketch") with
// the aim and grip poses, the trigger, squeeze, undo, redo, menu, the Vive trackpad and the
// haptic output, bound for the Khronos simple controller, Oculus Touch, Valve Index and HTC Vive
// (the README's "Headset" lists the buttons). Per frame, sync() reads the actions, locates the
// poses at the frame's display time and maps them (xr_mapping.h); a haptic tick marks the start
// of every stroke.

#include <openxr/openxr.h>

#include <string>
#include <vector>

#include "engine/input/controller.h"
#include "engine/input/xr_mapping.h"

namespace sketchsurf::input {

enum class Hand { Left, Right };

struct XrControllerOptions {
  Hand hand = Hand::Right;                  ///< the drawing hand
  XrMappingOptions mapping;                 ///< reference space to sketch, trigger thresholds
  float haptic_amplitude = 0.5f;            ///< of the tick on stroke start, in [0, 1]
  XrDuration haptic_duration = 20'000'000;  ///< nanoseconds
};

class XrController : public Controller6DoF {
 public:
  /// Creates the action set, suggests the bindings of the four controllers, attaches the set to
  /// `session` and creates the pose spaces. Throws XrError, Error (Usage) for invalid options.
  XrController(XrInstance instance, XrSession session, const XrControllerOptions& options = {});
  ~XrController() override;
  XrController(const XrController&) = delete;
  XrController& operator=(const XrController&) = delete;

  /// Once per frame while the session runs: syncs the actions, reads them, locates the poses in
  /// `base` at `display_time`, queues the ControllerState (time `time_s`) and sends the haptic
  /// tick when Draw goes down. Inactive actions (the session not focused) read as released and
  /// untracked.
  void sync(XrSpace base, XrTime display_time, double time_s);

  std::vector<ControllerState> poll(double now_s) override;
  ControllerState current() const override { return state_; }

  /// The drawing hand's interaction profile ("/interaction_profiles/valve/index_controller"),
  /// empty until the runtime binds one.
  std::string profile() const;
  /// Haptic ticks sent so far.
  std::size_t haptic_ticks() const { return ticks_; }

 private:
  XrAction make_action(const char* name, const char* label, XrActionType type);

  XrInstance instance_;
  XrSession session_;
  XrControllerOptions options_;
  XrPath hand_ = XR_NULL_PATH;
  XrActionSet set_ = XR_NULL_HANDLE;
  XrAction aim_ = XR_NULL_HANDLE, grip_ = XR_NULL_HANDLE, trigger_ = XR_NULL_HANDLE,
           squeeze_ = XR_NULL_HANDLE, undo_ = XR_NULL_HANDLE, redo_ = XR_NULL_HANDLE, menu_ = XR_NULL_HANDLE,
           pad_click_ = XR_NULL_HANDLE, pad_x_ = XR_NULL_HANDLE, haptic_ = XR_NULL_HANDLE;
  XrSpace aim_space_ = XR_NULL_HANDLE, grip_space_ = XR_NULL_HANDLE;
  ControllerState state_;
  std::vector<ControllerState> queue_;
  std::size_t ticks_ = 0;
};

}  // namespace sketchsurf::input
