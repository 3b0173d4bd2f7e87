#pragma once
// Creases the strokes imply but do not draw. A stroke that turns a sharp corner crosses a crease
// there (a box's cross-section turns at each edge of the box). When the edge itself was never
// drawn, the corners of neighbouring strokes still line up along it: joined, they guide the
// segmentation's region borders onto the crease, where they would otherwise cost as much as
// anywhere else and a face's region may wrap round the edge.

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "surfacing/sketch/sketch.h"

namespace sketchsurf {

/// Options for crease_guides(). Lengths are fractions of the sketch's bounding-box diagonal.
struct CreaseGuideOptions {
  bool enabled = true;         ///< look for corners and join them
  double window = 0.02;        ///< arc length on each side of a point over which its turn is measured
  double min_turn = 55.0;      ///< degrees a corner turns at least over `window` on each side
  double max_turn = 150.0;     ///< degrees above which a turn is a hairpin (a retrace), not a corner
  double concentration = 0.75; ///< a corner turns at least this share of its turn within half the
                               ///< window too; a tight arc turns only half as much there
  double max_gap = 0.3;        ///< longest join between two corners
  double min_gap = 0.01;       ///< corners closer than this are one corner drawn twice, not joined
  double alignment = 20.0;     ///< degrees between a join and either corner's crease direction
  double same_way = 45.0;      ///< degrees within which two corners' apexes point the same way. A
                               ///< crease's corners all do; a stroke round a plate's thin side
                               ///< turns up and out at its top edge, down and out at its bottom
                               ///< edge. A corner joins its nearest same-way candidate on a side
                               ///< when it has one, its nearest candidate otherwise (180: nearest
                               ///< only)
  double fold_radius = 0.04;   ///< a join is kept where the proxy's normals within this distance of
                               ///< its middle part spread this far from their mean...
  double min_fold = 10.0;      ///< ...in degrees: a crease folds the surface, a face does not (two
                               ///< corners can line up across a flat face by chance)
  bool valid(std::string* why) const;
};

/// A sharp turn of a stroke: where it is, the direction of the crease it crosses (the normal of
/// the plane of the turn, unit, sign arbitrary) and the direction its tip points (the unit
/// difference of its incoming and outgoing directions, the same whichever way the stroke runs).
struct StrokeCorner {
  Eigen::Vector3d position;
  Eigen::Vector3d axis;
  Eigen::Vector3d apex;
  int stroke = -1;  ///< index into the sketch's strokes
};

/// The sharp corners of the sketch's non-ignored strokes (a closed stroke is followed round its
/// closing point). `diagonal` is the length the options' fractions refer to.
std::vector<StrokeCorner> stroke_corners(const Sketch& sketch, double diagonal,
                                         const CreaseGuideOptions& options = {});

/// Segments joining corners of different strokes that lie along each other's crease direction,
/// each corner to its nearest such corner on either side (nearest among those pointing the same
/// way when there are any: options.same_way), kept when the choice is mutual. Empty
/// when options.enabled is false. Throws Error (Usage) on invalid options.
std::vector<std::array<Eigen::Vector3d, 2>> crease_guides(const Sketch& sketch, double diagonal,
                                                          const CreaseGuideOptions& options = {});

/// The guides along which the surface given by its vertex `positions` and unit `normals` folds:
/// of the vertices within options.fold_radius of the middle 80% of a guide, at least 90% have
/// normals within options.alignment of perpendicular to it (the two faces of a crease both contain
/// its direction), and those normals spread at least options.min_fold degrees from their mean. `diagonal` as for crease_guides().
std::vector<std::array<Eigen::Vector3d, 2>> guides_on_folds(
    const std::vector<std::array<Eigen::Vector3d, 2>>& guides, const Eigen::MatrixX3d& positions,
    const Eigen::MatrixX3d& normals, double diagonal, const CreaseGuideOptions& options = {});

}  // namespace sketchsurf
