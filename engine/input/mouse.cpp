#include "engine/input/mouse.h"

#include <algorithm>
#include <cmath>

#include "surfacing/error.h"

namespace sketchsurf::input {

namespace {
constexpr double kDegree = M_PI / 180.0;
constexpr double kTurnPerPixel = 0.3 * kDegree;  // right-drag turn of the controller
constexpr double kPlaneStep = 0.02;              // Shift+wheel: fraction of the view distance
constexpr double kDistanceStep = 1.1;            // Shift+wheel in Distance mode: factor per notch
constexpr double kZoomPerPixel = 1.0 / 20.0;     // Ctrl+middle-drag: wheel notches per pixel
}  // namespace

MouseController::MouseController(int width, int height) : width_(1), height_(1) {
  resize(width, height);
  state_.tracked = false;
}

void MouseController::resize(int width, int height) {
  width_ = std::max(1, width);
  height_ = std::max(1, height);
}

void MouseController::set_drawing_plane(const Plane& plane) {
  const double n = plane.normal.norm();
  if (!(n > 0.0) || !std::isfinite(n) || !std::isfinite(plane.offset))
    throw Error::usage("the drawing plane needs a finite, non-zero normal");
  plane_ = {plane.normal / n, plane.offset / n};
}

void MouseController::set_depth(double distance) {
  if (!(distance > 0.0) || !std::isfinite(distance))
    throw Error::usage("the drawing depth must be positive and finite");
  depth_ = distance;
}

std::pair<Eigen::Vector3d, Eigen::Vector3d> MouseController::ray(double x, double y) const {
  // The inverse of Camera::project(): pixel -> normalised device coordinates -> eye space.
  const render::Camera c = camera();
  const double aspect = double(width_) / double(height_);
  const double t = 1.0 / std::tan(0.5 * c.fov_y * kDegree);
  const double ndc_x = 2.0 * x / width_ - 1.0, ndc_y = 2.0 * y / height_ - 1.0;
  const Eigen::Vector3d forward = (c.target - c.eye).normalized();
  const Eigen::Vector3d right = forward.cross(c.up).normalized();
  const Eigen::Vector3d up = right.cross(forward);
  const Eigen::Vector3d direction =
      (forward + right * (ndc_x * aspect / t) - up * (ndc_y / t)).normalized();
  return {c.eye, direction};
}

void MouseController::move(double x, double y, double time_s) {
  const Eigen::Vector2d to(x, y);
  const Eigen::Vector2d d = to - cursor_;
  cursor_ = to;
  switch (drag_) {
    case Drag::Orbit: view_.orbit(d.x(), d.y()); break;
    case Drag::Pan: view_.pan(d.x(), d.y(), height_); break;
    case Drag::Zoom: view_.zoom(-d.y() * kZoomPerPixel); break;
    case Drag::Rotate:
      // Yaw about the view's up, pitch about the controller's own right axis.
      rotation_ = (Eigen::AngleAxisd(-d.x() * kTurnPerPixel, Eigen::Vector3d::UnitY()) * rotation_ *
                   Eigen::AngleAxisd(-d.y() * kTurnPerPixel, Eigen::Vector3d::UnitX()))
                      .normalized();
      break;
    case Drag::Draw:
    case Drag::None: break;
  }
  update(time_s);
}

void MouseController::button(MouseButton button, bool down, Modifiers mods, double time_s) {
  if (down) {
    if (drag_ != Drag::None) return;  // one drag at a time
    drag_button_ = button;
    const auto navigation = [&] {
      return mods.shift ? Drag::Pan : mods.ctrl ? Drag::Zoom : Drag::Orbit;
    };
    switch (button) {
      case MouseButton::Left:
        drag_ = mods.alt ? navigation() : Drag::Draw;
        break;
      case MouseButton::Right: drag_ = Drag::Rotate; break;
      case MouseButton::Middle: drag_ = navigation(); break;
    }
    if (drag_ == Drag::Draw) {
      state_.set(Button::Draw, true);
      state_.trigger = 1.0f;
    }
    if (drag_ != Drag::Draw && drag_ != Drag::Rotate) state_.set(Button::Grab, true);
  } else {
    if (drag_ == Drag::None || button != drag_button_) return;
    state_.set(Button::Draw, false);
    state_.set(Button::Grab, false);
    state_.trigger = 0.0f;
    drag_ = Drag::None;
  }
  update(time_s);
}

void MouseController::scroll(double steps, Modifiers mods, double time_s) {
  if (mods.shift) {
    if (depth_mode_ == DepthMode::Distance) {
      depth_ *= std::pow(kDistanceStep, steps);
    } else {
      const Eigen::Vector3d eye = view_.eye();
      const double side = plane_.signed_distance(eye) >= 0.0 ? 1.0 : -1.0;
      // Moving the plane by delta along n changes n . x + d = 0 into n . x + (d - delta) = 0.
      const double delta = -side * kPlaneStep * view_.distance * steps;
      plane_.offset -= delta;
    }
  } else {
    view_.zoom(steps);
  }
  update(time_s);
}

void MouseController::update(double time_s) {
  const auto [origin, direction] = ray(cursor_.x(), cursor_.y());
  std::optional<double> t;
  if (depth_mode_ == DepthMode::Distance) t = depth_;
  if (depth_mode_ == DepthMode::Snap && pick_) {
    const double radius = pick_pixels_ * 2.0 * std::tan(0.5 * view_.fov_y * kDegree) / height_;
    t = pick_(origin, direction, radius);
  }
  if (!t) {
    const double facing = plane_.normal.dot(direction);
    if (std::abs(facing) > 1e-12) {
      const double along = -plane_.signed_distance(origin) / facing;
      if (along > 0.0 && std::isfinite(along)) t = along;
    }
  }
  state_.time_s = std::max(time_s, state_.time_s);
  state_.tracked = t.has_value();
  if (t) state_.pose.position = origin + *t * direction;
  // The view's frame (x right, y up, z towards the viewer), turned by the user's rotation.
  const render::Camera c = camera();
  const Eigen::Vector3d back = (c.eye - c.target).normalized();
  const Eigen::Vector3d right = c.up.cross(back).normalized();
  Eigen::Matrix3d frame;
  frame.col(0) = right;
  frame.col(1) = back.cross(right);
  frame.col(2) = back;
  state_.pose.orientation = (Eigen::Quaterniond(frame) * rotation_).normalized();
  queue_.push_back(state_);
}

std::vector<ControllerState> MouseController::poll(double) {
  std::vector<ControllerState> out;
  out.swap(queue_);
  return out;
}

}  // namespace sketchsurf::input
