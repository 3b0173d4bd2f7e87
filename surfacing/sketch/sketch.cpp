#include "surfacing/sketch/sketch.h"

#include <algorithm>
#include <cmath>

#include "surfacing/error.h"

namespace sketchsurf {

double Stroke::length() const {
  double total = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) total += (points[i] - points[i - 1]).norm();
  return total;
}

bool Stroke::attributes_consistent() const {
  auto ok = [&](std::size_t n) { return n == 0 || n == points.size(); };
  return ok(orientations.size()) && ok(pressures.size()) && ok(timestamps_ms.size());
}

std::size_t Sketch::point_count() const {
  std::size_t n = 0;
  for (const auto& s : strokes) n += s.size();
  return n;
}

double Sketch::total_length() const {
  double total = 0.0;
  for (const auto& s : strokes) total += s.length();
  return total;
}

BoundingBox Sketch::bounding_box() const {
  BoundingBox box;
  for (const auto& s : strokes)
    for (const auto& p : s.points) box.extend(p);
  return box;
}

void Sketch::assign_ids() {
  std::int64_t next = 0;
  for (const auto& s : strokes) next = std::max(next, s.id + 1);
  for (auto& s : strokes)
    if (s.id < 0) s.id = next++;
}

namespace {

// Keeps the points (and their attributes) whose flag is set.
void keep_points(Stroke& s, const std::vector<char>& keep) {
  auto filter = [&](auto& v) {
    if (v.empty()) return;
    std::size_t out = 0;
    for (std::size_t i = 0; i < v.size(); ++i)
      if (keep[i]) v[out++] = v[i];
    v.resize(out);
  };
  filter(s.points);
  filter(s.orientations);
  filter(s.pressures);
  filter(s.timestamps_ms);
}

}  // namespace

CleanReport clean(Sketch& sketch, const CleanOptions& options) {
  CleanReport report;
  std::vector<Stroke> kept;
  kept.reserve(sketch.strokes.size());
  for (auto& s : sketch.strokes) {
    // Attributes that carry no geometry are reset rather than costing the stroke or the point.
    if (!std::all_of(s.color.begin(), s.color.end(), [](float c) { return std::isfinite(c); })) {
      s.color = Stroke{}.color;
      ++report.non_finite_attributes;
    }
    if (!std::isfinite(s.width)) {
      s.width = 0.0;
      ++report.non_finite_attributes;
    }
    for (float& p : s.pressures)
      if (!std::isfinite(p)) {
        p = 1.f;
        ++report.non_finite_attributes;
      }
    std::vector<char> keep(s.points.size(), 1);
    const Eigen::Vector3d* previous = nullptr;
    for (std::size_t i = 0; i < s.points.size(); ++i) {
      const bool finite = s.points[i].allFinite() &&
                          (s.orientations.empty() || s.orientations[i].coeffs().allFinite());
      if (!finite) {
        keep[i] = 0;
        ++report.non_finite_points;
      } else if (previous && *previous == s.points[i]) {
        keep[i] = 0;
        ++report.duplicate_points;
      } else {
        previous = &s.points[i];
      }
    }
    keep_points(s, keep);
    if (s.points.size() < options.min_points) {
      ++report.short_strokes;
      continue;
    }
    kept.push_back(std::move(s));
  }
  sketch.strokes = std::move(kept);
  if (report.non_finite_points)
    report.messages.push_back("removed " + std::to_string(report.non_finite_points) +
                              " point(s) with NaN or infinite coordinates");
  if (report.non_finite_attributes)
    report.messages.push_back("reset " + std::to_string(report.non_finite_attributes) +
                              " NaN or infinite colour, width or pressure value(s) to the default");
  if (report.duplicate_points)
    report.messages.push_back("removed " + std::to_string(report.duplicate_points) +
                              " duplicate consecutive point(s)");
  if (report.short_strokes)
    report.messages.push_back("dropped " + std::to_string(report.short_strokes) +
                              " stroke(s) with fewer than " + std::to_string(options.min_points) +
                              " points");
  return report;
}

Stroke resample(const Stroke& stroke, double spacing) {
  if (!(spacing > 0.0) || !std::isfinite(spacing))
    throw Error::usage("resampling spacing must be a positive number");
  Stroke out = stroke;
  out.points.clear();
  out.orientations.clear();
  out.pressures.clear();
  out.timestamps_ms.clear();
  const std::size_t n = stroke.points.size();
  if (n < 2) return stroke;

  // Cumulative arc length at each input point.
  std::vector<double> arc(n, 0.0);
  for (std::size_t i = 1; i < n; ++i) arc[i] = arc[i - 1] + (stroke.points[i] - stroke.points[i - 1]).norm();
  const double total = arc.back();
  const std::size_t segments = std::max<std::size_t>(1, static_cast<std::size_t>(std::llround(total / spacing)));

  std::size_t j = 0;  // input segment [j, j+1] containing the current arc position
  for (std::size_t k = 0; k <= segments; ++k) {
    std::size_t i0, i1;
    double t;
    if (k == segments) {
      i0 = i1 = n - 1;
      t = 0.0;
    } else {
      const double s = total * static_cast<double>(k) / static_cast<double>(segments);
      while (j + 1 < n - 1 && arc[j + 1] < s) ++j;
      i0 = j;
      i1 = j + 1;
      const double len = arc[i1] - arc[i0];
      t = len > 0.0 ? std::clamp((s - arc[i0]) / len, 0.0, 1.0) : 0.0;
    }
    out.points.push_back((1.0 - t) * stroke.points[i0] + t * stroke.points[i1]);
    if (!stroke.orientations.empty())
      out.orientations.push_back(stroke.orientations[i0].slerp(t, stroke.orientations[i1]));
    if (!stroke.pressures.empty())
      out.pressures.push_back(static_cast<float>((1.0 - t) * stroke.pressures[i0] + t * stroke.pressures[i1]));
    if (!stroke.timestamps_ms.empty())
      out.timestamps_ms.push_back(static_cast<std::uint32_t>(std::llround(
          (1.0 - t) * stroke.timestamps_ms[i0] + t * stroke.timestamps_ms[i1])));
  }
  return out;
}

void resample(Sketch& sketch, double spacing) {
  for (auto& s : sketch.strokes) s = resample(s, spacing);
}

Stroke mirrored(const Stroke& stroke, const Plane& plane) {
  Stroke out = stroke;
  for (auto& p : out.points) p = plane.reflect(p);
  const Eigen::Matrix3d m = Eigen::Matrix3d::Identity() - 2.0 * plane.normal * plane.normal.transpose();
  for (auto& q : out.orientations) q = Eigen::Quaterniond(m * q.toRotationMatrix() * m).normalized();
  return out;
}

}  // namespace sketchsurf
