#pragma once
// Scribbles: strokes that wind round and round over an area (a painterly fill, shading, a
// scribbled mass) instead of drawing a curve on a surface. A sketch made mostly of them depicts
// no surface the method can fit: whatever is surfaced is a blob around the ink. The measure is
// per stroke and needs no other stroke, so the scene can be refused before any surfacing work.

#include "surfacing/sketch/sketch.h"

namespace sketchsurf {

/// The ink a stroke lays down without retracing itself, in units of its own extent: the cells
/// (cubes of 1/16 of its bounding-box diagonal) its polyline passes through, over 16. A straight
/// stroke gives about 1.2, a circle about 2.8 (also when retraced three times with a wobble), a
/// scribble that sweeps over its area 5 or more. 0 for a stroke of fewer than 2 distinct points.
double stroke_fill(const Stroke& stroke);

/// Share of the sketch's ink (stroke length, strokes not ignored) in strokes whose
/// stroke_fill() exceeds `fill`; 0 for a sketch without ink.
double scribbled_share(const Sketch& sketch, double fill);

}  // namespace sketchsurf
