#pragma once
// Over-sketching: people drawing mid-air retrace a curve two or three times, each pass a little
// off the others. The passes are one curve to the designer, but to the fitting they are a band of
// parallel strokes a few millimetres apart that no smooth surface passes through: faces split
// along the band, edges bulge, patches tear. consolidate_overdrawn() pulls the passes of such a
// bundle onto their common centre line, so the rest of the method sees the one curve meant.
//
// Only strokes running together count: points of another stroke (or of the same stroke, a good
// arc length away: a back-and-forth retrace) within `radius` whose direction is parallel within
// `parallel`. Strokes that cross, meet at a corner, or run side by side farther apart than radius
// (the two sides of a thin part) are left where they are.

#include <cstddef>
#include <string>

#include "surfacing/sketch/sketch.h"

namespace sketchsurf {

/// Options of consolidate_overdrawn(). Lengths are fractions of the sketch's bounding-box diagonal.
struct ConsolidateOptions {
  double radius = 0.01;    ///< passes of one curve lie within this distance of each other
  double parallel = 0.9;   ///< ... and run in the same (or the opposite) direction: |cos| of the
                           ///< angle between their tangents at least this
  int rounds = 3;          ///< rounds of pulling every point toward the passes near it
  double taper = 0.02;     ///< the pull fades in and out along a stroke over this arc length, so
                           ///< where a pass leaves the bundle it bends away smoothly
  bool valid(std::string* why) const;
};

/// What consolidate_overdrawn() did.
struct Consolidation {
  std::size_t points = 0;   ///< stroke points pulled onto a bundle's centre line
  std::size_t strokes = 0;  ///< strokes with at least one such point
  double max_shift = 0.0;   ///< largest move of a point, fraction of the diagonal
};

/// Pulls the passes of over-sketched curves onto their centre line, in place: in each round every
/// point of a non-ignored stroke moves, across its stroke's direction only (the spacing along the
/// stroke stays), toward the mean of itself and the nearest running-together point of each other
/// pass; the moves are smoothed along the stroke over `taper`. Ignored strokes neither move nor
/// attract. Expects strokes resampled to a spacing well below `radius` (the pipeline's prepare
/// step). Deterministic: the result does not depend on the order of the work.
/// @throws Error (Usage) for invalid options.
Consolidation consolidate_overdrawn(Sketch& sketch, const ConsolidateOptions& options = {});

}  // namespace sketchsurf
