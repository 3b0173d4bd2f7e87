#include "surfacing/sketch/crossings.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace sketchsurf {

namespace {

struct Sample {
  Eigen::Vector3d point;
  Eigen::Vector3d direction;  // unit tangent of the segment the sample lies on
  std::size_t stroke;
};

// The polyline resampled every `spacing` of arc length (its last point included), each sample with
// the unit direction of the segment it lies on.
void resample(const Stroke& stroke, std::size_t index, double spacing, std::vector<Sample>& out) {
  double carried = 0.0;  // arc length since the last sample
  for (std::size_t i = 1; i < stroke.points.size(); ++i) {
    const Eigen::Vector3d a = stroke.points[i - 1], b = stroke.points[i];
    const double length = (b - a).norm();
    if (!(length > 0.0)) continue;
    const Eigen::Vector3d direction = (b - a) / length;
    if (out.empty() || out.back().stroke != index) out.push_back({a, direction, index});
    double at = spacing - carried;
    for (; at <= length; at += spacing) out.push_back({a + at * direction, direction, index});
    carried = length - (at - spacing);
  }
  if (!out.empty() && out.back().stroke == index && (out.back().point - stroke.points.back()).norm() > 0.0)
    out.push_back({stroke.points.back(), out.back().direction, index});
}

std::uint64_t cell_key(const Eigen::Vector3d& p, double cell) {
  const auto coordinate = [&](double x) {
    return static_cast<std::uint64_t>(static_cast<std::int64_t>(std::floor(x / cell)) + (1 << 20)) & 0x1fffff;
  };
  return (coordinate(p.x()) << 42) | (coordinate(p.y()) << 21) | coordinate(p.z());
}

}  // namespace

double unmet_share(const Sketch& sketch, double reach, double angle) {
  std::vector<Sample> samples;
  std::vector<double> lengths(sketch.strokes.size(), 0.0);
  double ink = 0.0;
  for (std::size_t s = 0; s < sketch.strokes.size(); ++s) {
    const Stroke& stroke = sketch.strokes[s];
    if (stroke.ignored || stroke.size() < 2) continue;
    lengths[s] = stroke.length();
    ink += lengths[s];
    resample(stroke, s, 0.5 * reach, samples);
  }
  if (!(ink > 0.0) || !(reach > 0.0)) return 0.0;
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> cells;
  for (std::size_t i = 0; i < samples.size(); ++i) cells[cell_key(samples[i].point, reach)].push_back(i);
  const double most_aligned = std::cos(angle);
  std::vector<char> met(sketch.strokes.size(), 0);
  const auto meets_another = [&](const Sample& a) {
    const Eigen::Vector3d c = (a.point / reach).array().floor();
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const Eigen::Vector3d corner =
              (c + Eigen::Vector3d(dx, dy, dz) + Eigen::Vector3d::Constant(0.5)) * reach;
          const auto found = cells.find(cell_key(corner, reach));
          if (found == cells.end()) continue;
          for (std::size_t j : found->second) {
            const Sample& b = samples[j];
            if (b.stroke == a.stroke || (b.point - a.point).squaredNorm() > reach * reach) continue;
            if (std::abs(a.direction.dot(b.direction)) < most_aligned) {
              met[b.stroke] = 1;
              return true;
            }
          }
        }
    return false;
  };
  for (const Sample& a : samples)
    if (!met[a.stroke] && meets_another(a)) met[a.stroke] = 1;
  double unmet = 0.0;
  for (std::size_t s = 0; s < sketch.strokes.size(); ++s)
    if (!met[s]) unmet += lengths[s];
  return unmet / ink;
}

}  // namespace sketchsurf
