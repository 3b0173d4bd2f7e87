#include "surfacing/sketch/symmetry.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <vector>

#include "surfacing/closest_face.h"
#include "surfacing/parallel.h"
#include "surfacing/portable_math.h"
#include "surfacing/sketch/stroke_point_grid.h"
#include "surfacing/sketch/stroke_segments.h"

namespace sketchsurf {

namespace {

using V3 = Eigen::Vector3d;

struct Score {
  double distance = 0.0;  // 90th percentile, sketch units
  double balance = 0.0;   // smaller share of points on one side
};

// The stroke point nearest to each point's reflection, on `threads` threads.
std::vector<V3> mirror_partners(const Plane& plane, const std::vector<V3>& points, const ClosestFaceTree& tree,
                                unsigned threads) {
  std::vector<V3> out(points.size());
  parallel_for(0, points.size(), threads, [&](std::size_t i) { tree.closest_face(plane.reflect(points[i]), &out[i]); });
  return out;
}

Score score(const Plane& plane, const std::vector<V3>& points, const ClosestFaceTree& tree, unsigned threads) {
  const std::vector<V3> partners = mirror_partners(plane, points, tree, threads);
  std::vector<double> d(points.size());
  std::size_t positive = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    d[i] = (partners[i] - plane.reflect(points[i])).norm();
    positive += plane.signed_distance(points[i]) > 0.0;
  }
  const std::size_t k = (d.size() * 9) / 10;
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(k), d.end());
  const double share = static_cast<double>(positive) / static_cast<double>(points.size());
  return {d[k], std::min(share, 1.0 - share)};
}

// One refinement: each point paired with the stroke point nearest to its reflection; the new
// normal is the mean of the pairs' differences (oriented along the old normal), the new plane
// passes through the mean of their midpoints.
Plane refine(const Plane& plane, const std::vector<V3>& points, const ClosestFaceTree& tree, unsigned threads) {
  const std::vector<V3> partners = mirror_partners(plane, points, tree, threads);
  V3 direction = V3::Zero(), middle = V3::Zero();
  for (std::size_t i = 0; i < points.size(); ++i) {
    const V3& p = points[i];
    const V3& m = partners[i];
    V3 d = p - m;
    if (d.dot(plane.normal) < 0.0) d = -d;
    direction += d;
    middle += 0.5 * (p + m);
  }
  if (!(direction.norm() > 0.0)) return plane;
  Plane out;
  out.normal = direction.normalized();
  out.offset = -out.normal.dot(middle / static_cast<double>(points.size()));
  return out;
}

}  // namespace

bool MirrorDetectOptions::valid(std::string* why) const {
  const auto fail = [&](const char* message) {
    if (why) *why = message;
    return false;
  };
  if (!(tolerance > 0.0 && tolerance < 0.5)) return fail("mirror detection tolerance must be in (0, 0.5)");
  if (!(balance >= 0.0 && balance <= 0.5)) return fail("mirror detection balance must be in [0, 0.5]");
  if (iterations < 0) return fail("mirror detection iterations must be >= 0");
  if (half_ends < 2) return fail("mirror detection half_ends must be at least 2");
  if (!(half_angle > 0.0 && half_angle < 90.0)) return fail("mirror detection half_angle must be in (0, 90) degrees");
  if (!(free_end >= 0.0 && free_end < 0.5)) return fail("mirror detection free_end must be in [0, 0.5)");
  return true;
}

