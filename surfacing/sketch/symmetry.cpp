#include "surfacing/sketch/symmetry.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <vector>

#include "surfacing/closest_face.h"
#include "surfacing/sketch/stroke_segments.h"

namespace sketchsurf {

namespace {

using V3 = Eigen::Vector3d;

struct Score {
  double distance = 0.0;  // 90th percentile, sketch units
  double balance = 0.0;   // smaller share of points on one side
};

Score score(const Plane& plane, const std::vector<V3>& points, const ClosestFaceTree& tree) {
  std::vector<double> d(points.size());
  std::size_t positive = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    V3 q;
    tree.closest_face(plane.reflect(points[i]), &q);
    d[i] = (q - plane.reflect(points[i])).norm();
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
Plane refine(const Plane& plane, const std::vector<V3>& points, const ClosestFaceTree& tree) {
  V3 direction = V3::Zero(), middle = V3::Zero();
  for (const V3& p : points) {
    V3 m;
    tree.closest_face(plane.reflect(p), &m);
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
    for (int i = 0; i < options.iterations; ++i) plane = refine(plane, points, tree);
    const Score s = score(plane, points, tree);
    if (s.distance > options.tolerance * diagonal || s.balance < options.balance) continue;
    if (!best || s.distance < best->distance * diagonal) best = DetectedMirror{plane, s.distance / diagonal};
  }
  return best;
}

}  // namespace sketchsurf
