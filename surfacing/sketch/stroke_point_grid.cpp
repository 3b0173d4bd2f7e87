#include "surfacing/sketch/stroke_point_grid.h"

#include <algorithm>
#include <cmath>

namespace sketchsurf {

StrokePointGrid::StrokePointGrid(const Sketch& sketch, double cell, bool with_ignored) : cell_(cell) {
  for (std::size_t s = 0; s < sketch.strokes.size(); ++s)
    if (with_ignored || !sketch.strokes[s].ignored)
      for (std::size_t i = 0; i < sketch.strokes[s].points.size(); ++i) {
        const Eigen::Vector3d& p = sketch.strokes[s].points[i];
        cells_[cell_key(index(p))].push_back({p, s, i});
      }
}

bool StrokePointGrid::any_near(const Eigen::Vector3d& p, std::size_t self, double r,
                               const std::function<bool(std::size_t, std::size_t)>& visit) const {
  const Eigen::Vector3i c = index(p);
  const int reach = static_cast<int>(std::ceil(r / cell_));
  for (int dx = -reach; dx <= reach; ++dx)
    for (int dy = -reach; dy <= reach; ++dy)
      for (int dz = -reach; dz <= reach; ++dz) {
        const auto it = cells_.find(cell_key(c + Eigen::Vector3i(dx, dy, dz)));
        if (it == cells_.end()) continue;
        for (const Entry& e : it->second)
          if (e.stroke != self && (e.point - p).squaredNorm() <= r * r && visit(e.stroke, e.index)) return true;
      }
  return false;
}

std::vector<std::size_t> StrokePointGrid::strokes_near(const Eigen::Vector3d& p, std::size_t self, double r) const {
  std::vector<std::size_t> out;
  any_near(p, self, r, [&](std::size_t s, std::size_t) {
    out.push_back(s);
    return false;
  });
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

Eigen::Vector3i StrokePointGrid::index(const Eigen::Vector3d& p) const {
  return (p / cell_).array().floor().cast<int>();
}

std::uint64_t StrokePointGrid::cell_key(const Eigen::Vector3i& c) {
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(c.x())) * 73856093ull) ^
         (static_cast<std::uint64_t>(static_cast<std::uint32_t>(c.y())) * 19349663ull) ^
         (static_cast<std::uint64_t>(static_cast<std::uint32_t>(c.z())) * 83492791ull);
}

}  // namespace sketchsurf
