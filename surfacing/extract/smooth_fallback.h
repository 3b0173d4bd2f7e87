#pragma once
// Smooth parts stay with the proxy where it fits their strokes better. A closed smooth part (a
// sphere, a torus, a bean) is one region, or several joined without a crease; the automatic proxy
// (VIPSS) is already a smooth surface through its strokes there, and one quartic per region,
// fitted in the least-squares sense, can only pass farther from them. The final surface is never
// less faithful to the strokes than the proxy on such a part.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "surfacing/mesh.h"
#include "surfacing/sketch/stroke_segments.h"

namespace sketchsurf {

/// Options for keep_smooth_proxy().
struct SmoothFallbackOptions {
  bool enabled = true;       ///< off: every part keeps its optimised positions
  double reach = 0.02;       ///< stroke points farther than this from the optimised surface
                             ///< (fraction of the diagonal) belong to no part and are not counted
  std::size_t min_points = 20;  ///< parts with fewer stroke points near them are left alone
  bool valid(std::string* why = nullptr) const;
};

/// What keep_smooth_proxy() did.
struct SmoothFallbackSummary {
  std::size_t parts = 0;      ///< connected parts without a crease vertex
  std::size_t reverted = 0;   ///< of those, the parts put back at their start (proxy) positions
  std::size_t vertices = 0;   ///< vertices put back
};

/// For every connected part of `mesh` (current, optimised positions) with no vertex flagged in
/// `sharp`: the root-mean-square distance of the stroke points near it to the part, at the current
/// positions and at `start` (#V x 3, the positions before optimisation: the proxy's); when the
/// start is closer, the part's vertices are put back at `start`. `diagonal` scales
/// options.reach. Deterministic; the strokes are those the surface was fitted to.
SmoothFallbackSummary keep_smooth_proxy(TriMesh& mesh, const Eigen::MatrixX3d& start,
                                        const std::vector<std::uint8_t>& sharp,
                                        const StrokeSegments& strokes, double diagonal,
                                        const SmoothFallbackOptions& options);

}  // namespace sketchsurf
