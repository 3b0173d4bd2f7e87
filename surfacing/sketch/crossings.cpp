#include "surfacing/sketch/crossings.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "surfacing/portable_math.h"
#include "surfacing/sketch/stroke_point_grid.h"

namespace sketchsurf {

double unmet_share(const Sketch& sketch, double reach, double angle) {
  if (!(reach > 0.0)) return 0.0;
  // The strokes resampled every reach / 2, so that a crossing leaves a point of each within reach.
  Sketch fine;
  fine.strokes.resize(sketch.strokes.size());
  double ink = 0.0;
  for (std::size_t s = 0; s < sketch.strokes.size(); ++s) {
    const Stroke& stroke = sketch.strokes[s];
    if (stroke.ignored || stroke.size() < 2) {
      fine.strokes[s].ignored = true;
      continue;
    }
    ink += stroke.length();
    fine.strokes[s] = resample(stroke, 0.5 * reach);
  }
  if (!(ink > 0.0)) return 0.0;
  // A resampled stroke's direction at its point i (central difference; unit, or zero).
  const auto direction = [&](std::size_t s, std::size_t i) -> Eigen::Vector3d {
    const std::vector<Eigen::Vector3d>& p = fine.strokes[s].points;
    const Eigen::Vector3d d = p[std::min(i + 1, p.size() - 1)] - p[i > 0 ? i - 1 : 0];
    return d.norm() > 0.0 ? Eigen::Vector3d(d.normalized()) : Eigen::Vector3d::Zero();
  };
  const StrokePointGrid grid(fine, reach, false);
  const double most_aligned = portable::cos(angle);
  std::vector<char> met(sketch.strokes.size(), 0);
  for (std::size_t s = 0; s < fine.strokes.size(); ++s) {
    if (fine.strokes[s].ignored) continue;
    for (std::size_t i = 0; i < fine.strokes[s].points.size() && !met[s]; ++i) {
      const Eigen::Vector3d t = direction(s, i);
      met[s] = grid.any_near(fine.strokes[s].points[i], s, reach, [&](std::size_t other, std::size_t j) {
        if (std::abs(t.dot(direction(other, j))) >= most_aligned) return false;
        met[other] = 1;
        return true;
      });
    }
  }
  double unmet = 0.0;
  for (std::size_t s = 0; s < sketch.strokes.size(); ++s)
    if (!met[s] && !fine.strokes[s].ignored) unmet += sketch.strokes[s].length();
  return unmet / ink;
}

}  // namespace sketchsurf
