#include "engine/input/xr_controller.h"

#include <cstring>
#include <utility>

#include "engine/vk/xr_check.h"

namespace sketchsurf::input {

namespace {

XrPath to_path(XrInstance instance, const std::string& text) {
  XrPath path = XR_NULL_PATH;
  XR_CHECK(xrStringToPath(instance, text.c_str(), &path));
  return path;
}

/// One controller's bindings: (action, input path below /user/hand/<hand>).
struct Profile {
  const char* path;
  std::vector<std::pair<XrAction, std::string>> bindings;
};

}  // namespace

XrAction XrController::make_action(const char* name, const char* label, XrActionType type) {
  XrActionCreateInfo info{XR_TYPE_ACTION_CREATE_INFO};
  std::strncpy(info.actionName, name, XR_MAX_ACTION_NAME_SIZE - 1);
  std::strncpy(info.localizedActionName, label, XR_MAX_LOCALIZED_ACTION_NAME_SIZE - 1);
  info.actionType = type;
  XrAction action = XR_NULL_HANDLE;
  XR_CHECK(xrCreateAction(set_, &info, &action));
  return action;
}

XrController::XrController(XrInstance instance, XrSession session, const XrControllerOptions& options)
    : instance_(instance), session_(session), options_(options) {
  std::string why;
  if (!options.mapping.valid(&why)) throw Error::usage("controller mapping: " + why);
  const std::string hand = options.hand == Hand::Right ? "/user/hand/right" : "/user/hand/left";
  hand_ = to_path(instance, hand);
  XrActionSetCreateInfo set_info{XR_TYPE_ACTION_SET_CREATE_INFO};
  std::strncpy(set_info.actionSetName, "sketch", XR_MAX_ACTION_SET_NAME_SIZE - 1);
  std::strncpy(set_info.localizedActionSetName, "Sketch", XR_MAX_LOCALIZED_ACTION_SET_NAME_SIZE - 1);
  XR_CHECK(xrCreateActionSet(instance, &set_info, &set_));
  try {
    aim_ = make_action("aim", "Aim pose", XR_ACTION_TYPE_POSE_INPUT);
    grip_ = make_action("grip", "Grip pose", XR_ACTION_TYPE_POSE_INPUT);
    trigger_ = make_action("draw", "Draw (trigger)", XR_ACTION_TYPE_FLOAT_INPUT);
    squeeze_ = make_action("grab", "Grab", XR_ACTION_TYPE_BOOLEAN_INPUT);
    undo_ = make_action("undo", "Undo", XR_ACTION_TYPE_BOOLEAN_INPUT);
    redo_ = make_action("redo", "Redo", XR_ACTION_TYPE_BOOLEAN_INPUT);
    menu_ = make_action("menu", "Menu", XR_ACTION_TYPE_BOOLEAN_INPUT);
    pad_click_ =
        make_action("pad_click", "Trackpad click (undo left, redo right)", XR_ACTION_TYPE_BOOLEAN_INPUT);
    pad_x_ = make_action("pad_x", "Trackpad x", XR_ACTION_TYPE_FLOAT_INPUT);
    haptic_ = make_action("stroke_tick", "Stroke start tick", XR_ACTION_TYPE_VIBRATION_OUTPUT);

    const bool right = options.hand == Hand::Right;
    const std::vector<Profile> profiles = {
        {"/interaction_profiles/khr/simple_controller",
         {{aim_, "/input/aim/pose"},
          {grip_, "/input/grip/pose"},
          {trigger_, "/input/select/click"},
          {menu_, "/input/menu/click"},
          {haptic_, "/output/haptic"}}},
        {"/interaction_profiles/oculus/touch_controller",
         {{aim_, "/input/aim/pose"},
          {grip_, "/input/grip/pose"},
          {trigger_, "/input/trigger/value"},
          {squeeze_, "/input/squeeze/value"},
          {undo_, right ? "/input/a/click" : "/input/x/click"},
          {redo_, right ? "/input/b/click" : "/input/y/click"},
          {menu_, "/input/thumbstick/click"},
          {haptic_, "/output/haptic"}}},
        {"/interaction_profiles/valve/index_controller",
         {{aim_, "/input/aim/pose"},
          {grip_, "/input/grip/pose"},
          {trigger_, "/input/trigger/value"},
          {squeeze_, "/input/squeeze/value"},
          {undo_, "/input/a/click"},
          {redo_, "/input/b/click"},
          {menu_, "/input/thumbstick/click"},
          {haptic_, "/output/haptic"}}},
        {"/interaction_profiles/htc/vive_controller",
         {{aim_, "/input/aim/pose"},
          {grip_, "/input/grip/pose"},
          {trigger_, "/input/trigger/value"},
          {squeeze_, "/input/squeeze/click"},
          {menu_, "/input/menu/click"},
          {pad_click_, "/input/trackpad/click"},
          {pad_x_, "/input/trackpad/x"},
          {haptic_, "/output/haptic"}}},
    };
    for (const Profile& p : profiles) {
      std::vector<XrActionSuggestedBinding> suggested;
      for (const auto& [action, input] : p.bindings)
        suggested.push_back({action, to_path(instance, hand + input)});
      XrInteractionProfileSuggestedBinding info{XR_TYPE_INTERACTION_PROFILE_SUGGESTED_BINDING};
      info.interactionProfile = to_path(instance, p.path);
      info.countSuggestedBindings = std::uint32_t(suggested.size());
      info.suggestedBindings = suggested.data();
      XR_CHECK(xrSuggestInteractionProfileBindings(instance, &info));
    }
    XrSessionActionSetsAttachInfo attach{XR_TYPE_SESSION_ACTION_SETS_ATTACH_INFO};
    attach.countActionSets = 1;
    attach.actionSets = &set_;
    XR_CHECK(xrAttachSessionActionSets(session, &attach));
    for (auto [action, space] : {std::pair{aim_, &aim_space_}, std::pair{grip_, &grip_space_}}) {
      XrActionSpaceCreateInfo info{XR_TYPE_ACTION_SPACE_CREATE_INFO};
      info.action = action;
      info.poseInActionSpace.orientation.w = 1.0f;
      XR_CHECK(xrCreateActionSpace(session, &info, space));
    }
  } catch (...) {
    if (aim_space_ != XR_NULL_HANDLE) xrDestroySpace(aim_space_);
    xrDestroyActionSet(set_);
    throw;
  }
  state_.tracked = false;
}

XrController::~XrController() {
  if (grip_space_ != XR_NULL_HANDLE) xrDestroySpace(grip_space_);
  if (aim_space_ != XR_NULL_HANDLE) xrDestroySpace(aim_space_);
  xrDestroyActionSet(set_);  // destroys its actions
}

void XrController::sync(XrSpace base, XrTime display_time, double time_s) {
  XrActiveActionSet active{set_, XR_NULL_PATH};
  XrActionsSyncInfo sync_info{XR_TYPE_ACTIONS_SYNC_INFO};
  sync_info.countActiveActionSets = 1;
  sync_info.activeActionSets = &active;
  XR_CHECK(xrSyncActions(session_, &sync_info));  // XR_SESSION_NOT_FOCUSED: every action inactive

  const auto boolean = [&](XrAction action) {
    XrActionStateGetInfo get{XR_TYPE_ACTION_STATE_GET_INFO};
    get.action = action;
    XrActionStateBoolean s{XR_TYPE_ACTION_STATE_BOOLEAN};
    XR_CHECK(xrGetActionStateBoolean(session_, &get, &s));
    return s.isActive && s.currentState;
  };
  const auto value = [&](XrAction action) {
    XrActionStateGetInfo get{XR_TYPE_ACTION_STATE_GET_INFO};
    get.action = action;
    XrActionStateFloat s{XR_TYPE_ACTION_STATE_FLOAT};
    XR_CHECK(xrGetActionStateFloat(session_, &get, &s));
    return s.isActive ? s.currentState : 0.0f;
  };
  const auto locate = [&](XrAction action, XrSpace space, XrPosef* pose) {
    XrActionStateGetInfo get{XR_TYPE_ACTION_STATE_GET_INFO};
    get.action = action;
    XrActionStatePose s{XR_TYPE_ACTION_STATE_POSE};
    XR_CHECK(xrGetActionStatePose(session_, &get, &s));
    if (!s.isActive) return false;
    XrSpaceLocation location{XR_TYPE_SPACE_LOCATION};
    XR_CHECK(xrLocateSpace(space, base, display_time, &location));
    const XrSpaceLocationFlags needed =
        XR_SPACE_LOCATION_POSITION_VALID_BIT | XR_SPACE_LOCATION_ORIENTATION_VALID_BIT;
    *pose = location.pose;
    return (location.locationFlags & needed) == needed;
  };
  XrControllerSample sample;
  sample.time_s = time_s;
  sample.aim_valid = locate(aim_, aim_space_, &sample.aim);
  sample.grip_valid = locate(grip_, grip_space_, &sample.grip);
  sample.trigger = value(trigger_);
  sample.squeeze = boolean(squeeze_);
  sample.undo = boolean(undo_);
  sample.redo = boolean(redo_);
  sample.menu = boolean(menu_);
  sample.pad_click = boolean(pad_click_);
  sample.pad_x = value(pad_x_);
  const ControllerState next = map_controller(sample, state_, options_.mapping);
  if (next.pressed(Button::Draw) && !state_.pressed(Button::Draw)) {
    XrHapticVibration tick{XR_TYPE_HAPTIC_VIBRATION};
    tick.amplitude = options_.haptic_amplitude;
    tick.duration = options_.haptic_duration;
    tick.frequency = XR_FREQUENCY_UNSPECIFIED;
    XrHapticActionInfo info{XR_TYPE_HAPTIC_ACTION_INFO};
    info.action = haptic_;
    XR_CHECK(xrApplyHapticFeedback(session_, &info, reinterpret_cast<const XrHapticBaseHeader*>(&tick)));
    ++ticks_;
  }
  state_ = next;
  queue_.push_back(next);
}

std::vector<ControllerState> XrController::poll(double now_s) {
  std::vector<ControllerState> out;
  std::vector<ControllerState> kept;
  for (const auto& s : queue_) (s.time_s <= now_s ? out : kept).push_back(s);
  queue_ = std::move(kept);
  return out;
}

std::string XrController::profile() const {
  XrInteractionProfileState state{XR_TYPE_INTERACTION_PROFILE_STATE};
  if (XR_FAILED(xrGetCurrentInteractionProfile(session_, hand_, &state)) ||
      state.interactionProfile == XR_NULL_PATH)
    return "";
  char text[XR_MAX_PATH_LENGTH];
  std::uint32_t length = 0;
  if (XR_FAILED(xrPathToString(instance_, state.interactionProfile, sizeof text, &length, text))) return "";
  return text;
}

}  // namespace sketchsurf::input
