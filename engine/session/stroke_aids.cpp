#include "engine/session/stroke_aids.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sketchsurf::session {

namespace {

/// The point of the polyline nearest to `p`: where it is, its arc length from the start, and
/// the distance.
struct Nearest {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double arc = 0.0;
  double distance = std::numeric_limits<double>::infinity();
};

Nearest nearest_on(const Stroke& stroke, const Eigen::Vector3d& p) {
  Nearest best;
  const auto& pts = stroke.points;
  if (pts.size() == 1) best = {pts[0], 0.0, (p - pts[0]).norm()};
  double arc = 0.0;
  for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
    const Eigen::Vector3d ab = pts[i + 1] - pts[i];
    const double len2 = ab.squaredNorm(), len = std::sqrt(len2);
    const double t = len2 > 0.0 ? std::clamp((p - pts[i]).dot(ab) / len2, 0.0, 1.0) : 0.0;
    // The segment's own ends exactly, so that a point on a vertex is that vertex.
    const Eigen::Vector3d q = t == 0.0 ? pts[i] : t == 1.0 ? pts[i + 1] : Eigen::Vector3d(pts[i] + t * ab);
    const double d = (p - q).norm();
    if (d < best.distance) best = {q, arc + t * len, d};
    arc += len;
  }
  return best;
}

/// How far each smoothing round moves a point towards its Catmull-Rom midpoint. The full step
/// (replacing the point) amplifies a zig-zag by 1.25 per round (the midpoint of alternating
/// points overshoots); half a step damps every frequency (by 1/8 for the zig-zag) and leaves
/// lines and gentle curves alone.
constexpr double kSmoothingStep = 0.5;

/// An end within this fraction of the snap radius of the drawing plane lies on it.
constexpr double kOnPlane = 1e-9;

/// Cumulative arc length at each point.
std::vector<double> arc_lengths(const std::vector<Eigen::Vector3d>& pts) {
  std::vector<double> cum(pts.size(), 0.0);
  for (std::size_t i = 1; i < pts.size(); ++i) cum[i] = cum[i - 1] + (pts[i] - pts[i - 1]).norm();
  return cum;
}

/// Moves the end of `stroke` at `index` (0 or the last) to `target` exactly; the other points
/// within `falloff` arc length of it follow with a half-cosine weight.
void move_end(Stroke& stroke, std::size_t index, const Eigen::Vector3d& target, double falloff) {
  auto& pts = stroke.points;
  const Eigen::Vector3d delta = target - pts[index];
  const bool from_start = index == 0;
  double arc = 0.0;
  for (std::size_t k = 1; k < pts.size(); ++k) {
    const std::size_t i = from_start ? k : pts.size() - 1 - k;
    const std::size_t prev = from_start ? i - 1 : i + 1;
    arc += (pts[i] - pts[prev]).norm();  // the original spacing: the points ahead have not moved
    if (!(arc < falloff)) break;
    pts[i] += 0.5 * (1.0 + std::cos(M_PI * arc / falloff)) * delta;
  }
  pts[index] = target;
}

Stroke reversed(Stroke s) {
  std::reverse(s.points.begin(), s.points.end());
  std::reverse(s.orientations.begin(), s.orientations.end());
  std::reverse(s.pressures.begin(), s.pressures.end());
  std::reverse(s.timestamps_ms.begin(), s.timestamps_ms.end());
  return s;
}

/// Kuhn's Eq. 4.4 with b_max = 1: 0 at u = 0 and 1, 1 between the two blends of width d.
double blend_weight(double u, double d) {
  if (u < d) return 0.5 - 0.5 * std::cos(M_PI * u / d);
  if (u > 1.0 - d) return 0.5 - 0.5 * std::cos(M_PI * (1.0 - u) / d);
  return 1.0;
}

}  // namespace

double distance_to_stroke(const Eigen::Vector3d& p, const Stroke& stroke) {
  return nearest_on(stroke, p).distance;
}

void straighten(Stroke& stroke) {
  auto& pts = stroke.points;
  if (pts.size() < 3) return;
  const Eigen::Vector3d a = pts.front(), b = pts.back();
  const double n = double(pts.size() - 1);
  for (std::size_t i = 1; i + 1 < pts.size(); ++i) pts[i] = a + (b - a) * (double(i) / n);
}

