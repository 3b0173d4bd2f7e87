#pragma once
// The strokes' points in a uniform grid: "which other strokes come within r of this point" in
// constant time per query, for the tests that ask whether a stroke end is free or touches others
// (decorations.h, symmetry.h). Points, not segments: strokes should be resampled finer than r.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <unordered_map>
#include <vector>

#include "surfacing/sketch/sketch.h"

namespace sketchsurf {

class StrokePointGrid {
 public:
  /// The points of every stroke (of the non-ignored ones only, unless `with_ignored`) in cells of
  /// size `cell`; queries are cheapest for radii up to `cell`.
  StrokePointGrid(const Sketch& sketch, double cell, bool with_ignored = true);

  /// The strokes other than `self` with a point within `r` of p, sorted, unique.
  std::vector<std::size_t> strokes_near(const Eigen::Vector3d& p, std::size_t self, double r) const;

  /// Calls visit(stroke, point index) for every point of a stroke other than `self` within `r` of
  /// p, until visit returns true; returns whether it did.
  bool any_near(const Eigen::Vector3d& p, std::size_t self, double r,
                const std::function<bool(std::size_t, std::size_t)>& visit) const;

 private:
  Eigen::Vector3i index(const Eigen::Vector3d& p) const;
  static std::uint64_t cell_key(const Eigen::Vector3i& c);

  double cell_;
  struct Entry {
    Eigen::Vector3d point;
    std::size_t stroke, index;  // the point is strokes[stroke].points[index]
  };
  std::unordered_map<std::uint64_t, std::vector<Entry>> cells_;
};

}  // namespace sketchsurf
