#pragma once
// Saddles of the proxy's distance-scaled VIPSS function where its zero set has the wrong topology
// between strokes: windows through thin double walls, to close, gaps that strokes cross, to
// bridge, and necks that no stroke crosses, to cut (METHOD.md section 1: the proxy should have the
// shape the strokes depict).

#include <Eigen/Core>
#include <vector>

#include "surfacing/proxy/point_grid.h"
#include "surfacing/proxy/vipss.h"
#include "surfacing/sketch/sketch.h"

namespace sketchsurf {

/// A bump that lowers the field within an ellipsoid: depth * (1 - q)^3, q the squared ellipsoidal
/// radius (0 for q >= 1). Lowering a function that is positive outside puts material there.
struct Bump {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  ///< columns: the ellipsoid's axes
  Eigen::Vector3d radii = Eigen::Vector3d::Ones();
  double depth = 0.0;  ///< the value at the centre, distance units

  /// The bump at p; its gradient is added to `gradient` (if given).
  double value(const Eigen::Vector3d& p, Eigen::Vector3d* gradient) const;
};

/// The sum of `bumps` at p (how far they lower the field there); their gradients are added to
/// `gradient` (if given).
double bumps_value(const std::vector<Bump>& bumps, const Eigen::Vector3d& p,
                   Eigen::Vector3d* gradient);

/// Where and how finely the saddles are searched, all lengths on the unit-diagonal sketch.
struct SaddleSearch {
  double near = 0.1;        ///< grid points farther than this from every stroke are not searched
  double step = 0.02;       ///< grid spacing h
  double window_most = 0.025;  ///< windows: saddle values in (-window_aliased, window_most);
                               ///< 0 = none
  double window_undrawn_most = 0.0;  ///< wider windows: saddle values in [window_most, this)
                                    ///< where no stroke depicts an opening; 0 = none
  double window_aliased = 0.0;  ///< a window saddle just inside the surface (the double wall's
                                ///< inside layer thinner than the polygonisation's cells there)
                                ///< opens in the polygonised surface all the same
  double across = 0.04;     ///< a window's membrane thickness
  double window_reach = 0.6;   ///< a window's open region is flooded this far from its saddle
  int window_points = 400;     ///< at most this many membrane bumps per window
  double bridge_most = 0.025;  ///< bridges: saddle values in (0, bridge_most); 0 = none
  double neck_most = 0.0;      ///< necks: saddle values in (-neck_most, 0); 0 = none
};

/// Whether the strokes of `unit` within `reach` of `centre` depict an opening along `axis` there:
/// one turns at least 3.5 radians round the axis within that reach (a hole's drawn rim, a
/// handle's C, a torus's inner circle), or those running within 45 degrees of the axis stand in 7
/// or more of 12 sectors round it (a bore drawn by its wall's lines). The strokes that frame a face
/// or a wall pass by a point of it.
bool opening_drawn(const Eigen::Vector3d& centre, const Eigen::Vector3d& axis, double reach,
                   const Sketch& unit);

/// What find_saddles() found, as bumps to lower the field by.
struct Saddles {
  std::vector<Bump> windows;  ///< membranes over windows through thin double walls
  std::vector<Bump> undrawn;  ///< membranes over wider windows that no stroke depicts
  std::vector<Bump> thin;     ///< membranes over the thin strips round windows whose saddle lies
                              ///< just inside the surface (not their own bumps: in `windows`)
  std::vector<Bump> tight;    ///< window bumps over window-shaped saddles below window_most
                              ///< whose space across does not open (open_across: a window
                              ///< beside another face, or a gap between two faces) and round
                              ///< which no stroke depicts an opening (opening_drawn())
  std::vector<Bump> bridges;  ///< connections across gaps that strokes cross
  std::vector<Bump> necks;    ///< cuts through thin connections that no stroke crosses
};

/// The saddles of s f (s: the factor that makes f a distance to first order, positive outside)
/// with a small value, found by Newton's method from the grid points near the strokes
/// where the gradient norm is a local minimum below 0.8 (a distance has gradient norm 1 but at
/// critical points):
/// - a window: two negative curvatures (the window's plane) and one positive (across it), as
///   between two walls whose inside layer pinches out where no stroke holds it. Its open region,
///   the points whose minimum of s f across the wall is positive and below window_most, is
///   flooded from the saddle over the grid, near the saddle's plane, and each point gets a small
///   bump: together a membrane about as thick as the walls (the slot of a thin plate is long and
///   flat-bottomed, not an ellipse). A window saddle just inside the surface (value above
///   -window_aliased: the inside layer thinner than the polygonisation's cells) counts too: the
///   polygonised surface opens there all the same. Its thin strip, the points whose minimum
///   across is above -window_aliased (the space across measured from that minimum), is flooded
///   likewise into `thin`: the polygonisation can open anywhere along it. A wider window (value
///   in [window_most, window_undrawn_most)) is one too where it lies in a cell of the strokes and
///   no stroke depicts an opening: within twice the saddle's distance to the nearest stroke (at
///   most 2.5 times its value: the hole spans the gap between them), strokes stand all round the
///   line through it along its across axis, none winds round that line (a hole's rim, a handle's
///   C) and those running along it do not stand all round it (a bore drawn by its wall's lines).
///   Those go to `undrawn`, their region flooded up to the saddle's value.
/// - a bridge: one negative curvature (along the gap) and two positive, as between two parts of
///   the surface that nearly touch, kept only when a stroke crosses the gap's mid-plane near the
///   saddle outside the surface (the strokes depict a connection there: a mug's handle meeting
///   its wall). Its bump is a ball that reaches the crossing strokes.
/// - a neck (searched from the grid points inside the surface, value in (-neck_most, 0)): one
///   negative curvature (along the neck) and two positive, as in a thin connection between two
///   parts, kept only when no stroke crosses the neck's mid-plane within twice its radius or 2 h
///   (nothing depicts the connection: two parts drawn apart that VIPSS merged). Its bump raises
///   the field over a thin disc across the neck.
/// `lowered`: bumps already lowering s f (the saddles are those of s f less their sum: a window
/// left open round a membrane that could not follow a curved wall). `unit` is the unit-diagonal
/// sketch whose samples made f; `strokes` a grid over points along its strokes; `box` the search
/// box.
Saddles find_saddles(const HermiteRbf& f, double scale, const std::vector<Bump>& lowered,
                     const Sketch& unit, const PointGrid& strokes, const BoundingBox& box,
                     const SaddleSearch& search, unsigned threads);

}  // namespace sketchsurf
