#include "engine/input/navigation.h"

#include <algorithm>
#include <cmath>

namespace sketchsurf::input {

namespace {
constexpr double kDegree = M_PI / 180.0;
constexpr double kMaxPitch = 89.0 * kDegree;
}  // namespace

Eigen::Vector3d OrbitCamera::eye() const {
  const Eigen::Vector3d back(std::cos(pitch) * std::sin(yaw), std::sin(pitch),
                             std::cos(pitch) * std::cos(yaw));
  return target + distance * back;
}

render::Camera OrbitCamera::camera() const {
  render::Camera c;
  c.eye = eye();
  c.target = target;
  c.up = Eigen::Vector3d::UnitY();
  c.fov_y = fov_y;
  c.near_plane = distance / 100.0;
  c.far_plane = distance * 100.0;
  return c;
}

void OrbitCamera::orbit(double dx_px, double dy_px) {
  yaw -= dx_px * orbit_speed * kDegree;
  pitch = std::clamp(pitch + dy_px * orbit_speed * kDegree, -kMaxPitch, kMaxPitch);
}

void OrbitCamera::pan(double dx_px, double dy_px, int viewport_height) {
  const render::Camera c = camera();
  const Eigen::Vector3d forward = (c.target - c.eye).normalized();
  const Eigen::Vector3d right = forward.cross(c.up).normalized();
  const Eigen::Vector3d up = right.cross(forward);
  const double per_pixel =
      2.0 * distance * std::tan(0.5 * fov_y * kDegree) / std::max(1, viewport_height);
  target += (-dx_px * right + dy_px * up) * per_pixel;
}

void OrbitCamera::zoom(double steps) {
  distance = std::clamp(distance * std::pow(0.9, steps), 1e-6, 1e9);
}

void OrbitCamera::frame(const BoundingBox& box, double aspect) {
  BoundingBox b = box;
  if (b.empty()) {
    b.extend(Eigen::Vector3d::Constant(-0.5));
    b.extend(Eigen::Vector3d::Constant(0.5));
  }
  // fit_camera() frames along a named view; do the same along the current direction by fitting
  // the box's bounding sphere, which any direction sees whole.
  const Eigen::Vector3d centre = 0.5 * (b.min + b.max);
  const double radius = std::max(0.5 * b.diagonal(), 1e-6);
  const double half = 0.5 * fov_y * kDegree;
  const double half_x = std::atan(std::tan(half) * std::max(aspect, 1e-3));
  target = centre;
  distance = 1.08 * radius / std::sin(std::min(half, half_x));
}

void OrbitCamera::look_from(render::View view) {
  switch (view) {
    case render::View::Front: yaw = 0.0, pitch = 0.0; break;
    case render::View::Back: yaw = M_PI, pitch = 0.0; break;
    case render::View::Left: yaw = -0.5 * M_PI, pitch = 0.0; break;
    case render::View::Right: yaw = 0.5 * M_PI, pitch = 0.0; break;
    case render::View::Top: yaw = 0.0, pitch = kMaxPitch; break;
    case render::View::Iso: yaw = 35.0 * kDegree, pitch = 25.0 * kDegree; break;
  }
}

}  // namespace sketchsurf::input
