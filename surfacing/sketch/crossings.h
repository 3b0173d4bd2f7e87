#pragma once
// Strokes that meet no other stroke. A surface sketch is a network: its outlines and sections cross
// or end on one another. Hatching, shading lines and writing lay strokes side by side, each on its
// own, and whatever is surfaced through them is a blob around the ink. The measure needs no
// surface, so such a scene can be refused before any surfacing work; unlike the result's distance
// to the strokes it does not change from one run to the next.

#include <cmath>
#include <cstddef>

#include "surfacing/sketch/sketch.h"

namespace sketchsurf {

/// Share of the sketch's ink (stroke length, strokes not ignored) in strokes that meet no other
/// stroke crosswise: no point of theirs lies within `reach` of a point of another stroke whose
/// direction there differs from theirs by more than `angle` (radians; strokes drawn over each
/// other, side by side, do not meet). Strokes are resampled every reach / 2. 0 for a sketch without
/// ink.
double unmet_share(const Sketch& sketch, double reach, double angle);

/// How far apart strokes pass where they cross: the median, over the pairs of strokes that come
/// within `reach` of each other crosswise (directions there more than `angle` radians apart,
/// neither stroke ending there, and neither turning more than `bend` radians within `reach` along
/// it), of the pair's closest distance (same units as the sketch). A curve network drawn on a
/// surface (a modelling tool's, a mesh's feature curves and sections) crosses exactly: its gaps are
/// rounding; strokes drawn by hand pass each other by the hand's tremor. Where a network's curve
/// turns at a crease, its polyline cuts the corner and passes the curve across it by the
/// polyline's chord, not by any tremor: `bend` leaves such crossings out. Negative when fewer than
/// `least` pairs cross.
double crossing_gap(const Sketch& sketch, double reach, double angle, std::size_t least,
                    double bend = M_PI);

}  // namespace sketchsurf
