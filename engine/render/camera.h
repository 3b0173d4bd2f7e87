#pragma once
// The camera: a perspective look-at camera with Vulkan conventions, fitted to a bounding box from
// a named view, given explicitly, or turned around its target (turntable).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "surfacing/sketch/sketch.h"

namespace sketchsurf::render {

/// Named views, for a +y-up scene (Open Brush and the other readers use +y up).
enum class View {
  Front,  ///< from +z looking towards -z
  Back,   ///< from -z
  Left,   ///< from -x
  Right,  ///< from +x
  Top,    ///< from +y, with -z up in the picture
  Iso,    ///< three-quarter view from (+x, +y, +z): azimuth 35 deg from +z, elevation 25 deg
};

/// Parses "front", "back", "left", "right", "top" or "iso"; empty when unknown.
std::optional<View> parse_view(std::string_view name);
/// The names parse_view() accepts, in enum order.
std::vector<std::string> view_names();

/// An asymmetric field of view (a headset eye's, OpenXR's XrFovf): the angles of the four clip
/// planes from the viewing direction, radians; left and down are negative for a frustum around
/// the direction.
struct Frustum {
  double left = -0.5, right = 0.5, up = 0.5, down = -0.5;
};

/// A perspective camera. Distances in scene units.
struct Camera {
  Eigen::Vector3d eye{0.0, 0.0, 3.0};   ///< position
  Eigen::Vector3d target{0.0, 0.0, 0.0};  ///< point looked at (centre of the picture)
  Eigen::Vector3d up{0.0, 1.0, 0.0};    ///< approximate up direction, not parallel to target - eye
  double fov_y = 35.0;                  ///< vertical field of view, degrees
  double near_plane = 0.01;             ///< distance from the eye to the near clip plane, > 0
  double far_plane = 100.0;             ///< distance to the far clip plane, > near_plane
  std::optional<Frustum> frustum;       ///< when set, replaces fov_y and the aspect ratio

  /// World -> eye: right-handed, looking down -z.
  Eigen::Matrix4d view_matrix() const;
  /// Eye -> Vulkan clip space (y down in the picture, depth 0 at near and 1 at far). `aspect`
  /// (width / height) is ignored with a frustum.
  Eigen::Matrix4d projection_matrix(double aspect) const;
  /// Pixel coordinates (x right, y down, from the top-left corner) and depth in [0, 1] of `p`
  /// in a width x height picture; depth outside [0, 1] or a negative w means clipped.
  Eigen::Vector3d project(const Eigen::Vector3d& p, int width, int height) const;
};

/// The camera of an eye at `position` with `orientation` (local -z the viewing direction, +y up,
/// as an OpenXR view pose) and the field of view `frustum`.
Camera eye_camera(const Eigen::Vector3d& position, const Eigen::Quaterniond& orientation,
                  const Frustum& frustum, double near_plane, double far_plane);

/// How fit_camera() frames a box.
struct FitOptions {
  double fov_y = 35.0;   ///< vertical field of view, degrees
  double margin = 1.08;  ///< the box fills at most 1/margin of the half field of view (>= 1)
};

/// A camera looking at the centre of `box` from `view`, at the smallest distance that keeps every
/// corner of the box (hence every point in it) inside the picture of aspect `aspect`
/// (width / height), with `options.margin`. An empty or zero-size box is treated as a cube of
/// half side 1 around its centre (or the origin).
Camera fit_camera(const BoundingBox& box, View view, double aspect, const FitOptions& options = {});

/// Sets near and far planes of `camera` so that `box` (grown by 10%) lies between them.
void fit_clip_planes(Camera& camera, const BoundingBox& box);

/// Parses "ex,ey,ez,tx,ty,tz[,ux,uy,uz]" (up defaults to +y) and fits the clip planes to `box`.
/// Throws Error (Usage) naming what is wrong (count, a non-number, eye == target, up parallel).
Camera parse_camera(std::string_view text, const BoundingBox& box, double fov_y = 35.0);

/// `camera` turned by `radians` around the axis through its target along its up vector
/// (a turntable frame; positive turns counter-clockwise seen from above).
Camera orbit(const Camera& camera, double radians);

}  // namespace sketchsurf::render
