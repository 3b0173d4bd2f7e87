#include "engine/session/drawing_plane.h"

#include <algorithm>
#include <cmath>

#include "surfacing/error.h"

namespace sketchsurf::session {

Plane axis_plane(int axis, const Eigen::Vector3d& through) {
  if (axis < 0 || axis > 2) throw Error::usage("the drawing plane's axis must be x, y or z");
  if (!through.allFinite()) throw Error::usage("the drawing plane needs a finite point");
  Plane plane;
  plane.normal = Eigen::Vector3d::Unit(axis);
  plane.offset = -through[axis];
  return plane;
}

Plane plane_through(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  if (!a.allFinite() || !b.allFinite() || !c.allFinite())
    throw Error::usage("the drawing plane needs three finite points");
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double longest = std::max({(b - a).norm(), (c - b).norm(), (a - c).norm()});
  // Twice the area over the longest side is the smallest height of the triangle.
  if (!(longest > 0.0) || !(n.norm() / longest > 1e-9 * longest))
    throw Error::usage("the three points of a drawing plane lie on a line; click three points "
                       "that span a triangle");
  Plane plane;
  plane.normal = n.normalized();
  plane.offset = -plane.normal.dot(a);
  return plane;
}

Plane plane_facing(const render::Camera& camera, const Eigen::Vector3d& through) {
  Eigen::Vector3d n = camera.eye - camera.target;
  if (!(n.norm() > 0.0)) n = Eigen::Vector3d::UnitZ();
  Plane plane;
  plane.normal = n.normalized();
  plane.offset = -plane.normal.dot(through);
  return plane;
}

Eigen::Vector3d guide_to_plane(const Plane& plane, const Eigen::Vector3d& p, double band) {
  const double d = plane.signed_distance(p);
  return std::abs(d) <= band ? Eigen::Vector3d(p - d * plane.normal) : p;
}

}  // namespace sketchsurf::session
