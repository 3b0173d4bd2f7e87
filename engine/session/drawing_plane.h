#pragma once
// The drawing plane (Kuhn 2009 §3.4's support geometry): the one plane that the mouse's cursor
// ray lands on (input::MouseController, DepthMode::Plane) and that guides a 6-DoF controller:
// with the plane guide on, every point drawn within a band of the plane is projected onto it, so
// that strokes meant to be planar are, while a stroke drawn away from it stays free.
// Made axis-aligned, through three points the user clicks, or facing the view.

#include <Eigen/Core>

#include "engine/render/camera.h"
#include "surfacing/sketch/sketch.h"

namespace sketchsurf::session {

/// The plane x = through.x (axis 0), y = through.y (1) or z = through.z (2). Throws Error (Usage)
/// for another axis or a point that is not finite.
Plane axis_plane(int axis, const Eigen::Vector3d& through);

/// The plane through three points, its normal by the right-hand rule (a, b, c counter-clockwise
/// seen from the front). Throws Error (Usage) when the points are not finite or lie on a line
/// (the triangle's smallest height under 1e-9 of its longest side).
Plane plane_through(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);

/// The plane through `through` facing the camera (normal from the target towards the eye).
Plane plane_facing(const render::Camera& camera, const Eigen::Vector3d& through);

/// `p` projected onto `plane` when it lies within `band` (sketch units) of it, else `p`.
Eigen::Vector3d guide_to_plane(const Plane& plane, const Eigen::Vector3d& p, double band);

}  // namespace sketchsurf::session
