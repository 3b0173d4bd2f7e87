#pragma once
// Normals that the strokes of a thin part give (a chair's leg, a lamp's pole, a torch's handle):
// where the strokes near a sample surround an axis, the surface's normal there points away from
// it. VIPSS chooses its normals for the smoothest surface, and where thin parts stand close it
// chooses those of one blob round them: a web fills the space between them (METHOD.md section 1).

#include <Eigen/Core>
#include <vector>

#include "surfacing/proxy/point_grid.h"
#include "surfacing/proxy/vipss.h"

namespace sketchsurf {

/// How a thin part is told, lengths on the unit-diagonal sketch.
struct PartSearch {
  double reach = 0.04;   ///< the stroke points within this of a sample are its part's ...
  int least = 12;        ///< ... when there are at least this many
  double gap = 90.0;     ///< they surround an axis (their principal direction through their
                         ///< centroid): seen along it, they leave no gap of this many degrees
  double round = 3.0;    ///< the part's section is round: its variances across the axis differ
                         ///< by at most this ratio (a plate's or a rim's do not)
  double rim = 0.6;      ///< the sample is on the part's side: at least this times the points'
                         ///< median distance from the axis
  double ahead = 0.03;   ///< a web in front of the sample: the point this far along its normal
  double clear = 0.7;    ///< ... has no stroke within this times `ahead` and is inside
  double between = 0.5;  ///< the web lies between parts when strokes lie ahead within this,
  double cone = 45.0;    ///< ... within this many degrees of the sample's normal
  unsigned threads = 0;  ///< worker threads (0 = all); never changes the result
};

/// Per sample: the normal its part gives, and where, and where a web lies in front of it.
struct PartNormals {
  Eigen::MatrixX3d normals;  ///< #n x 3 unit normals (zero where not known)
  std::vector<char> known;   ///< #n: the sample's strokes surround an axis, and that axis lies
                             ///< inside the surface (outside it, the place is concave)
  std::vector<char> web;     ///< #n: known, and the space in front of the sample, clear of
                             ///< strokes, is inside the surface
  std::vector<char> between;  ///< #n: web, with strokes ahead (another part): the web lies
                              ///< between two parts (not a bulge of the surface below a foot)
};

/// The normals of the thin parts at `samples` (#n x 3) from the stroke points near them
/// (`strokes` over `stroke_points`), judged against the surface s f = 0 (`scale` s as the proxy's
/// distance scale: s f > 0 outside).
PartNormals part_normals(const HermiteRbf& f, double scale, const Eigen::MatrixX3d& samples,
                         const Eigen::MatrixX3d& stroke_points, const PointGrid& strokes,
                         const PartSearch& search);

}  // namespace sketchsurf
