#pragma once
// The strokes as closest-point geometry: their points and segments as degenerate triangles
// (a, b, b), the form a ClosestFaceTree (surfacing/closest_face.h) answers "nearest stroke" with.

#include <Eigen/Core>

#include "surfacing/sketch/sketch.h"

namespace sketchsurf {

/// Points (#P x 3) and segments (#S x 3, degenerate triangles) of the strokes, and their box.
struct StrokeSegments {
  Eigen::MatrixX3d points;
  Eigen::MatrixX3i segments;
  BoundingBox box;
};

/// The non-ignored strokes of `sketch`, in order; a one-point stroke gives one degenerate segment.
/// With `mirrored` and a mirror plane, their mirror images follow (a mirrored surface is measured
/// against both halves).
StrokeSegments stroke_segments(const Sketch& sketch, bool mirrored);

}  // namespace sketchsurf
