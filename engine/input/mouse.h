#pragma once
// MouseController: the mouse emulating a 6-DoF controller, and the view navigation of a desktop
// 3D application.
//
// Pose: the cursor's camera ray gives the direction; the depth along it comes from the depth
// mode: the active drawing plane (default), a distance from the eye that Shift+wheel sets, or
// the surface / stroke under the cursor (snap; the drawing plane where there is none). The
// orientation is the view's, turned by right-dragging. Left button: the trigger (Draw, pressure 1).
//
// Navigation: middle-drag orbits, Shift+middle-drag pans, Ctrl+middle-drag zooms; the wheel zooms;
// Alt+left-drag orbits, Alt+Shift+left-drag pans, Alt+Ctrl+left-drag zooms (for mice and
// touchpads without a middle button). Shift+wheel moves the drawing depth (the plane along its
// normal, or the distance), away from the eye for positive steps.
//
// Events carry the caller's time (seconds); every event that changes the state queues one
// ControllerState, which poll() hands over.

#include <functional>
#include <optional>
#include <utility>
#include <vector>

#include "engine/input/controller.h"
#include "engine/input/navigation.h"
#include "surfacing/sketch/sketch.h"

namespace sketchsurf::input {

enum class MouseButton { Left, Right, Middle };

/// Keyboard modifiers held during a mouse event.
struct Modifiers {
  bool shift = false;
  bool ctrl = false;
  bool alt = false;
};

/// Where the controller's depth along the cursor ray comes from.
enum class DepthMode {
  Plane,     ///< the drawing plane
  Distance,  ///< a fixed distance from the eye
  Snap,      ///< the surface or stroke under the cursor; the drawing plane elsewhere
};

/// Distance along a ray (origin, unit direction) to what lies under the cursor, or none. The third
/// argument is the pick tolerance: radius per unit of distance from the eye.
using PickFunction = std::function<std::optional<double>(
    const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double radius_per_distance)>;

class MouseController : public Controller6DoF {
 public:
  /// A window of width x height (screen units of the cursor positions, each >= 1).
  MouseController(int width, int height);

  // --- events -----------------------------------------------------------------------------
  void resize(int width, int height);
  /// The cursor moved to (x, y), from the window's top-left corner.
  void move(double x, double y, double time_s);
  void button(MouseButton button, bool down, Modifiers mods, double time_s);
  /// Wheel by `steps` notches (positive: away from the user / up).
  void scroll(double steps, Modifiers mods, double time_s);

  // --- Controller6DoF -----------------------------------------------------------------------
  std::vector<ControllerState> poll(double now_s) override;
  ControllerState current() const override { return state_; }

  // --- settings -----------------------------------------------------------------------------
  OrbitCamera& view() { return view_; }
  const OrbitCamera& view() const { return view_; }
  /// The camera of the view.
  render::Camera camera() const { return view_.camera(); }
  int width() const { return width_; }
  int height() const { return height_; }

  DepthMode depth_mode() const { return depth_mode_; }
  void set_depth_mode(DepthMode mode) { depth_mode_ = mode; }
  /// The drawing plane (default z = 0: n = +z, d = 0).
  const Plane& drawing_plane() const { return plane_; }
  void set_drawing_plane(const Plane& plane);
  /// The distance from the eye in DepthMode::Distance (default 3).
  double depth() const { return depth_; }
  void set_depth(double distance);
  /// What Snap picks (the session's strokes and surface); without one, Snap acts as Plane.
  void set_pick(PickFunction pick) { pick_ = std::move(pick); }
  /// Pick tolerance in pixels (default 8).
  void set_pick_pixels(double pixels) { pick_pixels_ = pixels; }
  /// The controller's turn relative to the view (right-drag), and 0.3 degrees per pixel.
  const Eigen::Quaterniond& rotation() const { return rotation_; }
  void set_rotation(const Eigen::Quaterniond& rotation) { rotation_ = rotation.normalized(); }

  /// The ray through the window point (x, y): the eye and a unit direction.
  std::pair<Eigen::Vector3d, Eigen::Vector3d> ray(double x, double y) const;
  /// True while a navigation drag (orbit, pan, zoom) or a controller turn is under way.
  bool dragging() const { return drag_ != Drag::None; }
  /// The cursor position.
  Eigen::Vector2d cursor() const { return cursor_; }

 private:
  enum class Drag { None, Draw, Rotate, Orbit, Pan, Zoom };
  /// Recomputes the pose from the cursor and queues the state.
  void update(double time_s);

  int width_, height_;
  OrbitCamera view_;
  DepthMode depth_mode_ = DepthMode::Plane;
  Plane plane_{Eigen::Vector3d::UnitZ(), 0.0};
  double depth_ = 3.0;
  double pick_pixels_ = 8.0;
  PickFunction pick_;
  Eigen::Quaterniond rotation_ = Eigen::Quaterniond::Identity();
  Eigen::Vector2d cursor_{0.0, 0.0};
  Drag drag_ = Drag::None;
  MouseButton drag_button_ = MouseButton::Left;
  ControllerState state_;
  std::vector<ControllerState> queue_;
};

}  // namespace sketchsurf::input
