#pragma once
// Mirror symmetry of a sketch: people sketch symmetric objects (cars, chairs, mugs) and the
// surfacer does better on half of them, mirrored (paper §5), but only when told the plane. This
// finds the plane when the strokes have one, and when they are only one half of a symmetric
// object, its strokes running up to the plane and stopping there.

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
  int half_ends = 4;        ///< half a sketch: at least this many free stroke ends lie on one plane
                            ///< (within the tolerance), with every stroke on one side of it...
  double half_angle = 25.0; ///< ...each stroke arriving within this many degrees of the plane's
                            ///< normal (it runs on across the plane in the mirror image)...
  double free_end = 0.02;   ///< ...and no other stroke within this of its end (a box's edges end
                            ///< on each other at its corners; half an object's sections end in the air)
  unsigned threads = 0;     ///< for the closest-point queries (0 = all); the result does not depend on it
  bool valid(std::string* why) const;
};

/// A symmetry plane found in a sketch.
struct DetectedMirror {
  Plane plane;             ///< unit normal, offset: n . x + d = 0
  double distance = 0.0;   ///< 90th percentile of the reflected points' distance to the strokes
                           ///< (half a sketch: the free ends' distance to the plane, 90th percentile)
  int half_ends = 0;       ///< > 0: the strokes are one half, this many of them ending on the plane
};

/// The best mirror plane of the non-ignored strokes, if they are symmetric within the tolerance:
/// candidate planes through the points' centroid, normal to their principal axes and to the
/// coordinate axes, each refined by pairing every point with the stroke point nearest to its
/// reflection and fitting the plane that bisects the pairs. Deterministic. Strokes should be
/// resampled (the test runs on their points).
std::optional<DetectedMirror> detect_mirror(const Sketch& sketch, const MirrorDetectOptions& options = {});

/// The plane that the non-ignored strokes are one half of, if they are: at least
/// options.half_ends free open-stroke ends (no other stroke within options.free_end) lie within
/// options.tolerance of it, each stroke arriving there within options.half_angle of its normal,
/// and no stroke point lies farther than the tolerance beyond it. The normal points toward the
/// strokes (the kept side of a mirror plane). Candidates are the planes through each free end
/// normal to its stroke's arrival, refitted to the ends they gather; the one with the most wins.
/// Deterministic. Strokes should be resampled.
std::optional<DetectedMirror> detect_half_mirror(const Sketch& sketch, const MirrorDetectOptions& options = {});

/// Completes half a sketch with its mirror image in `plane`. A stroke with an end on the plane
/// (within `tolerance`, sketch units; snapped onto it) runs on through it into its own image, as
/// one stroke: a half section or rim becomes a closed loop, as drawn on the whole object. Every
/// other stroke gets its image as a new stroke (ids after the largest); a stroke lying in the
/// plane is its own image. The sketch's mirror plane is left as it is.
void complete_half(Sketch& sketch, const Plane& plane, double tolerance);

}  // namespace sketchsurf
