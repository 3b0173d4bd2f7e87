#pragma once
// OrbitCamera: the view a 3D-software user expects to move: orbit around a target, pan, zoom
// (dolly), frame everything. Turns into a render::Camera for the renderer.

#include <Eigen/Core>

#include "engine/render/camera.h"
#include "surfacing/sketch/sketch.h"

namespace sketchsurf::input {

/// A camera orbiting `target` at `distance`, +y up. Angles in radians.
struct OrbitCamera {
  Eigen::Vector3d target = Eigen::Vector3d::Zero();  ///< the point looked at and orbited around
  double distance = 3.0;     ///< from the eye to the target, sketch units, > 0
  double yaw = 0.0;          ///< around +y; 0 looks from +z towards -z (the front view)
  double pitch = 0.0;        ///< elevation; positive looks from above; kept within +-89 degrees
  double fov_y = 35.0;       ///< vertical field of view, degrees
  double orbit_speed = 0.5;  ///< degrees per pixel dragged

  /// The eye position.
  Eigen::Vector3d eye() const;
  /// The camera (clip planes at distance / 100 and distance * 100).
  render::Camera camera() const;
  /// Turns around the target: dragging right turns the scene right (the eye moves left), dragging
  /// down tilts it towards the viewer.
  void orbit(double dx_px, double dy_px);
  /// Moves eye and target so that the point on the target's depth follows the cursor.
  void pan(double dx_px, double dy_px, int viewport_height);
  /// Moves the eye towards the target by 10% per step (negative steps move away).
  void zoom(double steps);
  /// Keeps the direction, centres `box` and moves back until all of it is in view.
  void frame(const BoundingBox& box, double aspect);
  /// Sets the direction of a named view (front, top, iso, ...), keeping target and distance.
  void look_from(render::View view);
};

}  // namespace sketchsurf::input
