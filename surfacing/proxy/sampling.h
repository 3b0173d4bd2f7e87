#pragma once
// Choosing the VIPSS input points from the strokes (METHOD.md section 1, first step).

#include <Eigen/Core>
#include <cstddef>

#include "surfacing/sketch/sketch.h"

namespace sketchsurf {

/// Options for sample_strokes().
struct SamplingOptions {
  std::size_t count = 1000;  ///< number of points wanted (fewer when the strokes are too short)
  double spacing = 0.002;    ///< candidate spacing along each stroke, fraction of the bbox diagonal
  double min_distance = 0.001;  ///< no two samples closer than this, fraction of the bbox diagonal

  /// True when the options can be used; otherwise `why` (if given) says which field is wrong.
  bool valid(std::string* why = nullptr) const;
};

/// Evenly spread points on the strokes: every stroke not flagged `ignored` is resampled at
/// `spacing`, then farthest-point sampling picks `count` of those candidates (the first one is the
/// candidate farthest from the centre of the box), so that coverage is even along every stroke
/// whatever the stroke density. Stops early when the next sample would be closer than
/// `min_distance` to another. Deterministic.
/// @return #samples x 3, in the sketch's units, in the order they were picked.
/// @throws Error (Usage) for invalid options; Error (Processing) when no stroke has points.
Eigen::MatrixX3d sample_strokes(const Sketch& sketch, const SamplingOptions& options);

}  // namespace sketchsurf