std::optional<DetectedMirror> detect_mirror(const Sketch& sketch, const MirrorDetectOptions& options) {
  const StrokeSegments strokes = stroke_segments(sketch, false);
  const Eigen::MatrixX3d& V = strokes.points;
  if (V.rows() < 4) return std::nullopt;
  const double diagonal = strokes.box.diagonal();
  if (!(diagonal > 0.0)) return std::nullopt;
  std::vector<V3> points(static_cast<std::size_t>(V.rows()));
  for (std::size_t i = 0; i < points.size(); ++i) points[i] = V.row(static_cast<Eigen::Index>(i));
  const ClosestFaceTree tree(V, strokes.segments);

  const V3 centroid = V.colwise().mean();
  const Eigen::Matrix3d covariance = (V.rowwise() - centroid.transpose()).transpose() *
                                     (V.rowwise() - centroid.transpose());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> pca(covariance);
  std::vector<V3> normals = {pca.eigenvectors().col(0), pca.eigenvectors().col(1),
                             pca.eigenvectors().col(2), V3::UnitX(), V3::UnitY(), V3::UnitZ()};

  std::optional<DetectedMirror> best;
  for (const V3& n : normals) {
    Plane plane;
    plane.normal = n.normalized();
    plane.offset = -plane.normal.dot(centroid);
    for (int i = 0; i < options.iterations; ++i) plane = refine(plane, points, tree, options.threads);
    const Score s = score(plane, points, tree, options.threads);
    if (s.distance > options.tolerance * diagonal || s.balance < options.balance) continue;
    if (!best || s.distance < best->distance * diagonal) best = DetectedMirror{plane, s.distance / diagonal};
  }
  return best;
}

namespace {

// A free end of an open stroke: where it is and the direction the stroke arrives in (unit).
struct FreeEnd {
  V3 position;
  V3 arrival;
};

std::vector<FreeEnd> free_ends(const Sketch& sketch, double diagonal, const MirrorDetectOptions& options) {
  std::vector<FreeEnd> ends;
  const double reach = options.free_end * diagonal;
  const StrokePointGrid grid(sketch, std::max(reach, 1e-6 * diagonal), /*with_ignored=*/false);
  for (std::size_t s = 0; s < sketch.strokes.size(); ++s) {
    const Stroke& stroke = sketch.strokes[s];
    const auto& p = stroke.points;
    if (stroke.ignored || p.size() < 3 || (p.front() - p.back()).norm() <= options.tolerance * diagonal ||
        stroke.length() < 4.0 * reach)
      continue;  // closed, or too short to have a direction
    for (const bool at_start : {true, false}) {
      const V3& end = at_start ? p.front() : p.back();
      // The arrival: from the point 1% of the diagonal back along the stroke.
      V3 back = end;
      double run = 0.0;
      for (std::size_t j = 1; j < p.size() && run < 0.01 * diagonal; ++j) {
        const V3& q = at_start ? p[j] : p[p.size() - 1 - j];
        run += (q - back).norm();
        back = q;
      }
      if ((end - back).norm() > 0.0 && grid.strokes_near(end, s, reach).empty())
        ends.push_back({end, (end - back).normalized()});
    }
  }
  return ends;
}

}  // namespace

