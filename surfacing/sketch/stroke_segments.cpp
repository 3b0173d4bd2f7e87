#include "surfacing/sketch/stroke_segments.h"

#include <vector>

namespace sketchsurf {

StrokeSegments stroke_segments(const Sketch& sketch, bool mirrored) {
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector3i> segments;
  StrokeSegments out;
  for (int copy = 0; copy < (mirrored && sketch.mirror ? 2 : 1); ++copy)
    for (const Stroke& s : sketch.strokes) {
      if (s.ignored || s.points.empty()) continue;
      const int first = static_cast<int>(points.size());
      for (const Eigen::Vector3d& p : s.points) {
        points.push_back(copy == 1 ? sketch.mirror->reflect(p) : p);
        out.box.extend(points.back());
      }
      const int n = static_cast<int>(s.points.size());
      if (n == 1) segments.emplace_back(first, first, first);
      for (int i = 0; i + 1 < n; ++i) segments.emplace_back(first + i, first + i + 1, first + i + 1);
    }
  out.points.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) out.points.row(static_cast<Eigen::Index>(i)) = points[i];
  out.segments.resize(static_cast<Eigen::Index>(segments.size()), 3);
  for (std::size_t i = 0; i < segments.size(); ++i) out.segments.row(static_cast<Eigen::Index>(i)) = segments[i];
  return out;
}

}  // namespace sketchsurf