void smooth_stroke(Stroke& stroke, int iterations) {
  auto& p = stroke.points;
  const std::size_t n = p.size();
  if (n < 3) return;
  std::vector<Eigen::Vector3d> next(p);
  for (int it = 0; it < iterations; ++it) {
    const auto at = [&](std::ptrdiff_t i) -> Eigen::Vector3d {
      if (i < 0) return 2.0 * p[0] - p[1];
      if (i >= std::ptrdiff_t(n)) return 2.0 * p[n - 1] - p[n - 2];
      return p[std::size_t(i)];
    };
    for (std::size_t i = 1; i + 1 < n; ++i) {
      const auto k = std::ptrdiff_t(i);
      const Eigen::Vector3d mid = (-at(k - 2) + 9.0 * at(k - 1) + 9.0 * at(k + 1) - at(k + 2)) / 16.0;
      next[i] = p[i] + kSmoothingStep * (mid - p[i]);
    }
    p.swap(next);  // the ends of both are the stroke's, never written
  }
}

std::pair<EndSnap, EndSnap> snap_ends(Stroke& stroke, const std::vector<Stroke>& others, double radius,
                                      const std::optional<Plane>& plane, const std::optional<Plane>& mirror) {
  std::pair<EndSnap, EndSnap> result;
  if (stroke.points.size() < 2 || !(radius > 0.0)) return result;
  const double falloff = std::min(3.0 * radius, 0.5 * stroke.length());
  const auto find = [&](const Eigen::Vector3d& p) {
    EndSnap snap;
    double best = radius;
    // On the plane: where another stroke crosses it, so that the moved points stay on it.
    if (plane && std::abs(plane->signed_distance(p)) <= kOnPlane * radius) {
      for (std::size_t k = 0; k < others.size(); ++k) {
        const auto& o = others[k].points;
        for (std::size_t i = 0; i + 1 < o.size(); ++i) {
          const double da = plane->signed_distance(o[i]), db = plane->signed_distance(o[i + 1]);
          if ((da > 0.0 && db > 0.0) || (da < 0.0 && db < 0.0) || da == db) continue;
          Eigen::Vector3d x = o[i] + (da / (da - db)) * (o[i + 1] - o[i]);
          x -= plane->signed_distance(x) * plane->normal;
          const double d = (x - p).norm();
          if (d <= best) {
            best = d;
            snap = {true, x, k};
          }
        }
      }
      if (snap.snapped) return snap;
    }
    // A nearby end first: strokes meeting at a corner share the point.
    for (std::size_t k = 0; k < others.size(); ++k) {
      const auto& o = others[k].points;
      if (o.empty()) continue;
      for (const Eigen::Vector3d* e : {&o.front(), &o.back()}) {
        const double d = (*e - p).norm();
        if (d <= best) {
          best = d;
          snap = {true, *e, k};
        }
      }
    }
    if (snap.snapped) return snap;
    for (std::size_t k = 0; k < others.size(); ++k) {
      const Nearest q = nearest_on(others[k], p);
      if (q.distance <= best) {
        best = q.distance;
        snap = {true, q.point, k};
      }
    }
    if (!snap.snapped && mirror && std::abs(mirror->signed_distance(p)) <= radius)
      snap = {true, Eigen::Vector3d(p - mirror->signed_distance(p) * mirror->normal), std::nullopt};
    return snap;
  };
  result.first = find(stroke.points.front());
  if (result.first.snapped) move_end(stroke, 0, result.first.target, falloff);
  const Eigen::Vector3d& start = stroke.points.front();
  if (stroke.length() > 4.0 * radius && (stroke.points.back() - start).norm() <= radius)
    result.second = {true, start, std::nullopt};  // the stroke closes on itself
  else
    result.second = find(stroke.points.back());
  if (result.second.snapped) move_end(stroke, stroke.points.size() - 1, result.second.target, falloff);
  return result;
}

std::optional<std::size_t> oversketch_target(const std::vector<Stroke>& strokes, const Stroke& style,
                                             const OversketchOptions& options) {
  if (style.points.size() < 2) return std::nullopt;
  std::optional<std::size_t> best;
  double best_mean = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < strokes.size(); ++k) {
    const Stroke& r = strokes[k];
    if (r.points.size() < 2) continue;
    const Nearest a = nearest_on(r, style.points.front()), b = nearest_on(r, style.points.back());
    if (a.distance > options.end_radius || b.distance > options.end_radius) continue;
    if (!(std::abs(a.arc - b.arc) > 2.0 * options.end_radius)) continue;
    double sum = 0.0;
    bool near = true;
    for (const auto& p : style.points) {
      const double d = nearest_on(r, p).distance;
      if (d > options.max_distance) {
        near = false;
        break;
      }
      sum += d;
    }
    const double mean = sum / double(style.points.size());
    if (near && mean < best_mean) {
      best_mean = mean;
      best = k;
    }
  }
  return best;
}

