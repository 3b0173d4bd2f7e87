#pragma once
// The sketch data model: strokes with their attributes and annotations, and the sketch around them.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace sketchsurf {

/// One stroke: a polyline with optional per-point attributes. Per-point attribute vectors are
/// either empty (attribute absent) or exactly as long as `points`.
struct Stroke {
  std::vector<Eigen::Vector3d> points;            ///< positions, in the sketch's units
  std::vector<Eigen::Quaterniond> orientations;   ///< controller orientation per point (optional)
  std::vector<float> pressures;                   ///< pen pressure in [0, 1] per point (optional)
  std::vector<std::uint32_t> timestamps_ms;       ///< capture time per point, milliseconds (optional)
  double width = 0.0;                             ///< brush width, sketch units (0 = unknown)
  std::array<float, 4> color{0.f, 0.f, 0.f, 1.f}; ///< RGBA in [0, 1], gamma space
  std::string brush;                              ///< brush identifier (Open Brush GUID), may be empty
  std::int64_t id = -1;                           ///< stable identifier; -1 = unassigned
  std::uint32_t layer = 0;                        ///< index of the source layer
  bool boundary = false;  ///< marks the edge of an open surface (paper App. D)
  bool ignored = false;   ///< internal / skeletal stroke that the surface must not follow (§6.3)

  std::size_t size() const { return points.size(); }
  /// Sum of segment lengths.
  double length() const;
  /// True when every per-point attribute vector is empty or as long as `points`.
  bool attributes_consistent() const;
};

/// A plane n . x + d = 0 with unit normal n.
struct Plane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();
  double offset = 0.0;
  double signed_distance(const Eigen::Vector3d& p) const { return normal.dot(p) + offset; }
  Eigen::Vector3d reflect(const Eigen::Vector3d& p) const {
    return p - 2.0 * signed_distance(p) * normal;
  }
};

/// An n-fold rotational pattern: every stroke drawn is repeated `count` times about the axis
/// through `center` along `axis`, 360/count degrees apart (Kuhn 2009 Fig. 43; Open Brush's
/// multi-mirror). Stored with the sketch for the studio; the surfacer does not use it.
struct RotationPattern {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  ///< a point on the axis
  Eigen::Vector3d axis = Eigen::Vector3d::UnitY();   ///< the axis direction, unit
  int count = 2;                                     ///< copies, the stroke drawn included, >= 2
};

/// Axis-aligned bounding box; empty when min > max.
struct BoundingBox {
  Eigen::Vector3d min = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d max = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());
  bool empty() const { return (min.array() > max.array()).any(); }
  void extend(const Eigen::Vector3d& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  /// Length of the diagonal; 0 for an empty box.
  double diagonal() const { return empty() ? 0.0 : (max - min).norm(); }
};

/// A whole sketch.
struct Sketch {
  std::vector<Stroke> strokes;
  std::optional<Plane> mirror;  ///< symmetry plane, if the sketch is symmetric
  std::optional<RotationPattern> rotation;  ///< rotational pattern the sketch was drawn with
  std::string units = "m";      ///< unit of the coordinates ("m" for every reader we have)
  std::string provenance;       ///< where it came from (file name, application)
  /// Surfacing parameters stored with the sketch, as dotted names ("segment.epsilon") to values.
  std::map<std::string, double> params;

  std::size_t point_count() const;
  double total_length() const;
  /// Bounding box of every point of every stroke (ignored strokes included).
  BoundingBox bounding_box() const;
  /// Gives every stroke with id -1 the next free id, so ids are unique and stable.
  void assign_ids();
};

/// What clean() removed, in words a user can read.
struct CleanReport {
  std::size_t non_finite_points = 0;   ///< NaN or Inf coordinates
  std::size_t duplicate_points = 0;    ///< exact repeats of the previous point
  std::size_t short_strokes = 0;       ///< strokes left with fewer than min_points points
  std::size_t non_finite_attributes = 0;  ///< NaN or Inf colours, widths, pressures reset
  std::vector<std::string> messages;   ///< one line per removal kind, empty when nothing removed
  bool changed() const {
    return non_finite_points + duplicate_points + short_strokes + non_finite_attributes > 0;
  }
};

/// Options for clean().
struct CleanOptions {
  std::size_t min_points = 2;  ///< strokes with fewer points after cleaning are dropped (METHOD §0)
};

/// Removes non-finite points, exact duplicate consecutive points and too-short strokes, keeping
/// per-point attributes aligned; resets a non-finite colour, width or pressure to its default
/// (black, 0 = unknown, 1). Returns what was removed.
CleanReport clean(Sketch& sketch, const CleanOptions& options = {});

/// Resamples a polyline to uniform arc-length spacing `spacing` (> 0), keeping both endpoints.
/// Per-point attributes are interpolated (orientations by slerp, timestamps rounded).
/// A stroke shorter than `spacing` keeps only its two endpoints.
Stroke resample(const Stroke& stroke, double spacing);

/// Resamples every stroke of the sketch in place.
void resample(Sketch& sketch, double spacing);

/// The mirror image of `stroke` in `plane` (unit normal): points reflected, orientations
/// M R M (M the reflection), so that they stay rotations and point along the reflected direction.
Stroke mirrored(const Stroke& stroke, const Plane& plane);

}  // namespace sketchsurf
