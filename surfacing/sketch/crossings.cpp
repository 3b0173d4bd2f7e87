#include "surfacing/sketch/crossings.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <map>
#include <utility>
#include <vector>

#include "surfacing/portable_math.h"
#include "surfacing/sketch/stroke_point_grid.h"

namespace sketchsurf {

namespace {

// The closest points of segments p0p1 and q0q1 (Ericson, Real-Time Collision Detection 5.1.9):
// their distance and the points' parameters along each segment, in [0, 1].
struct Approach {
  double distance = 0.0, s = 0.0, t = 0.0;
};

Approach closest_approach(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& q0,
                          const Eigen::Vector3d& q1) {
  const Eigen::Vector3d d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  Approach out;
  if (a <= 0.0 && e <= 0.0) {
    out.distance = r.norm();
    return out;
  }
  if (a <= 0.0) {
    out.t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= 0.0) {
      out.s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), denominator = a * e - b * b;
      out.s = denominator > 0.0 ? std::clamp((b * f - c * e) / denominator, 0.0, 1.0) : 0.0;
      out.t = (b * out.s + f) / e;
      if (out.t < 0.0) {
        out.t = 0.0;
        out.s = std::clamp(-c / a, 0.0, 1.0);
      } else if (out.t > 1.0) {
        out.t = 1.0;
        out.s = std::clamp((b - c) / a, 0.0, 1.0);
      }
    }
  }
  out.distance = ((p0 + out.s * d1) - (q0 + out.t * d2)).norm();
  return out;
}

}  // namespace

double unmet_share(const Sketch& sketch, double reach, double angle) {
  if (!(reach > 0.0)) return 0.0;
  // The strokes resampled every reach / 2, so that a crossing leaves a point of each within reach.
  Sketch fine;
  fine.strokes.resize(sketch.strokes.size());
  double ink = 0.0;
  for (std::size_t s = 0; s < sketch.strokes.size(); ++s) {
    const Stroke& stroke = sketch.strokes[s];
    if (stroke.ignored || stroke.size() < 2) {
      fine.strokes[s].ignored = true;
      continue;
    }
    ink += stroke.length();
    fine.strokes[s] = resample(stroke, 0.5 * reach);
  }
  if (!(ink > 0.0)) return 0.0;
  // A resampled stroke's direction at its point i (central difference; unit, or zero).
  const auto direction = [&](std::size_t s, std::size_t i) -> Eigen::Vector3d {
    const std::vector<Eigen::Vector3d>& p = fine.strokes[s].points;
    const Eigen::Vector3d d = p[std::min(i + 1, p.size() - 1)] - p[i > 0 ? i - 1 : 0];
    return d.norm() > 0.0 ? Eigen::Vector3d(d.normalized()) : Eigen::Vector3d::Zero();
  };
  const StrokePointGrid grid(fine, reach, false);
  const double most_aligned = portable::cos(angle);
  std::vector<char> met(sketch.strokes.size(), 0);
  for (std::size_t s = 0; s < fine.strokes.size(); ++s) {
    if (fine.strokes[s].ignored) continue;
    for (std::size_t i = 0; i < fine.strokes[s].points.size() && !met[s]; ++i) {
      const Eigen::Vector3d t = direction(s, i);
      met[s] = grid.any_near(fine.strokes[s].points[i], s, reach, [&](std::size_t other, std::size_t j) {
        if (std::abs(t.dot(direction(other, j))) >= most_aligned) return false;
        met[other] = 1;
        return true;
      });
    }
  }
  double unmet = 0.0;
  for (std::size_t s = 0; s < sketch.strokes.size(); ++s)
    if (!met[s] && !fine.strokes[s].ignored) unmet += sketch.strokes[s].length();
  return unmet / ink;
}

namespace {

// How far stroke `p` turns about its piece `a` (pieces p[i]p[i+1]): the angle between its chords
// from `reach` (arc length) before the piece to its end and from its start to `reach` after it
// (chords, not pieces: a hand's tremor turns each short piece of its own).
double turn_about(const std::vector<Eigen::Vector3d>& p, std::size_t a, double reach) {
  std::size_t before = a, after = a + 1;
  for (double arc = 0.0; before > 0 && arc < reach; --before) arc += (p[before] - p[before - 1]).norm();
  for (double arc = 0.0; after + 1 < p.size() && arc < reach; ++after) arc += (p[after + 1] - p[after]).norm();
  const Eigen::Vector3d u = p[a + 1] - p[before], v = p[after] - p[a];
  const double n = u.norm() * v.norm();
  if (!(n > 0.0)) return 0.0;
  return std::acos(std::clamp(u.dot(v) / n, -1.0, 1.0));
}

}  // namespace