Stroke oversketch(const Stroke& target, const Stroke& style_in, double blend) {
  const auto& tp = target.points;
  if (tp.size() < 2 || style_in.points.size() < 2) return target;
  double sa = nearest_on(target, style_in.points.front()).arc;
  double sb = nearest_on(target, style_in.points.back()).arc;
  const Stroke style = sa <= sb ? style_in : reversed(style_in);
  if (sa > sb) std::swap(sa, sb);
  const std::vector<double> cum = arc_lengths(tp), su = arc_lengths(style.points);
  const double d = std::clamp(blend, 1e-6, 0.5);

  const bool orientations = !target.orientations.empty() && !style.orientations.empty();
  const bool pressures = !target.pressures.empty() && !style.pressures.empty();
  const bool stamps = !target.timestamps_ms.empty();
  Stroke out = target;
  out.points.clear();
  out.orientations.clear();
  out.pressures.clear();
  out.timestamps_ms.clear();
  const auto keep = [&](std::size_t i) {
    out.points.push_back(tp[i]);
    if (!target.orientations.empty()) out.orientations.push_back(target.orientations[i]);
    if (!target.pressures.empty()) out.pressures.push_back(target.pressures[i]);
    if (stamps) out.timestamps_ms.push_back(target.timestamps_ms[i]);
  };
  std::size_t i = 0;
  for (; i < tp.size() && cum[i] < sa; ++i) keep(i);
  // The covered part, at the style's own samples.
  std::size_t seg = 0;
  for (std::size_t j = 0; j < style.points.size(); ++j) {
    const double u = su.back() > 0.0 ? su[j] / su.back() : double(j) / double(style.points.size() - 1);
    const double s = sa + u * (sb - sa);
    while (seg + 2 < tp.size() && cum[seg + 1] < s) ++seg;
    const double len = cum[seg + 1] - cum[seg];
    const double f = len > 0.0 ? std::clamp((s - cum[seg]) / len, 0.0, 1.0) : 0.0;
    const Eigen::Vector3d base = tp[seg] + f * (tp[seg + 1] - tp[seg]);
    const double w = j == 0 || j + 1 == style.points.size() ? 0.0 : blend_weight(u, d);
    out.points.push_back(w == 1.0 ? style.points[j] : Eigen::Vector3d(base + w * (style.points[j] - base)));
    if (!target.orientations.empty())
      out.orientations.push_back(orientations ? style.orientations[j]
                                              : target.orientations[seg].slerp(f, target.orientations[seg + 1]));
    if (!target.pressures.empty())
      out.pressures.push_back(pressures ? style.pressures[j]
                                        : target.pressures[seg] + float(f) * (target.pressures[seg + 1] - target.pressures[seg]));
    if (stamps) {
      const double t0 = target.timestamps_ms[seg], t1 = target.timestamps_ms[seg + 1];
      out.timestamps_ms.push_back(static_cast<std::uint32_t>(std::llround(t0 + f * (t1 - t0))));
    }
  }
  for (; i < tp.size(); ++i)
    if (cum[i] > sb) keep(i);
  // Exact repeats (a kept point on the covered part's end) would be zero-length segments.
  Stroke clean = out;
  clean.points.clear();
  clean.orientations.clear();
  clean.pressures.clear();
  clean.timestamps_ms.clear();
  for (std::size_t k = 0; k < out.points.size(); ++k) {
    if (k > 0 && out.points[k] == clean.points.back()) continue;
    clean.points.push_back(out.points[k]);
    if (!out.orientations.empty()) clean.orientations.push_back(out.orientations[k]);
    if (!out.pressures.empty()) clean.pressures.push_back(out.pressures[k]);
    if (!out.timestamps_ms.empty()) clean.timestamps_ms.push_back(out.timestamps_ms[k]);
  }
  return clean;
}

}  // namespace sketchsurf::session
