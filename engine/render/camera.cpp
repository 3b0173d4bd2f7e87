#include "engine/render/camera.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <charconv>
#include <cmath>

#include "surfacing/error.h"

namespace sketchsurf::render {

namespace {

constexpr double kDegree = M_PI / 180.0;

struct ViewDirection {
  const char* name;
  Eigen::Vector3d towards_eye;  // from the target towards the eye
  Eigen::Vector3d up;
};

ViewDirection direction(View view) {
  const double az = 35.0 * kDegree, el = 25.0 * kDegree;
  switch (view) {
    case View::Front: return {"front", {0, 0, 1}, {0, 1, 0}};
    case View::Back: return {"back", {0, 0, -1}, {0, 1, 0}};
    case View::Left: return {"left", {-1, 0, 0}, {0, 1, 0}};
    case View::Right: return {"right", {1, 0, 0}, {0, 1, 0}};
    case View::Top: return {"top", {0, 1, 0}, {0, 0, -1}};
    case View::Iso:
      return {"iso", {std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az)}, {0, 1, 0}};
  }
  return {"iso", {0, 0, 1}, {0, 1, 0}};
}

constexpr View kViews[] = {View::Front, View::Back, View::Left, View::Right, View::Top, View::Iso};

/// Centre and bounding-sphere radius of a box; a unit sphere for an empty or point-like box.
std::pair<Eigen::Vector3d, double> sphere_of(const BoundingBox& box) {
  if (box.empty()) return {Eigen::Vector3d::Zero(), 1.0};
  const Eigen::Vector3d centre = 0.5 * (box.min + box.max);
  const double r = 0.5 * box.diagonal();
  return {centre, r > 0.0 ? r : 1.0};
}

}  // namespace

std::optional<View> parse_view(std::string_view name) {
  for (View v : kViews)
    if (name == direction(v).name) return v;
  return std::nullopt;
}

std::vector<std::string> view_names() {
  std::vector<std::string> names;
  for (View v : kViews) names.emplace_back(direction(v).name);
  return names;
}

Eigen::Matrix4d Camera::view_matrix() const {
  const Eigen::Vector3d f = (target - eye).normalized();
  const Eigen::Vector3d s = f.cross(up).normalized();
  const Eigen::Vector3d u = s.cross(f);
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  m.block<1, 3>(0, 0) = s.transpose();
  m.block<1, 3>(1, 0) = u.transpose();
  m.block<1, 3>(2, 0) = -f.transpose();
  m(0, 3) = -s.dot(eye);
  m(1, 3) = -u.dot(eye);
  m(2, 3) = f.dot(eye);
  return m;
}

Eigen::Matrix4d Camera::projection_matrix(double aspect) const {
  // Right-handed eye space (looking down -z) to Vulkan clip space: y flipped so that +y in the
  // eye is up in the picture, depth mapped to [0, 1].
  const double n = near_plane, f = far_plane;
  Eigen::Matrix4d p = Eigen::Matrix4d::Zero();
  if (frustum) {
    // x / -z runs from tan(left) to tan(right) across the picture, y / -z from tan(up) at the
    // top to tan(down) at the bottom.
    const double l = std::tan(frustum->left), r = std::tan(frustum->right);
    const double u = std::tan(frustum->up), d = std::tan(frustum->down);
    p(0, 0) = 2.0 / (r - l);
    p(0, 2) = (r + l) / (r - l);
    p(1, 1) = -2.0 / (u - d);
    p(1, 2) = -(u + d) / (u - d);
  } else {
    const double t = 1.0 / std::tan(0.5 * fov_y * kDegree);
    p(0, 0) = t / aspect;
    p(1, 1) = -t;
  }
  p(2, 2) = f / (n - f);
  p(2, 3) = f * n / (n - f);
  p(3, 2) = -1.0;
  return p;
}

Eigen::Vector3d Camera::project(const Eigen::Vector3d& p, int width, int height) const {
  const Eigen::Vector4d clip = projection_matrix(double(width) / double(height)) * view_matrix() *
                               Eigen::Vector4d(p.x(), p.y(), p.z(), 1.0);
  if (clip.w() <= 0.0) return {-1.0, -1.0, -1.0};
  const Eigen::Vector3d ndc = clip.head<3>() / clip.w();
  return {(ndc.x() + 1.0) * 0.5 * width, (ndc.y() + 1.0) * 0.5 * height, ndc.z()};
}

