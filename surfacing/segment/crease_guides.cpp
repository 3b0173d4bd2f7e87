#include "surfacing/segment/crease_guides.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "surfacing/error.h"
#include "surfacing/portable_math.h"

namespace sketchsurf {

namespace {

using V3 = Eigen::Vector3d;

// A stroke as a polyline with arc lengths, open or closed, and the point at any arc length
// (taken modulo the length when closed).
struct ArcPolyline {
  std::vector<V3> points;
  std::vector<double> arc;  // arc[i]: length from points[0]; for a closed one, arc.back() = total
  bool closed = false;

  double length() const { return arc.back(); }

  V3 at(double s) const {
    if (closed) s -= length() * std::floor(s / length());
    const auto it = std::upper_bound(arc.begin(), arc.end(), s);
    const std::size_t i = std::clamp<std::size_t>(static_cast<std::size_t>(it - arc.begin()), 1, arc.size() - 1);
    const double span = arc[i] - arc[i - 1];
    const double t = span > 0 ? std::clamp((s - arc[i - 1]) / span, 0.0, 1.0) : 0.0;
    const V3& a = points[i - 1];
    const V3& b = i < points.size() ? points[i] : points[0];
    return a + t * (b - a);
  }
};

ArcPolyline arc_polyline(const Stroke& stroke, double closing_gap) {
  ArcPolyline line;
  for (const V3& p : stroke.points)
    if (line.points.empty() || (p - line.points.back()).norm() > 0) line.points.push_back(p);
  line.arc.assign(1, 0.0);
  for (std::size_t i = 1; i < line.points.size(); ++i)
    line.arc.push_back(line.arc.back() + (line.points[i] - line.points[i - 1]).norm());
  if (line.points.size() >= 3 && (line.points.front() - line.points.back()).norm() <= closing_gap) {
    line.closed = true;
    line.arc.push_back(line.arc.back() + (line.points.front() - line.points.back()).norm());
  }
  return line;
}

double angle_deg(const V3& a, const V3& b) {
  const double n = a.norm() * b.norm();
  if (!(n > 0)) return 0.0;
  return portable::acos(std::clamp(a.dot(b) / n, -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

}  // namespace

bool CreaseGuideOptions::valid(std::string* why) const {
  auto fail = [&](const char* m) {
    if (why) *why = m;
    return false;
  };
  if (!(window > 0) || !std::isfinite(window)) return fail("crease guide window must be positive");
  if (!(min_turn > 0 && min_turn < max_turn && max_turn <= 180))
    return fail("crease guide turns need 0 < min_turn < max_turn <= 180 degrees");
  if (!(concentration >= 0 && concentration <= 1))
    return fail("crease guide concentration must be in [0, 1]");
  if (!(min_gap >= 0 && max_gap > min_gap) || !std::isfinite(max_gap))
    return fail("crease guide gaps need 0 <= min_gap < max_gap");
  if (!(alignment > 0 && alignment < 90)) return fail("crease guide alignment must be in (0, 90) degrees");
  if (!(same_way > 0 && same_way <= 180)) return fail("crease guide same_way must be in (0, 180] degrees");
  if (!(fold_radius > 0) || !std::isfinite(fold_radius)) return fail("crease guide fold_radius must be positive");
  if (!(min_fold >= 0 && min_fold < 90)) return fail("crease guide min_fold must be in [0, 90) degrees");
  return true;
}

std::vector<StrokeCorner> stroke_corners(const Sketch& sketch, double diagonal,
                                         const CreaseGuideOptions& options) {
  std::string why;
  if (!options.valid(&why)) throw Error::usage(why);
  std::vector<StrokeCorner> corners;
  const double w = options.window * diagonal;
  for (std::size_t s = 0; s < sketch.strokes.size(); ++s) {
    const Stroke& stroke = sketch.strokes[s];
    if (stroke.ignored) continue;
    const ArcPolyline line = arc_polyline(stroke, 0.5 * w);
    if (line.points.size() < 3 || line.length() < (line.closed ? 4 * w : 2 * w)) continue;
    const std::size_t n = line.points.size();
    // Turn over the window at every point that has a full window on both sides.
    std::vector<double> turn(n, -1.0);
    std::vector<V3> axis(n, V3::Zero()), apex(n, V3::Zero());
    for (std::size_t i = 0; i < n; ++i) {
      const double s0 = line.arc[i];
      if (!line.closed && (s0 < w || s0 > line.length() - w)) continue;
      const V3& p = line.points[i];
      const V3 in = p - line.at(s0 - w), out = line.at(s0 + w) - p;
      const double t = angle_deg(in, out);
      if (t < options.min_turn || t > options.max_turn) continue;
      const double half = angle_deg(p - line.at(s0 - 0.5 * w), line.at(s0 + 0.5 * w) - p);
      if (half < options.concentration * t) continue;
      const V3 a = in.normalized().cross(out.normalized());
      const V3 tip = in.normalized() - out.normalized();
      if (!(a.norm() > 0) || !(tip.norm() > 0)) continue;
      turn[i] = t;
      axis[i] = a.normalized();
      apex[i] = tip.normalized();
    }
    // Keep each point that turns most within the window on both sides (the first on a tie).
    auto arc_gap = [&](std::size_t i, std::size_t j) {
      const double d = std::abs(line.arc[i] - line.arc[j]);
      return line.closed ? std::min(d, line.length() - d) : d;
    };
    for (std::size_t i = 0; i < n; ++i) {
      if (turn[i] < 0) continue;
      bool best = true;
      for (std::size_t j = 0; j < n && best; ++j)
        if (j != i && turn[j] >= 0 && arc_gap(i, j) < w)
          best = turn[j] < turn[i] || (turn[j] == turn[i] && j > i);
      if (best) corners.push_back({line.points[i], axis[i], apex[i], static_cast<int>(s)});
    }
  }
  return corners;
}

std::vector<std::array<V3, 2>> crease_guides(const Sketch& sketch, double diagonal,
                                             const CreaseGuideOptions& options) {
  std::string why;
  if (!options.valid(&why)) throw Error::usage(why);
  std::vector<std::array<V3, 2>> guides;
  if (!options.enabled) return guides;
  const std::vector<StrokeCorner> corners = stroke_corners(sketch, diagonal, options);
  const double cos_align = portable::cos(options.alignment * std::numbers::pi / 180.0);
  const double cos_same = portable::cos(options.same_way * std::numbers::pi / 180.0);
  const double lo = options.min_gap * diagonal, hi = options.max_gap * diagonal;
  const std::size_t n = corners.size();
  // nearest[2 i + side]: the chosen corner along +axis (side 0) or -axis (side 1) of corner i:
  // the closest of those whose apex points the same way (rank 0), else the closest (rank 1).
  std::vector<int> nearest(2 * n, -1), nearest_rank(2 * n, 2);
  std::vector<double> nearest_d(2 * n, hi);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) {
      if (corners[i].stroke == corners[j].stroke) continue;
      const V3 g = corners[j].position - corners[i].position;
      const double d = g.norm();
      if (d < lo || d > hi) continue;
      const double along = g.dot(corners[i].axis);
      if (std::abs(along) < cos_align * d || std::abs(g.dot(corners[j].axis)) < cos_align * d) continue;
      const std::size_t slot = 2 * i + (along > 0 ? 0 : 1);
      const int rank = options.same_way >= 180 || corners[i].apex.dot(corners[j].apex) >= cos_same ? 0 : 1;
      if (rank < nearest_rank[slot] || (rank == nearest_rank[slot] && d < nearest_d[slot])) {
        nearest_rank[slot] = rank;
        nearest_d[slot] = d;
        nearest[slot] = static_cast<int>(j);
      }
    }
  for (std::size_t i = 0; i < n; ++i)
    for (int side = 0; side < 2; ++side) {
      const int j = nearest[2 * i + side];
      if (j < 0 || static_cast<std::size_t>(j) < i) continue;  // each pair once, from its lower index
      const V3 back = corners[i].position - corners[j].position;
      const int back_side = back.dot(corners[j].axis) > 0 ? 0 : 1;
      if (nearest[2 * j + back_side] == static_cast<int>(i))
        guides.push_back({corners[i].position, corners[j].position});
    }
  return guides;
}

std::vector<std::array<V3, 2>> guides_on_folds(const std::vector<std::array<V3, 2>>& guides,
                                               const Eigen::MatrixX3d& positions,
                                               const Eigen::MatrixX3d& normals, double diagonal,
                                               const CreaseGuideOptions& options) {
  std::string why;
  if (!options.valid(&why)) throw Error::usage(why);
  const double r = options.fold_radius * diagonal;
  const double cos_fold = portable::cos(options.min_fold * std::numbers::pi / 180.0);
  const double sin_align = portable::sin(options.alignment * std::numbers::pi / 180.0);
  std::vector<std::array<V3, 2>> kept;
  std::vector<Eigen::Index> near;
  for (const auto& g : guides) {
    const V3 d = g[1] - g[0];
    const double len2 = d.squaredNorm();
    if (!(len2 > 0)) continue;
    // Near a crease along d both faces contain d: their normals are perpendicular to it.
    const V3 axis = d / std::sqrt(len2);
    near.clear();
    std::size_t crossing = 0;
    V3 mean = V3::Zero();
    for (Eigen::Index v = 0; v < positions.rows(); ++v) {
      const V3 p = positions.row(v).transpose();
      const double t = (p - g[0]).dot(d) / len2;
      if (t < 0.1 || t > 0.9 || (p - g[0] - t * d).squaredNorm() > r * r) continue;
      const V3 n = normals.row(v).transpose();
      if (std::abs(n.dot(axis)) > sin_align) {
        ++crossing;
        continue;
      }
      near.push_back(v);
      mean += n;
    }
    if (near.empty() || static_cast<double>(crossing) > 0.1 * static_cast<double>(near.size() + crossing) ||
        !(mean.norm() > 0))
      continue;
    mean.normalize();
    double least = 1.0;
    for (Eigen::Index v : near) least = std::min(least, normals.row(v).dot(mean));
    if (least <= cos_fold) kept.push_back(g);
  }
  return kept;
}

}  // namespace sketchsurf
