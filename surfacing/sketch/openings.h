#pragma once
// Open rims: the top of a cup, a vase's neck, a bathtub's inner rim. A designer draws the rim as a
// closed, flat loop and draws nothing across it; the proxy, being closed, caps it, and the surface
// comes out solid. A loop with no stroke across it and no stroke beyond it on one side, while the
// object's strokes lie on the other, is an opening: its stroke is marked as a boundary (paper
// App. D) so the surface is trimmed there. The same loop geometry tells the trim which side of a
// boundary loop is empty (trim.h).

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "surfacing/sketch/sketch.h"

namespace sketchsurf {

/// Options of find_openings() and stroke_loop(). Lengths are fractions of the loop's radius unless
/// said otherwise.
struct OpeningOptions {
  double closed_gap = 0.1;   ///< a stroke is closed when its ends are this close (fraction of its length)
  double min_size = 0.08;    ///< loops narrower than this fraction of the sketch's diagonal are no rims
  double flatness = 0.15;    ///< every loop point within this distance of the loop's plane
  double margin = 0.15;      ///< a point is across the loop when inside its outline by this much
  double thickness = 0.12;   ///< ... and within this distance of its plane (the disc the rim spans)
  double lowest_up = -0.5;   ///< sketches are y-up (Open Brush, CASSIE, VNS): a loop whose opening
                             ///< would face down more than this (the y of its unit normal) is a
                             ///< base or a sole the object stands on, not an opening
  bool valid(std::string* why) const;
};

/// A closed, nearly flat stroke loop: its plane (normal toward the open side once oriented),
/// centre, mean radius and outline in the plane's coordinates.
struct StrokeLoop {
  Plane plane;
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  Eigen::Vector3d u = Eigen::Vector3d::UnitX(), v = Eigen::Vector3d::UnitY();  ///< in-plane axes
  double radius = 0.0;
  std::vector<Eigen::Vector2d> outline;

  /// Height of `p` above the plane (along the normal).
  double height(const Eigen::Vector3d& p) const { return plane.signed_distance(p); }
  /// Whether `p` projects inside the outline, at least `margin` (sketch units) from it.
  bool encloses(const Eigen::Vector3d& p, double margin) const;
  /// Turns the normal around (the outline stays the same set of points).
  void flip();
};

/// The loop a stroke's points make, when they make one: ends within closed_gap of its length,
/// every point within flatness * radius of the best-fit plane. No size test. The normal is the
/// plane fit's, unoriented.
std::optional<StrokeLoop> stroke_loop(const std::vector<Eigen::Vector3d>& points,
                                      const OpeningOptions& options = {});

/// Counts of `points` inside `loop`'s outline (by options.margin * radius): across the disc
/// (|height| <= thickness * radius), above it and below it.
struct LoopSides {
  std::size_t across = 0, above = 0, below = 0;
};
LoopSides loop_sides(const StrokeLoop& loop, const std::vector<Eigen::Vector3d>& points,
                     const OpeningOptions& options = {});

/// One opening found by find_openings().
struct Opening {
  std::size_t stroke = 0;  ///< index into sketch.strokes
  std::int64_t id = -1;    ///< that stroke's id
  StrokeLoop loop;         ///< normal pointing out of the object, through the opening
};

/// The rims of `sketch`: strokes (not ignored, not boundary, at least min_size * diagonal across)
/// whose loop has no stroke point across it and none beyond it on one side, and the points of
/// other strokes inside its outline on the other side (the object the rim opens), that do not
/// face down (lowest_up) and that have no other such loop beyond them, over their outline (the
/// sections of an open cup under its rim). Deterministic; `sketch` should be resampled.
std::vector<Opening> find_openings(const Sketch& sketch, const OpeningOptions& options = {});

}  // namespace sketchsurf