std::optional<DetectedMirror> detect_half_mirror(const Sketch& sketch, const MirrorDetectOptions& options) {
  const StrokeSegments strokes = stroke_segments(sketch, false);
  if (strokes.points.rows() < 4) return std::nullopt;
  const double diagonal = strokes.box.diagonal();
  if (!(diagonal > 0.0)) return std::nullopt;
  const std::vector<FreeEnd> ends = free_ends(sketch, diagonal, options);
  const double tolerance = options.tolerance * diagonal;
  const double arrives = portable::cos(options.half_angle * M_PI / 180.0);

  std::optional<DetectedMirror> best;
  for (const FreeEnd& seed : ends) {
    // The plane through the seed normal to its arrival, normal toward the strokes; refitted to
    // the ends it gathers, twice.
    Plane plane{-seed.arrival, seed.arrival.dot(seed.position)};
    std::vector<const FreeEnd*> on;
    for (int round = 0; round < 3; ++round) {
      on.clear();
      V3 arrival = V3::Zero(), centre = V3::Zero();
      for (const FreeEnd& e : ends)
        if (std::abs(plane.signed_distance(e.position)) <= tolerance && -e.arrival.dot(plane.normal) >= arrives) {
          on.push_back(&e);
          arrival += e.arrival;
          centre += e.position;
        }
      if (on.empty() || round == 2) break;
      // The plane of the ends' positions (sharper than their arrivals) when they spread over it;
      // else normal to their mean arrival.
      centre /= static_cast<double>(on.size());
      Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
      for (const FreeEnd* e : on) covariance += (e->position - centre) * (e->position - centre).transpose();
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> pca(covariance);
      const bool spread = on.size() >= 3 && pca.eigenvalues()(1) > 100.0 * std::max(pca.eigenvalues()(0), 0.0);
      plane.normal = spread ? V3(pca.eigenvectors().col(0)) : V3(-arrival.normalized());
      if (plane.normal.dot(arrival) > 0.0) plane.normal = -plane.normal;
      plane.offset = -plane.normal.dot(centre);
    }
    if (static_cast<int>(on.size()) < options.half_ends) continue;
    if (best && static_cast<int>(on.size()) <= best->half_ends) continue;
    // Every stroke on the kept side.
    if ((strokes.points * plane.normal).minCoeff() + plane.offset < -tolerance) continue;
    std::vector<double> d;
    for (const FreeEnd* e : on) d.push_back(std::abs(plane.signed_distance(e->position)));
    std::sort(d.begin(), d.end());
    best = DetectedMirror{plane, d[(d.size() * 9) / 10] / diagonal, static_cast<int>(on.size())};
  }
  return best;
}

namespace {

// A stroke's points (and per-point attributes) taken in `order`: (from the image?, index).
Stroke gathered(const Stroke& stroke, const Stroke& image, const std::vector<std::pair<bool, std::size_t>>& order) {
  Stroke out = stroke;
  out.points.clear();
  out.orientations.clear();
  out.pressures.clear();
  out.timestamps_ms.clear();
  for (const auto& [from_image, i] : order) {
    const Stroke& s = from_image ? image : stroke;
    out.points.push_back(s.points[i]);
    if (!s.orientations.empty()) out.orientations.push_back(s.orientations[i]);
    if (!s.pressures.empty()) out.pressures.push_back(s.pressures[i]);
    if (!s.timestamps_ms.empty()) out.timestamps_ms.push_back(s.timestamps_ms[i]);
  }
  return out;
}

}  // namespace

void complete_half(Sketch& sketch, const Plane& plane, double tolerance) {
  std::int64_t id = 0;
  for (const Stroke& s : sketch.strokes) id = std::max(id, s.id);
  const std::size_t n = sketch.strokes.size();
  for (std::size_t i = 0; i < n; ++i) {
    Stroke& stroke = sketch.strokes[i];
    auto& p = stroke.points;
    const auto on = [&](const V3& x) { return std::abs(plane.signed_distance(x)) <= tolerance; };
    if (p.empty() || std::all_of(p.begin(), p.end(), on)) continue;  // its own image
    const bool first_on = p.size() >= 2 && on(p.front()), last_on = p.size() >= 2 && on(p.back());
    if (first_on) p.front() -= plane.signed_distance(p.front()) * plane.normal;
    if (last_on) p.back() -= plane.signed_distance(p.back()) * plane.normal;
    const Stroke image = mirrored(stroke, plane);
    if (!first_on && !last_on) {
      sketch.strokes.push_back(image);
      sketch.strokes.back().id = ++id;
      continue;
    }
    // Through the plane: the stroke and its image as one (closed when both ends are on it).
    std::vector<std::pair<bool, std::size_t>> order;
    const std::size_t m = p.size();
    if (last_on) {
      for (std::size_t j = 0; j < m; ++j) order.emplace_back(false, j);
      for (std::size_t j = m - 1; j-- > 0;) order.emplace_back(true, j);
    } else {
      for (std::size_t j = m; j-- > 1;) order.emplace_back(true, j);
      for (std::size_t j = 0; j < m; ++j) order.emplace_back(false, j);
    }
    stroke = gathered(stroke, image, order);
  }
}

}  // namespace sketchsurf
