#pragma once
// What the drawing aids do to a finished stroke, as plain functions on strokes (the session
// applies them in finish order: straight line, smoothing, over-sketch or end snapping):
// - straighten: the straight segment between the stroke's ends;
// - smooth_stroke: Kuhn 2009 §4.3's iterative smoothing (each inner point moved to the
//   Catmull-Rom midpoint of its neighbours, ends fixed);
// - snap_ends: a stroke end near another stroke is moved onto it, so that curve networks close;
// - oversketch: a stroke drawn along part of an existing one replaces that part (Kuhn §3.4's
//   deform, with §4.3's blending function at its ends).

#include <cstddef>
#include <optional>
#include <vector>

#include "surfacing/sketch/sketch.h"

namespace sketchsurf::session {

/// Replaces the points of `stroke` by the same number of points evenly spaced on the segment
/// from its first point to its last (ends unchanged, attributes kept per point).
void straighten(Stroke& stroke);

/// `iterations` rounds of Kuhn's iterative smoothing (2009, §4.3): every point but the ends moves
/// half way towards the Catmull-Rom midpoint (tension 1/2) of p[i-2], p[i-1], p[i+1], p[i+2],
/// i.e. (-p[i-2] + 9 p[i-1] + 9 p[i+1] - p[i+2]) / 16, all from the previous round (half way: a
/// full step would amplify a zig-zag); beyond an end the missing point is the end's point
/// reflection (2 p0 - p1). Noise fades in the first rounds, spacing evens out; evenly spaced
/// points on a line do not move. Attributes are kept.
void smooth_stroke(Stroke& stroke, int iterations);

/// Where an end of a stroke was snapped to.
struct EndSnap {
  bool snapped = false;
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  std::optional<std::size_t> stroke;  ///< index into `others`; none: the stroke's own other
                                      ///< end or the mirror plane
};

/// Snaps the ends of `stroke` that lie within `radius` (sketch units) of a stroke of `others`:
/// an end on `plane` (the drawing plane with its guide on) to the nearest point where a stroke
/// crosses the plane, so that the stroke stays on it; otherwise to the nearest end of a stroke
/// (corners meet at a point), else to the nearest point of a polyline; else, within the radius
/// of the `mirror` plane, onto it (the stroke then meets its mirror image); an end within the
/// radius of the stroke's own other end (on a stroke longer than 4 radii) closes the loop. The
/// end is set to the target exactly; the displacement fades out along the stroke over 3 radii
/// (half cosine), so no kink appears. Returns what the start and the end snapped to.
std::pair<EndSnap, EndSnap> snap_ends(Stroke& stroke, const std::vector<Stroke>& others, double radius,
                                      const std::optional<Plane>& plane = std::nullopt,
                                      const std::optional<Plane>& mirror = std::nullopt);

/// Options of the over-sketch.
struct OversketchOptions {
  double end_radius = 0.0;    ///< both ends of the new stroke within this of the old one (sketch units)
  double max_distance = 0.0;  ///< and every point of it within this (sketch units)
  double blend = 0.15;        ///< fraction of the covered part blended at each end (Kuhn's d, in [0, 0.5])
};

/// The index in `strokes` of the stroke that `style` over-sketches (both ends within
/// end_radius, every point within max_distance, covering more than 2 end radii of it; the
/// nearest on average when several qualify), or none.
std::optional<std::size_t> oversketch_target(const std::vector<Stroke>& strokes, const Stroke& style,
                                             const OversketchOptions& options);

/// `target` with the part between the points nearest to the ends of `style` replaced by `style`
/// (Kuhn 2009 §3.4 and Eq. 4.4 with b_max = 1): with u the arc-length parameter of `style` and
/// base(u) the matching point of the covered part, the new points are base + b(u) (style - base),
/// b rising from 0 to 1 over the first `blend` of u and falling back over the last; between them
/// the new points are the style's exactly. Points outside the covered part are kept bit for bit,
/// as are id, flags, width, colour. The new points take the style's orientations and pressures
/// and timestamps interpolated along the covered part (when both strokes have them).
Stroke oversketch(const Stroke& target, const Stroke& style, double blend);

/// Distance from `p` to the polyline of `stroke` (its point for a one-point stroke; infinity for
/// none).
double distance_to_stroke(const Eigen::Vector3d& p, const Stroke& stroke);

}  // namespace sketchsurf::session