Camera eye_camera(const Eigen::Vector3d& position, const Eigen::Quaterniond& orientation,
                  const Frustum& frustum, double near_plane, double far_plane) {
  Camera camera;
  camera.eye = position;
  camera.target = position + orientation * -Eigen::Vector3d::UnitZ();
  camera.up = orientation * Eigen::Vector3d::UnitY();
  camera.frustum = frustum;
  camera.fov_y = (frustum.up - frustum.down) / kDegree;
  camera.near_plane = near_plane;
  camera.far_plane = far_plane;
  return camera;
}

Camera fit_camera(const BoundingBox& box, View view, double aspect, const FitOptions& options) {
  const auto [centre, radius] = sphere_of(box);
  const ViewDirection dir = direction(view);
  Camera camera;
  camera.fov_y = options.fov_y;
  camera.target = centre;
  camera.up = dir.up;
  const Eigen::Vector3d back = dir.towards_eye.normalized();
  const Eigen::Vector3d right = dir.up.cross(back).normalized();
  const Eigen::Vector3d up = back.cross(right);
  // Each corner of the box (or of the sphere's cube for an empty or point-like box) must be in
  // the view frustum: with the corner at (x, y, z) in the camera frame around the target (z
  // towards the eye), the eye at distance d sees it inside when |x| <= tan(half_x) (d - z), and
  // likewise for y. The frustum is convex, so every point of the box is then inside too.
  const double margin = std::max(options.margin, 1.0);
  const double tan_y = std::tan(0.5 * options.fov_y * kDegree) / margin;
  const double tan_x = tan_y * aspect;
  const bool degenerate = box.empty() || box.diagonal() == 0.0;
  const Eigen::Vector3d lo = degenerate ? centre - Eigen::Vector3d::Constant(radius) : box.min;
  const Eigen::Vector3d hi = degenerate ? centre + Eigen::Vector3d::Constant(radius) : box.max;
  double distance = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d p((corner & 1) ? hi.x() : lo.x(), (corner & 2) ? hi.y() : lo.y(),
                            (corner & 4) ? hi.z() : lo.z());
    const Eigen::Vector3d q = p - centre;
    const double z = q.dot(back);
    distance = std::max({distance, z + std::abs(q.dot(right)) / tan_x,
                         z + std::abs(q.dot(up)) / tan_y, z + 1e-3 * radius});
  }
  camera.eye = centre + distance * back;
  fit_clip_planes(camera, box);
  return camera;
}

void fit_clip_planes(Camera& camera, const BoundingBox& box) {
  const auto [centre, radius] = sphere_of(box);
  const double d = (centre - camera.eye).norm();
  const double reach = 1.1 * radius;
  camera.far_plane = d + reach;
  camera.near_plane = std::max(d - reach, 1e-3 * camera.far_plane);
}

Camera parse_camera(std::string_view text, const BoundingBox& box, double fov_y) {
  std::vector<double> values;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    std::string item(text.substr(start, comma - start));
    item.erase(0, item.find_first_not_of(' '));
    item.erase(item.find_last_not_of(' ') + 1);
    double v = 0.0;
    const auto [end, ec] = std::from_chars(item.data(), item.data() + item.size(), v);
    if (item.empty() || ec != std::errc() || end != item.data() + item.size() || !std::isfinite(v))
      throw Error::usage("--camera: '" + item + "' is not a number (expected ex,ey,ez,tx,ty,tz[,ux,uy,uz])");
    values.push_back(v);
    start = comma + 1;
  }
  if (values.size() != 6 && values.size() != 9)
    throw Error::usage("--camera: expected 6 or 9 comma-separated numbers (ex,ey,ez,tx,ty,tz[,ux,uy,uz]), got " +
                       std::to_string(values.size()));
  Camera camera;
  camera.fov_y = fov_y;
  camera.eye = {values[0], values[1], values[2]};
  camera.target = {values[3], values[4], values[5]};
  if (values.size() == 9) camera.up = {values[6], values[7], values[8]};
  const Eigen::Vector3d forward = camera.target - camera.eye;
  if (forward.norm() == 0.0) throw Error::usage("--camera: eye and target are the same point");
  if (camera.up.norm() == 0.0 || forward.normalized().cross(camera.up.normalized()).norm() < 1e-6)
    throw Error::usage("--camera: the up vector is zero or parallel to the viewing direction");
  fit_clip_planes(camera, box);
  return camera;
}

Camera orbit(const Camera& camera, double radians) {
  const Eigen::AngleAxisd turn(radians, camera.up.normalized());
  Camera turned = camera;
  turned.eye = camera.target + turn * (camera.eye - camera.target);
  return turned;
}

}  // namespace sketchsurf::render
