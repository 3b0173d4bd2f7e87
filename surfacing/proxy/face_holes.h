#pragma once
// Holes that a face drawn in cuts through the proxy where its surface dips through the face (a
// glass's thin foot whose top comes down below its drawn bottom between the strokes across it):
// the strokes draw a face there, not an opening (METHOD.md section 1: the proxy should have the
// shape the strokes depict).

#include <Eigen/Core>
#include <cstddef>
#include <functional>
#include <vector>

#include "surfacing/proxy/point_grid.h"
#include "surfacing/proxy/saddles.h"
#include "surfacing/sketch/sketch.h"

namespace sketchsurf {

/// Where face_holes() looks and how thick it closes, lengths on the unit-diagonal sketch.
struct FaceHoleSearch {
  double step = 0.01;       ///< grid spacing h over the face (the polygonisation's cell)
  double thickness = 0.03;  ///< the membranes' reach inside the face
};

/// What face_holes() found.
struct FaceHoles {
  std::size_t holes = 0;        ///< holes to close
  std::vector<Bump> membranes;  ///< bumps that close them, to lower the field by
};

/// The holes through `face` (its normal pointing out of the surface) in the surface g = 0 (g < 0
/// inside; the surface cut on the face): on a grid of spacing h over the face within `extent`
/// (the strokes' box), half a cell inside the face, the points where g >= 0 that the points
/// where g < 0, grown by two grid points, enclose (4-connected; those connected to the grid's
/// edge are the space round the surface; the growth closes a rim thinner than a cell round its
/// hole). A hole is its enclosed points and the outside points within two of them. It is left
/// open where the strokes depict an opening round its centre (opening_drawn(), within twice the
/// distance to the nearest stroke of `strokes`): a plate's drawn hole, a bore. The others get a
/// membrane on the face: a bump at each point of the hole, 1.5 h wide and `thickness` deep across
/// the face, lowering g by twice (g there + h) at its centre.
FaceHoles face_holes(const std::function<double(const Eigen::Vector3d&)>& g, const Plane& face,
                     const BoundingBox& extent, const Sketch& unit, const PointGrid& strokes,
                     const FaceHoleSearch& search, unsigned threads);

}  // namespace sketchsurf
