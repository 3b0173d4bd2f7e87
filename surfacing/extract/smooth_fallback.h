#pragma once
// The proxy where the region models cannot follow the strokes. One quartic per region, fitted in
// the least-squares sense, is exact on planes, quadrics and the other shapes of a CAD-like sketch,
// but on a free-form smooth shape (blended blobs, a head, a sphere drawn by hand) it passes farther
// from its strokes than the automatic proxy (VIPSS, a smooth surface through them) and bulges
// between them. Two safeguards, both comparing distances to the strokes:
// - before the solve, per region: a region whose model lies farther from its strokes than the
//   proxy, and which the model would only reshape in detail (not move past a corner the proxy
//   rounds or a bulge it makes), is not projected; its vertices are held at the proxy
//   (E_attract) and the Laplacian joins them smoothly to the regions around (regions_at_proxy).
//   A plane is always projected onto: a face the strokes depict flat stays flat, however the
//   proxy bulges between them;
// - after the solve, per connected part without a crease (a sphere, a torus, a bean): the
//   Laplacian's pull shrinks a projected part slightly off its strokes; when the proxy passes closer
//   to them, the part goes back to the proxy (keep_smooth_proxy).
// The final surface is thus never less faithful to the strokes than the proxy on such parts.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "surfacing/extract/optimize.h"
#include "surfacing/extract/seams.h"
#include "surfacing/mesh.h"
#include "surfacing/segment/implicit.h"
#include "surfacing/sketch/stroke_segments.h"

namespace sketchsurf {

/// Options for regions_at_proxy() and keep_smooth_proxy().
struct SmoothFallbackOptions {
  bool enabled = true;       ///< off: every region is projected and every part keeps its
                             ///< optimised positions
  double reach = 0.02;       ///< stroke points farther than this from the surface belong to no
                             ///< region or part; a model farther than this from a point counts as
                             ///< this far (fractions of the diagonal)
  std::size_t min_points = 20;  ///< regions and parts with fewer stroke points are left alone
  double margin = 0.05;      ///< the proxy counts as closer to a region's stroke points unless its
                             ///< mean squared distance exceeds the model's by more than this share:
                             ///< a model that fits them only about as well buys nothing at the
                             ///< strokes and may bulge between them, where the proxy is smooth
  double agree = 0.02;       ///< a region stays projected when the projection onto its model moves
                             ///< 5% of its vertices farther than this (fraction of the diagonal):
                             ///< there the model corrects the proxy's shape, not its detail
  bool hold_curved = false;  ///< every region that is not a plane stays at the proxy, whatever its
                             ///< model (margin and agree unused): the proxy is already the surface
                             ///< the strokes depict between them (lofted through their sections),
                             ///< where a model fitted to those few strokes only bulges
  bool valid(std::string* why = nullptr) const;
};

/// What regions_at_proxy() and keep_smooth_proxy() did.
struct SmoothFallbackSummary {
  std::size_t regions = 0;    ///< regions with at least min_points stroke points
  std::size_t kept = 0;       ///< of those, the regions kept at the proxy
  std::size_t held = 0;       ///< vertices with a kept region among their labels
  std::size_t parts = 0;      ///< connected parts without a crease vertex
  std::size_t reverted = 0;   ///< of those, the parts put back at their start (proxy) positions
  std::size_t vertices = 0;   ///< vertices put back
};

/// Per region (index into `models`): whether it stays at the proxy. The stroke points within
/// options.reach * diagonal of `mesh` (the seamed proxy, before optimisation) belong to the region
/// of their closest face; a region stays when the mean squared distance of its points to the
/// proxy is below (1 + options.margin) times their mean squared first-order distance to its
/// model (each capped at the reach), its model is not a plane (degree 1), and the projection that
/// starts the solve (project_vertices() with `energy`'s steps) moves at most 5% of its own
/// vertices farther than options.agree * diagonal; with options.hold_curved, when it has enough
/// points and its model is not a plane. Fills summary->regions, kept and held.
/// Deterministic; `strokes` are those the surface is fitted to (extract() leaves out an open
/// surface's boundary strokes: its border is attracted to them either way).
std::vector<char> regions_at_proxy(const LabeledMesh& mesh, const std::vector<ImplicitModel>& models,
                                   const StrokeSegments& strokes, double diagonal,
                                   const SmoothFallbackOptions& options, const MeshEnergyOptions& energy,
                                   SmoothFallbackSummary* summary = nullptr);

/// For every connected part of `mesh` (current, optimised positions) with no vertex flagged in
/// `sharp`: the root-mean-square distance of the stroke points near it to the part, at the current
/// positions and at `start` (#V x 3, the positions before optimisation: the proxy's); when the
/// start is closer, or when every vertex of the part is flagged in `held` (all its regions kept at
/// the proxy: nothing was fitted, and the Laplacian only shrinks it), the part's vertices are put
/// back at `start`. `diagonal` scales
/// options.reach. Fills summary->parts, reverted and vertices. Deterministic; the strokes are
/// those the surface was fitted to.
void keep_smooth_proxy(TriMesh& mesh, const Eigen::MatrixX3d& start, const std::vector<std::uint8_t>& sharp,
                       const std::vector<char>& held, const StrokeSegments& strokes, double diagonal,
                       const SmoothFallbackOptions& options, SmoothFallbackSummary* summary = nullptr);

}  // namespace sketchsurf
