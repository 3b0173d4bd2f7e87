#pragma once
// Controller6DoF: what every input device gives the studio, per frame: a pose (position and
// orientation, world space, sketch units), an analog trigger (0..1, the stroke's pressure),
// buttons and a timestamp. The mouse (mouse.h), a recorded track (scripted.h) and, later, an
// OpenXR controller implement it; the session (engine/session) consumes it and knows none of them.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace sketchsurf::input {

/// The buttons of a controller, as bits of ControllerState::buttons.
enum class Button : std::uint32_t {
  Draw = 1u << 0,  ///< the trigger's click: draws, or applies the active tool, while held
  Grab = 1u << 1,  ///< grab / navigate: moves the view while held (the session ignores it)
  Undo = 1u << 2,  ///< undoes the last edit when pressed
  Redo = 1u << 3,  ///< redoes the last undone edit when pressed
  Menu = 1u << 4,  ///< shows or hides the panel when pressed (the session ignores it)
};

/// Every button, in bit order.
const std::vector<Button>& all_buttons();
/// "draw", "grab", "undo", "redo", "menu".
std::string_view button_name(Button button);
/// The button named `name` (as button_name() spells it); empty when unknown.
std::optional<Button> parse_button(std::string_view name);

/// Where a controller is and where it points: the controller's local -z axis is its pointing
/// direction, +y its up, +x its right (OpenXR's grip/aim convention).
struct Pose {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();                ///< world, sketch units
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();   ///< local -> world, unit

  /// The pointing direction (orientation applied to -z), unit.
  Eigen::Vector3d direction() const { return orientation * -Eigen::Vector3d::UnitZ(); }
};

/// One sample of a controller.
struct ControllerState {
  double time_s = 0.0;        ///< seconds since the controller started, never decreasing
  Pose pose;                  ///< meaningful only when `tracked`
  float trigger = 0.0f;       ///< analog trigger in [0, 1]; becomes the stroke's pressure
  std::uint32_t buttons = 0;  ///< Button bits held down
  bool tracked = true;        ///< false when the pose is unknown (the mouse ray misses the
                              ///< drawing plane, a headset lost tracking): no point is drawn

  bool pressed(Button b) const { return (buttons & static_cast<std::uint32_t>(b)) != 0; }
  void set(Button b, bool down) {
    if (down)
      buttons |= static_cast<std::uint32_t>(b);
    else
      buttons &= ~static_cast<std::uint32_t>(b);
  }
};

/// The interface of every input device. One instance per device; polled once per frame.
class Controller6DoF {
 public:
  virtual ~Controller6DoF() = default;

  /// The samples since the previous call up to time `now_s` (seconds, the caller's clock), oldest
  /// first; empty when nothing changed. A device that samples faster than the frame rate (the
  /// mouse's events, a recorded track) returns every sample, so strokes do not depend on the
  /// frame rate.
  virtual std::vector<ControllerState> poll(double now_s) = 0;
  /// The latest sample (drawn as the cursor).
  virtual ControllerState current() const = 0;
};

}  // namespace sketchsurf::input
