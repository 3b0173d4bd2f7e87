#pragma once
// Whether a smoothed zero set leaves the strokes by rounding the shape off or by ignoring their
// tremor. A hand's tremor moves each stroke off the surface on its own, so a zero set smooth
// enough to ignore it leaves neighbouring strokes on either side at random; a zero set smoothed
// past the shape (a car's shoulder, a box's edge rounded off) leaves every stroke near the
// rounding on the same side. The signed misfits of nearby points of different strokes tell the
// two apart: uncorrelated for tremor, correlated for rounding.

#include <Eigen/Core>
#include <vector>

#include "surfacing/proxy/vipss.h"

namespace sketchsurf {

/// Correlation, over the points of `points` that have points of other strokes within `reach`,
/// between a point's signed misfit to the zero set of f (f / |grad f|, a first-order distance)
/// and the mean misfit of those other strokes' points (weighted (1 - (r/reach)^2)^2). In [-1, 1]:
/// near 0 or below where f ignores the strokes' own wobbles, towards 1 where it rounds off a
/// shape the strokes share. `stroke_of` (#points) names each point's stroke. 0 when no point has
/// another stroke's within `reach`. Deterministic whatever `threads` (0 = all).
double shared_misfit(const HermiteRbf& f, const Eigen::MatrixX3d& points,
                     const std::vector<int>& stroke_of, double reach, unsigned threads = 0);

}  // namespace sketchsurf
