#include "surfacing/sketch/scribbles.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_set>

namespace sketchsurf {

namespace {

constexpr double kCells = 16.0;  // cells across a stroke's bounding-box diagonal

}  // namespace

double stroke_fill(const Stroke& stroke) {
  BoundingBox box;
  for (const Eigen::Vector3d& p : stroke.points) box.extend(p);
  const double extent = box.diagonal();
  if (!(extent > 0.0)) return 0.0;
  const double cell = extent / kCells;
  // Cell indices are at most kCells along each axis: one 64-bit key per cell.
  const auto key = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector3d c = ((p - box.min) / cell).array().floor();
    return (static_cast<std::uint64_t>(c.x()) << 42) | (static_cast<std::uint64_t>(c.y()) << 21) |
           static_cast<std::uint64_t>(c.z());
  };
  std::unordered_set<std::uint64_t> cells;
  cells.insert(key(stroke.points.front()));
  // Steps of a quarter cell along every segment: no cell the polyline crosses is missed by more
  // than a corner.
  for (std::size_t i = 1; i < stroke.points.size(); ++i) {
    const Eigen::Vector3d a = stroke.points[i - 1], b = stroke.points[i];
    const int steps = std::max(1, static_cast<int>(std::ceil(4.0 * (b - a).norm() / cell)));
    for (int k = 1; k <= steps; ++k) cells.insert(key(a + (b - a) * (static_cast<double>(k) / steps)));
  }
  return static_cast<double>(cells.size()) / kCells;
}

double scribbled_share(const Sketch& sketch, double fill) {
  double ink = 0.0, scribbled = 0.0;
  for (const Stroke& stroke : sketch.strokes) {
    if (stroke.ignored || stroke.size() < 2) continue;
    const double length = stroke.length();
    ink += length;
    if (stroke_fill(stroke) > fill) scribbled += length;
  }
  return ink > 0.0 ? scribbled / ink : 0.0;
}

}  // namespace sketchsurf
