#pragma once
// The drawn outline of each flat region: where its surface ends. A proxy rounds a
// sharp rim (a disc's edge, a wedge's acute end) into a bulge past the rim stroke; the part of
// the bulge that takes the flat face's label would otherwise be projected onto the face's plane
// beyond the rim, a flange no stroke asks for. Private to the extract room.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "surfacing/extract/seams.h"
#include "surfacing/segment/implicit.h"
#include "surfacing/sketch/stroke_segments.h"

namespace sketchsurf {

/// How a flat region's outline is found and used, lengths as fractions of the sketch's diagonal.
struct OutlineOptions {
  double tolerance = 0.01;  ///< a stroke segment lies on a surface when both its ends lie this close
  double flat_share = 0.7;  ///< a region is flat when this share of the strokes on its surface
                            ///< lie that close to one plane, where its surface runs along the
                            ///< plane (within `angle`)
  double reach = 0.02;      ///< a point of the outline is drawn when such a segment passes this close
  double drawn_share = 0.8; ///< an edge of the outline is drawn when this share of it is
  double angle = 20.0;      ///< degrees: a surface runs along a plane where its normal is within
                            ///< this of the plane's (a flange lies in the plane; a curved part
                            ///< of the region may cross it); only such vertices are pulled back
  double margin = 0.015;    ///< a vertex is pulled back only from farther outside than this;
                            ///< 0 = outlines off
  bool valid(std::string* why) const;
};

/// A plane and the convex hull, in it, of the strokes that lie on it, with per hull edge whether
/// strokes run along it. The hull is conservative: a concave face's notch lies inside it; an edge
/// that no stroke draws (a face drawn by two of its sides only) limits nothing.
struct PlaneOutline {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  ///< a point of the plane
  Eigen::Vector3d u = Eigen::Vector3d::UnitX(), v = Eigen::Vector3d::UnitY();  ///< in-plane axes
  std::vector<Eigen::Vector2d> hull;  ///< counter-clockwise, in (u, v) coordinates
  std::vector<char> drawn;            ///< edge i runs from hull[i] to hull[i + 1] (cyclic)
  double near = 0.0;                  ///< only points this close to the plane are pulled back,
  double least_cosine = 1.0;          ///< where their surface's normal is this close to the plane's

  /// The point of the outline closest to x's projection onto the plane, when x lies within `near`
  /// of the plane, its surface runs along the plane there (not across it), and that projection lies
  /// farther than `margin` outside it across drawn edges only (an edge, or a corner between two
  /// drawn edges); nothing otherwise.
  /// `normal`: the region's surface normal at x (any length; its sign does not matter).
  std::optional<Eigen::Vector3d> pull_back(const Eigen::Vector3d& x, const Eigen::Vector3d& normal,
                                           double margin) const;
};

/// Per model: the outlines of its region when the region is flat, none otherwise. A region's
/// strokes are the stroke segments on its model's surface whose nearest face of `mesh` (the
/// labelled proxy) is the region's; it is flat when options.flat_share of them lie on one plane
/// (the best of planes through three of them, refit to its inliers) where the model's surface
/// runs along that plane. A flat region gets a second outline on a plane parallel to the first,
/// farther than twice the tolerance from it, when at least three of its other strokes lie on that
/// one (a model whose zero set is a slab: a thin plate's two faces). Each plane's outline spans
/// every stroke segment on it. `diagonal` scales the options' lengths; the result does not depend
/// on anything but the inputs.
std::vector<std::vector<PlaneOutline>> plane_outlines(const LabeledMesh& mesh,
                                                      const std::vector<ImplicitModel>& models,
                                                      const StrokeSegments& strokes, double diagonal,
                                                      const OutlineOptions& options);

}  // namespace sketchsurf