double crossing_gap(const Sketch& sketch, double reach, double angle, std::size_t least, double bend) {
  if (!(reach > 0.0)) return -1.0;
  // Every segment split into pieces of at most reach / 2, points added on it and none moved: two
  // pieces within reach of each other then have end points within 1.5 reach.
  const double piece = 0.5 * reach;
  Sketch fine;
  fine.strokes.resize(sketch.strokes.size());
  for (std::size_t s = 0; s < sketch.strokes.size(); ++s) {
    const Stroke& stroke = sketch.strokes[s];
    if (stroke.ignored || stroke.size() < 2) {
      fine.strokes[s].ignored = true;
      continue;
    }
    std::vector<Eigen::Vector3d>& out = fine.strokes[s].points;
    out.push_back(stroke.points.front());
    for (std::size_t i = 1; i < stroke.points.size(); ++i) {
      const Eigen::Vector3d a = stroke.points[i - 1], b = stroke.points[i];
      const int pieces = std::max(1, static_cast<int>(std::ceil((b - a).norm() / piece)));
      for (int k = 1; k < pieces; ++k) out.push_back(a + (b - a) * (static_cast<double>(k) / pieces));
      out.push_back(b);
    }
  }
  // Per pair of strokes, its closest approach and whether it is a crossing there.
  struct Closest {
    double distance = 0.0;
    bool crossing = false;
  };
  std::map<std::pair<std::size_t, std::size_t>, Closest> pairs;
  const double most_aligned = portable::cos(angle);
  const StrokePointGrid grid(fine, 1.5 * reach, false);
  for (std::size_t s = 0; s < fine.strokes.size(); ++s) {
    if (fine.strokes[s].ignored) continue;
    const std::vector<Eigen::Vector3d>& p = fine.strokes[s].points;
    for (std::size_t i = 0; i < p.size(); ++i) {
      grid.any_near(p[i], s, 1.5 * reach, [&](std::size_t o, std::size_t j) {
        if (o < s) return false;
        const std::vector<Eigen::Vector3d>& q = fine.strokes[o].points;
        // The pieces on either side of point i against those on either side of point j.
        for (std::size_t a = i > 0 ? i - 1 : i; a < std::min(i + 1, p.size() - 1); ++a) {
          for (std::size_t b = j > 0 ? j - 1 : j; b < std::min(j + 1, q.size() - 1); ++b) {
            const Approach c = closest_approach(p[a], p[a + 1], q[b], q[b + 1]);
            if (c.distance > reach) continue;
            const auto [it, added] = pairs.try_emplace({s, o}, Closest{c.distance, false});
            if (!added && it->second.distance <= c.distance) continue;
            const bool at_end = (a == 0 && c.s == 0.0) || (a + 2 == p.size() && c.s == 1.0) ||
                                (b == 0 && c.t == 0.0) || (b + 2 == q.size() && c.t == 1.0);
            const Eigen::Vector3d u = p[a + 1] - p[a], v = q[b + 1] - q[b];
            const bool across = std::abs(u.dot(v)) < most_aligned * u.norm() * v.norm();
            // The turns are looked at only for a crossing (the walks along both strokes).
            it->second = Closest{c.distance, across && !at_end && turn_about(p, a, reach) <= bend &&
                                                 turn_about(q, b, reach) <= bend};
          }
        }
        return false;
      });
    }
  }
  std::vector<double> gaps;
  for (const auto& [key, closest] : pairs)
    if (closest.crossing) gaps.push_back(closest.distance);
  if (gaps.empty() || gaps.size() < least) return -1.0;
  const auto middle = gaps.begin() + static_cast<std::ptrdiff_t>(gaps.size() / 2);
  std::nth_element(gaps.begin(), middle, gaps.end());
  return *middle;
}

}  // namespace sketchsurf
