#include "surfacing/sketch/openings.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

namespace sketchsurf {

bool OpeningOptions::valid(std::string* why) const {
  const auto fail = [&](const char* message) {
    if (why) *why = message;
    return false;
  };
  if (!(closed_gap > 0.0 && closed_gap < 1.0)) return fail("openings closed_gap must be in (0, 1)");
  if (!(min_size >= 0.0 && min_size < 1.0)) return fail("openings min_size must be in [0, 1)");
  if (!(flatness > 0.0)) return fail("openings flatness must be > 0");
  if (!(margin >= 0.0 && margin < 1.0)) return fail("openings margin must be in [0, 1)");
  if (!(thickness > 0.0)) return fail("openings thickness must be > 0");
  if (!(lowest_up >= -1.0 && lowest_up <= 1.0)) return fail("openings lowest_up must be in [-1, 1]");
  return true;
}

bool StrokeLoop::encloses(const Eigen::Vector3d& p, double margin) const {
  const Eigen::Vector2d q((p - center).dot(u), (p - center).dot(v));
  bool inside = false;
  double nearest = std::numeric_limits<double>::infinity();
  const std::size_t n = outline.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Eigen::Vector2d& a = outline[i];
    const Eigen::Vector2d& b = outline[j];
    if ((a.y() > q.y()) != (b.y() > q.y()) &&
        q.x() < (b.x() - a.x()) * (q.y() - a.y()) / (b.y() - a.y()) + a.x())
      inside = !inside;
    const Eigen::Vector2d d = b - a;
    const double len2 = d.squaredNorm();
    const double t = len2 > 0.0 ? std::clamp((q - a).dot(d) / len2, 0.0, 1.0) : 0.0;
    nearest = std::min(nearest, (a + t * d - q).norm());
  }
  return inside && nearest >= margin;
}

void StrokeLoop::flip() {
  plane.normal = -plane.normal;
  plane.offset = -plane.offset;
  v = -v;
  for (Eigen::Vector2d& q : outline) q.y() = -q.y();
}

std::optional<StrokeLoop> stroke_loop(const std::vector<Eigen::Vector3d>& points,
                                      const OpeningOptions& options) {
  if (points.size() < 4) return std::nullopt;
  double length = 0.0;
  for (std::size_t i = 1; i < points.size(); ++i) length += (points[i] - points[i - 1]).norm();
  if (!(length > 0.0) || (points.front() - points.back()).norm() > options.closed_gap * length)
    return std::nullopt;

  StrokeLoop loop;
  for (const Eigen::Vector3d& p : points) loop.center += p;
  loop.center /= static_cast<double>(points.size());
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& p : points) covariance += (p - loop.center) * (p - loop.center).transpose();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> pca(covariance);
  loop.plane.normal = pca.eigenvectors().col(0).normalized();
  loop.plane.offset = -loop.plane.normal.dot(loop.center);
  loop.u = pca.eigenvectors().col(2).normalized();
  loop.v = loop.plane.normal.cross(loop.u);
  double flat = 0.0;
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d d = p - loop.center;
    loop.outline.emplace_back(d.dot(loop.u), d.dot(loop.v));
    loop.radius += loop.outline.back().norm();
    flat = std::max(flat, std::abs(loop.height(p)));
  }
  loop.radius /= static_cast<double>(points.size());
  if (!(loop.radius > 0.0) || flat > options.flatness * loop.radius) return std::nullopt;
  return loop;
}

LoopSides loop_sides(const StrokeLoop& loop, const std::vector<Eigen::Vector3d>& points,
                     const OpeningOptions& options) {
  LoopSides sides;
  const double margin = options.margin * loop.radius;
  const double thickness = options.thickness * loop.radius;
  for (const Eigen::Vector3d& p : points) {
    if (!loop.encloses(p, margin)) continue;
    const double h = loop.height(p);
    if (std::abs(h) <= thickness) ++sides.across;
    else if (h > 0.0) ++sides.above;
    else ++sides.below;
  }
  return sides;
}

std::vector<Opening> find_openings(const Sketch& sketch, const OpeningOptions& options) {
  std::vector<Opening> openings;
  const double diagonal = sketch.bounding_box().diagonal();
  if (!(diagonal > 0.0)) return openings;
  for (std::size_t i = 0; i < sketch.strokes.size(); ++i) {
    const Stroke& rim = sketch.strokes[i];
    if (rim.ignored || rim.boundary) continue;
    std::optional<StrokeLoop> loop = stroke_loop(rim.points, options);
    if (!loop || 2.0 * loop->radius < options.min_size * diagonal) continue;
    std::vector<Eigen::Vector3d> others;
    for (std::size_t j = 0; j < sketch.strokes.size(); ++j)
      if (j != i && !sketch.strokes[j].ignored)
        others.insert(others.end(), sketch.strokes[j].points.begin(), sketch.strokes[j].points.end());
    const LoopSides sides = loop_sides(*loop, others, options);
    if (sides.across > 0 || (sides.above > 0) == (sides.below > 0)) continue;
    if (sides.above > 0) loop->flip();  // the normal points through the opening
    if (loop->plane.normal.y() < options.lowest_up) continue;
    openings.push_back({i, rim.id, std::move(*loop)});
  }
  // Sections drawn round an open object under its rim pass the same tests: only the loops with no
  // other one beyond them on their open side (within their outline) are the rims.
  std::vector<Opening> rims;
  for (const Opening& o : openings) {
    const bool covered = std::any_of(openings.begin(), openings.end(), [&](const Opening& other) {
      return &other != &o && o.loop.height(other.loop.center) > options.thickness * o.loop.radius &&
             o.loop.encloses(other.loop.center, 0.0);
    });
    if (!covered) rims.push_back(o);
  }
  return rims;
}

}  // namespace sketchsurf
