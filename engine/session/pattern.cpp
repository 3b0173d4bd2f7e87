#include "engine/session/pattern.h"

#include <cmath>

#include "surfacing/error.h"

namespace sketchsurf::session {

Stroke rotated(const Stroke& stroke, const RotationPattern& pattern, int step) {
  const double angle = 2.0 * M_PI * double(step) / double(pattern.count);
  const Eigen::AngleAxisd turn(angle, pattern.axis);
  const Eigen::Matrix3d r = turn.toRotationMatrix();
  Stroke out = stroke;
  for (auto& p : out.points) p = pattern.center + r * (p - pattern.center);
  const Eigen::Quaterniond q_turn(turn);
  for (auto& q : out.orientations) q = (q_turn * q).normalized();
  return out;
}

std::vector<Stroke> pattern_images(const Stroke& stroke, const std::optional<Plane>& mirror,
                                   const std::optional<RotationPattern>& rotation) {
  std::vector<Stroke> copies{stroke};
  if (rotation)
    for (int k = 1; k < rotation->count; ++k) copies.push_back(rotated(stroke, *rotation, k));
  if (mirror) {
    const std::size_t n = copies.size();
    for (std::size_t i = 0; i < n; ++i) copies.push_back(mirrored(copies[i], *mirror));
  }
  copies.erase(copies.begin());
  return copies;
}

RotationPattern checked_rotation(const RotationPattern& pattern) {
  const double n = pattern.axis.norm();
  if (!(n > 0.0) || !std::isfinite(n) || !pattern.center.allFinite())
    throw Error::usage("the rotation needs a finite centre and a finite, non-zero axis");
  if (pattern.count < 2 || pattern.count > 360)
    throw Error::usage("the rotation's count must be from 2 to 360, not " + std::to_string(pattern.count));
  RotationPattern out = pattern;
  out.axis /= n;
  return out;
}

}  // namespace sketchsurf::session
