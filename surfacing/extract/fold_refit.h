#pragma once
// A fold's region refitted at a lower degree. A fold the fills leave (unfold.h) is most often one
// region's model running on past the surface it meets: a quartic fitted to a shoe's flat sole
// curls up inside the shoe's sides, a dress's hem cap flares out through the skirt. Nearly all of
// the crossing triangles then belong to that one region, and a model of lower degree, fitted to
// the same stroke points, cannot turn back on itself that way (a plane, a quadric).

#include <Eigen/Core>
#include <array>
#include <vector>

#include "surfacing/extract/seams.h"
#include "surfacing/segment/implicit.h"

namespace sketchsurf {

/// The regions of `mesh` whose vertices lie on at least `share` of the triangles of `folds`
/// (crossing face pairs, as unfold() leaves them), in index order; with a share just above 0,
/// every region on any of them.
std::vector<int> fold_regions(const LabeledMesh& mesh, const std::vector<std::array<int, 2>>& folds,
                              double share);

/// What refit_regions() fits each region to: the stroke points of `strokes` whose closest face of
/// `mesh` at `positions` (#V x 3) lies in the region, within `reach` (sketch units), and the
/// region's own vertices there with their area-weighted normals.
struct RegionSamples {
  std::vector<int> regions;                 ///< the regions, as given
  std::vector<Eigen::MatrixX3d> points;     ///< per region: its stroke points
  std::vector<Eigen::MatrixX3d> vertices;   ///< per region: its own vertices (one label) ...
  std::vector<Eigen::MatrixX3d> normals;    ///< ... and their unit normals
};
RegionSamples region_samples(const LabeledMesh& mesh, const Eigen::MatrixX3d& positions,
                             const std::vector<int>& regions, const Eigen::MatrixX3d& strokes, double reach);

/// `models` with each region of `samples` whose degree is above `degree` fitted again at `degree`
/// (fit_implicit(), the segmentation's default options with `diagonal` as length unit) to its
/// samples. A region with fewer than `least` stroke points keeps its model. `refitted` (if given)
/// receives how many models changed.
std::vector<ImplicitModel> refit_regions(const std::vector<ImplicitModel>& models, const RegionSamples& samples,
                                         int degree, double diagonal, std::size_t least,
                                         std::size_t* refitted = nullptr);

}  // namespace sketchsurf
