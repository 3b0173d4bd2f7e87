#pragma once
// Mirror symmetry of a sketch: people sketch symmetric objects (cars, chairs, mugs) and the
// surfacer does better on half of them, mirrored (paper §5), but only when told the plane. This
// finds the plane when the strokes have one.

#include <optional>
#include <string>

#include "surfacing/sketch/sketch.h"

namespace sketchsurf {

/// Options for detect_mirror(). Distances are fractions of the sketch's bounding-box diagonal.
struct MirrorDetectOptions {
  double tolerance = 0.01;  ///< symmetric when 90% of the reflected stroke points lie this close
                            ///< to a stroke
  double balance = 0.25;    ///< and at least this share of the points lies on each side
  int iterations = 8;       ///< refinements of each candidate plane (closest-point pairs)
  bool valid(std::string* why) const;
};

/// A symmetry plane found in a sketch.
struct DetectedMirror {
  Plane plane;             ///< unit normal, offset: n . x + d = 0
  double distance = 0.0;   ///< 90th percentile of the reflected points' distance to the strokes
};

/// The best mirror plane of the non-ignored strokes, if they are symmetric within the tolerance:
/// candidate planes through the points' centroid, normal to their principal axes and to the
/// coordinate axes, each refined by pairing every point with the stroke point nearest to its
/// reflection and fitting the plane that bisects the pairs. Deterministic. Strokes should be
/// resampled (the test runs on their points).
std::optional<DetectedMirror> detect_mirror(const Sketch& sketch, const MirrorDetectOptions& options = {});

}  // namespace sketchsurf
