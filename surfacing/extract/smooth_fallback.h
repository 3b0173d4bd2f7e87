#pragma once
// The proxy where the region models cannot follow the strokes. One quartic per region, fitted in
// the least-squares sense, is exact on planes, quadrics and the other shapes of a CAD-like sketch,
// but on a free-form smooth shape (blended blobs, a head, a sphere drawn by hand) it passes farther
// from its strokes than the automatic proxy (VIPSS, a smooth surface through them) and bulges
// between them. Three safeguards, each comparing distances to the strokes:
// - before the solve, per region: a region whose model lies farther from its strokes than the
//   proxy, and which the model would only reshape in detail (not move past a corner the proxy
//   rounds or a bulge it makes), is not projected; its vertices are held at the proxy
//   (E_attract) and the Laplacian joins them smoothly to the regions around (regions_at_proxy).
//   A plane is always projected onto: a face the strokes depict flat stays flat, however the
//   proxy bulges between them;
// - before the solve, per region: a doubly curved region (a blob, a head, a belly) whose model is
//   nearer its strokes, but only a little, is projected and also pulled gently back toward the
//   proxy (E_attract with a small weight; regions_at_proxy). Both estimate the same surface from
//   the same strokes, and at the strokes the model wins by fitting their noise; between them, on
//   such a shape, the proxy's smooth interpolant is the better guess, where a model right at its
//   strokes can bulge. A developable region (a flat face, a cylinder, a leg) is not pulled: there
//   the proxy is what bulges between the strokes or inflates a thin part, and the model is right;
//   nor is a region the model reshapes (as for holding);
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
  bool rounded = false;      ///< the proxy follows its strokes closely rather than smoothly (VIPSS
                             ///< with less smoothing where more rounds the shape off them,
                             ///< ProxyReport::rounded; set by the pipeline): between the strokes it
                             ///< sags and bulges by the tremor it follows. Then a region whose model
                             ///< is of degree rounded_degree or less (a plane, a cylinder, a cone)
                             ///< is held only when the proxy is clearly nearer its strokes
                             ///< (rounded_margin) and never pulled toward it, and a held region
                             ///< stays held even where its model would reshape it (agree unused)
  double rounded_margin = -0.2;  ///< ... the margin then: held when the proxy's mean squared
                                 ///< distance is below 0.8 times the model's (a quadric that fits
                                 ///< about as well as a nearly interpolating surface is the shape)
  int rounded_degree = 2;    ///< ... for models of at most this degree (a quartic that fits about as
                             ///< well follows the tremor too)
  double agree = 0.02;       ///< a region stays projected when the projection onto its model moves
                             ///< 5% of its vertices farther than this (fraction of the diagonal):
                             ///< there the model corrects the proxy's shape, not its detail
  double pull_ratio = 1.25;  ///< a projected region whose proxy's mean squared distance to its
                             ///< stroke points is below this many times its model's is pulled
                             ///< toward the proxy when doubly curved (1 = never)
  double pull_weight = 0.03;  ///< the pull: E_attract to the proxy position, this share of
                              ///< attract_weight (0.03 of 100 against E_project's 1: a vertex
                              ///< settles about three quarters of the way back to the proxy)
  double pull_curvature = 2.0;  ///< doubly curved: the median over the region's vertices of its
                                ///< model's smaller principal curvature, times the diagonal, at
                                ///< least this (a sphere of half the diagonal's radius: 4; a
                                ///< cylinder, a plane: 0)
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
  std::size_t pulled = 0;     ///< of the regions, those projected and pulled toward the proxy
  std::size_t parts = 0;      ///< connected parts without a crease vertex
  std::size_t reverted = 0;   ///< of those, the parts put back at their start (proxy) positions
  std::size_t vertices = 0;   ///< vertices put back
};

/// What regions_at_proxy() decides for a region.
inline constexpr char kRegionProjected = 0;  ///< projected onto its model
inline constexpr char kRegionHeld = 1;       ///< held at the proxy
inline constexpr char kRegionPulled = 2;     ///< projected, and pulled toward the proxy

/// Per region (index into `models`): kRegionHeld when it stays at the proxy. The stroke points within
/// options.reach * diagonal of `mesh` (the seamed proxy, before optimisation) belong to the region
/// of their closest face; a region stays when the mean squared distance of its points to the
/// proxy is below (1 + options.margin) times their mean squared first-order distance to its
/// model (each capped at the reach; with options.rounded, (1 + options.rounded_margin) times for a
/// model of at most options.rounded_degree), its model is not a plane (degree 1), and the
/// projection that starts the solve (project_vertices() with `energy`'s steps) moves at most 5% of
/// its own vertices farther than options.agree * diagonal (not asked with options.rounded); with
/// options.hold_curved, when it has enough
/// points and its model is not a plane. kRegionPulled for a region with enough
/// points, a model that is not a plane and not held (nor of at most options.rounded_degree with
/// options.rounded), a proxy mean squared distance below
/// options.pull_ratio times the model's, a model doubly curved at the region's own vertices
/// (options.pull_curvature) and the same bound on the projection's moves (a proxy dented by
/// scribbles, 3% off a smooth body, is not pulled toward); kRegionProjected otherwise. Fills
/// summary->regions, kept, held and pulled.
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
