#pragma once
// Patterns: the copies of a stroke that the sketch's mirror plane and rotational pattern ask for
// (Kuhn 2009 Fig. 43; Open Brush's mirror). A stroke drawn with a pattern on is added with all
// its images, so that the sketch stays exactly symmetric: a mirror image is the exact reflection,
// the copies of an n-fold rotation are 360/n degrees apart.

#include <optional>
#include <vector>

#include "surfacing/sketch/sketch.h"

namespace sketchsurf::session {

/// `stroke` turned by `step` * 360 / pattern.count degrees about the pattern's axis (right-hand
/// rule): points and orientations.
Stroke rotated(const Stroke& stroke, const RotationPattern& pattern, int step);

/// The images of `stroke` under the patterns, the stroke itself excluded: its rotations by
/// 1..count-1 steps, then the mirror image of the stroke and of each rotation. Empty when neither
/// pattern is set.
std::vector<Stroke> pattern_images(const Stroke& stroke, const std::optional<Plane>& mirror,
                                   const std::optional<RotationPattern>& rotation);

/// The pattern with a unit axis. Throws Error (Usage) when the axis is zero or not finite, the
/// centre not finite, or the count outside 2..360.
RotationPattern checked_rotation(const RotationPattern& pattern);

}  // namespace sketchsurf::session
