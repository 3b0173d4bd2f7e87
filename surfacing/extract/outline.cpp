#include "surfacing/extract/outline.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include <Eigen/Eigenvalues>

#include "surfacing/closest_face.h"

namespace sketchsurf {

bool OutlineOptions::valid(std::string* why) const {
  auto fail = [&](const char* what) {
    if (why) *why = what;
    return false;
  };
  if (!(tolerance > 0.0)) return fail("extract.outline_tolerance must be > 0");
  if (!(reach > 0.0)) return fail("extract.outline_reach must be > 0");
  if (!(flat_share > 0.0 && flat_share <= 1.0)) return fail("extract.outline_flat_share must be in (0, 1]");
  if (!(drawn_share > 0.0 && drawn_share <= 1.0)) return fail("extract.outline_drawn_share must be in (0, 1]");
  if (!(angle >= 0.0 && angle <= 90.0)) return fail("extract.outline_angle must be in [0, 90]");
  if (!(margin >= 0.0)) return fail("extract.outline_margin must be >= 0");
  return true;
}

namespace {

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

/// Convex hull, counter-clockwise, without collinear points (Andrew's monotone chain).
std::vector<Eigen::Vector2d> convex_hull(std::vector<Eigen::Vector2d> points) {
  std::sort(points.begin(), points.end(), [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  if (points.size() < 3) return points;
  std::vector<Eigen::Vector2d> hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {  // lower chain
    while (k >= 2 && cross(hull[k - 1] - hull[k - 2], points[i] - hull[k - 2]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size() - 1, lower = k + 1; i-- > 0;) {  // upper chain
    while (k >= lower && cross(hull[k - 1] - hull[k - 2], points[i] - hull[k - 2]) <= 0.0) --k;
    hull[k++] = points[i];
  }
  hull.resize(k - 1);
  return hull;
}

/// Distance from p to the segment a-b, and the parameter of its closest point.
double segment_distance(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b, double* t) {
  const Eigen::Vector2d d = b - a;
  const double dd = d.squaredNorm();
  *t = dd > 0.0 ? std::clamp((p - a).dot(d) / dd, 0.0, 1.0) : 0.0;
  return (a + *t * d - p).norm();
}

/// The plane that most of `points` lie within `tolerance` of: the best of candidate planes through
/// three points (drawn by a fixed-seed generator, so the same points give the same plane), refit
/// by least squares to its inliers.
Plane dominant_plane(const std::vector<Eigen::Vector3d>& points, double tolerance) {
  auto inliers = [&](const Eigen::Vector3d& normal, const Eigen::Vector3d& origin) {
    std::size_t count = 0;
    for (const Eigen::Vector3d& p : points) count += std::abs(normal.dot(p - origin)) <= tolerance;
    return count;
  };
  std::mt19937 random(1);
  std::uniform_int_distribution<std::size_t> pick(0, points.size() - 1);
  Eigen::Vector3d best_normal = Eigen::Vector3d::UnitZ(), best_origin = points.front();
  std::size_t best = 0;
  for (int candidate = 0; candidate < 200; ++candidate) {
    const Eigen::Vector3d a = points[pick(random)], b = points[pick(random)], c = points[pick(random)];
    const Eigen::Vector3d n = (b - a).cross(c - a);
    if (!(n.norm() > 0.0)) continue;
    const std::size_t count = inliers(n.normalized(), a);
    if (count > best) {
      best = count;
      best_normal = n.normalized();
      best_origin = a;
    }
  }
  // Least squares over the inliers.
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  std::size_t count = 0;
  for (const Eigen::Vector3d& p : points)
    if (std::abs(best_normal.dot(p - best_origin)) <= tolerance) {
      mean += p;
      ++count;
    }
  if (count == 0) return {best_normal, -best_normal.dot(best_origin)};
  mean /= static_cast<double>(count);
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& p : points)
    if (std::abs(best_normal.dot(p - best_origin)) <= tolerance) scatter += (p - mean) * (p - mean).transpose();
  const Eigen::Vector3d normal = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(scatter).eigenvectors().col(0);
  return {normal, -normal.dot(mean)};
}

}  // namespace

std::optional<Eigen::Vector3d> PlaneOutline::pull_back(const Eigen::Vector3d& x, const Eigen::Vector3d& normal,
                                                       double margin) const {
  const std::size_t k = hull.size();
  if (k < 3) return std::nullopt;
  const Eigen::Vector3d plane_normal = u.cross(v);
  if (std::abs((x - origin).dot(plane_normal)) > near) return std::nullopt;
  const double length = normal.norm();
  if (!(length > 0.0 && std::abs(normal.dot(plane_normal)) >= least_cosine * length)) return std::nullopt;
  const Eigen::Vector2d p((x - origin).dot(u), (x - origin).dot(v));
  bool inside = true;
  for (std::size_t i = 0; i < k && inside; ++i) inside = cross(hull[(i + 1) % k] - hull[i], p - hull[i]) >= 0.0;
  if (inside) return std::nullopt;
  double best = std::numeric_limits<double>::infinity(), best_t = 0.0;
  std::size_t edge = 0;
  for (std::size_t i = 0; i < k; ++i) {
    double t = 0.0;
    const double d = segment_distance(p, hull[i], hull[(i + 1) % k], &t);
    if (d < best) {
      best = d;
      best_t = t;
      edge = i;
    }
  }
  if (!(best > margin)) return std::nullopt;
  // A corner limits only when both of its edges are drawn.
  const bool limits = best_t <= 0.0   ? drawn[edge] && drawn[(edge + k - 1) % k]
                      : best_t >= 1.0 ? drawn[edge] && drawn[(edge + 1) % k]
                                      : drawn[edge] != 0;
  if (!limits) return std::nullopt;
  const Eigen::Vector2d q = hull[edge] + best_t * (hull[(edge + 1) % k] - hull[edge]);
  return Eigen::Vector3d(origin + q.x() * u + q.y() * v);
}

std::vector<std::vector<PlaneOutline>> plane_outlines(const LabeledMesh& mesh,
                                                      const std::vector<ImplicitModel>& models,
                                                      const StrokeSegments& strokes, double diagonal,
                                                      const OutlineOptions& options) {
  std::vector<std::vector<PlaneOutline>> out(models.size());
  if (!(options.margin > 0.0) || strokes.points.rows() == 0) return out;
  const double tolerance = options.tolerance * diagonal, reach = options.reach * diagonal;
  // Per stroke point: the proxy face nearest to it, when within the tolerance.
  const Eigen::Index points = strokes.points.rows();
  std::vector<int> face(static_cast<std::size_t>(points), -1);
  {
    const ClosestFaceTree tree(vertex_matrix(mesh.mesh), face_matrix(mesh.mesh));
    for (Eigen::Index i = 0; i < points; ++i) {
      Eigen::Vector3d q;
      const Eigen::Vector3d p = strokes.points.row(i).transpose();
      const int f = tree.closest_face(p, &q);
      if (f >= 0 && (q - p).norm() <= tolerance) face[static_cast<std::size_t>(i)] = f;
    }
  }
  const double least_cosine = std::cos(options.angle * M_PI / 180.0);
  // The outline on `plane`: the hull of the stroke segments on it (the region's and any other's: a
  // stroke of the rim may lie beside another region's part of the proxy), each edge drawn or not.
  const auto outline_on = [&](const Plane& plane, std::vector<PlaneOutline>& into) {
    PlaneOutline outline;
    outline.origin = -plane.offset * plane.normal;  // the plane's point nearest the world origin
    outline.near = tolerance;
    outline.least_cosine = least_cosine;
    outline.u = plane.normal.unitOrthogonal();
    outline.v = plane.normal.cross(outline.u);
    auto in_plane = [&](int i) {
      const Eigen::Vector3d d = strokes.points.row(i).transpose() - outline.origin;
      return Eigen::Vector2d(d.dot(outline.u), d.dot(outline.v));
    };
    std::vector<Eigen::Vector2d> lines;  // two entries per segment
    for (Eigen::Index s = 0; s < strokes.segments.rows(); ++s) {
      const int i = strokes.segments(s, 0), j = strokes.segments(s, 1);
      if (std::abs(plane.signed_distance(strokes.points.row(i).transpose())) > tolerance ||
          std::abs(plane.signed_distance(strokes.points.row(j).transpose())) > tolerance)
        continue;
      lines.push_back(in_plane(i));
      lines.push_back(in_plane(j));
    }
    outline.hull = convex_hull(lines);
    const std::size_t k = outline.hull.size();
    if (k < 3) return;
    outline.drawn.assign(k, 0);
    for (std::size_t e = 0; e < k; ++e) {
      const Eigen::Vector2d a = outline.hull[e], b = outline.hull[(e + 1) % k];
      const int samples = std::max(2, static_cast<int>(std::ceil(2.0 * (b - a).norm() / reach)));
      int covered = 0;
      for (int j = 0; j < samples; ++j) {
        const Eigen::Vector2d p = a + (j + 0.5) / samples * (b - a);
        double t = 0.0;
        for (std::size_t s = 0; s < lines.size(); s += 2)
          if (segment_distance(p, lines[s], lines[s + 1], &t) <= reach) {
            ++covered;
            break;
          }
      }
      outline.drawn[e] = covered >= options.drawn_share * samples;
    }
    into.push_back(std::move(outline));
  };
  std::vector<double> distance(static_cast<std::size_t>(points));
  for (std::size_t m = 0; m < models.size(); ++m) {
    // The region's strokes: on its model's surface, beside its part of the proxy.
    implicit_distances(models[m], strokes.points, distance.data());
    auto in_region = [&](int i) {
      if (face[static_cast<std::size_t>(i)] < 0 || !(distance[static_cast<std::size_t>(i)] <= tolerance)) return false;
      for (auto v : mesh.mesh.fv_range(TriMesh::FaceHandle(face[static_cast<std::size_t>(i)]))) {
        const auto& l = mesh.labels[static_cast<std::size_t>(v.idx())];
        if (std::find(l.begin(), l.end(), static_cast<int>(m)) != l.end()) return true;
      }
      return false;
    };
    std::vector<int> on;
    for (Eigen::Index s = 0; s < strokes.segments.rows(); ++s)
      if (in_region(strokes.segments(s, 0)) && in_region(strokes.segments(s, 1))) on.push_back(static_cast<int>(s));
    if (on.size() < 3) continue;
    std::vector<Eigen::Vector3d> ink;
    for (int s : on) ink.push_back(strokes.points.row(strokes.segments(s, 0)).transpose());
    // Flat: on the plane, and the model's surface runs along it there.
    const auto along = [&](const Plane& plane, const Eigen::Vector3d& p) {
      const Eigen::Vector3d g = models[m].gradient(p);
      return std::abs(plane.signed_distance(p)) <= tolerance && g.norm() > 0.0 &&
             std::abs(g.dot(plane.normal)) >= least_cosine * g.norm();
    };
    const Plane plane = dominant_plane(ink, tolerance);
    std::size_t flat = 0;
    std::vector<Eigen::Vector3d> rest;
    for (const Eigen::Vector3d& p : ink) {
      flat += along(plane, p);
      if (!(std::abs(plane.signed_distance(p)) <= 2.0 * tolerance)) rest.push_back(p);
    }
    if (flat < options.flat_share * ink.size()) continue;
    outline_on(plane, out[m]);
    // A flat region's model may be a slab (a pair of parallel planes: a thin plate's two faces, a
    // face and a section through the solid); past its second plane's outline the region's
    // vertices spread as well. That plane lies clear of the first (no vertex near both) and
    // carries at least three of the region's strokes.
    if (rest.size() >= 3) {
      const Plane other = dominant_plane(rest, tolerance);
      std::size_t on_other = 0;
      for (const Eigen::Vector3d& p : rest) on_other += along(other, p);
      if (on_other >= 3 && std::abs(other.normal.dot(plane.normal)) >= least_cosine &&
          std::abs(plane.signed_distance(-other.offset * other.normal)) > 2.0 * tolerance)
        outline_on(other, out[m]);
    }
  }
  return out;
}

}  // namespace sketchsurf
