#include "surfacing/quality/eval.h"

#include <algorithm>
#include <cmath>

#include "surfacing/closest_face.h"
#include "surfacing/error.h"
#include "surfacing/parallel.h"
#include "surfacing/portable_math.h"

namespace sketchsurf {

namespace {

using V3 = Eigen::Vector3d;

double mesh_diagonal(const Eigen::MatrixX3d& V) {
  if (V.rows() == 0) return 0.0;
  return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
}

// Distance from every row of `points` to the surface of `tree`, divided by `scale`.
std::vector<double> distances(const Eigen::MatrixX3d& points, const ClosestFaceTree& tree,
                              double scale, unsigned threads) {
  std::vector<double> d(static_cast<std::size_t>(points.rows()));
  parallel_for(0, d.size(), threads, [&](std::size_t i) {
    const V3 p = points.row(static_cast<Eigen::Index>(i));
    V3 q;
    tree.closest_face(p, &q);
    d[i] = (q - p).norm() / scale;
  });
  return d;
}

Eigen::MatrixX3d face_normals(const Eigen::MatrixX3d& V, const Eigen::MatrixX3i& F) {
  Eigen::MatrixX3d N(F.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const V3 a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    N.row(f) = (b - a).cross(c - a).normalized();
  }
  return N;
}

double angle_degrees(const V3& a, const V3& b) {
  return portable::acos(std::clamp(a.dot(b), -1.0, 1.0)) * 180.0 / M_PI;
}

CreaseEvaluation evaluate_creases(const TriMesh& truth, const Eigen::MatrixX3d& result_normals,
                                  const ClosestFaceTree& result_tree, double diagonal,
                                  const EvalOptions& options) {
  struct SharpEdge {
    V3 midpoint, into[2];
    double angle, length;
  };
  std::vector<SharpEdge> edges;
  for (auto e : truth.edges()) {
    if (truth.is_boundary(e)) continue;
    const auto h0 = truth.halfedge_handle(e, 0), h1 = truth.halfedge_handle(e, 1);
    const V3 n0 = to_eigen(truth.calc_face_normal(truth.face_handle(h0)));
    const V3 n1 = to_eigen(truth.calc_face_normal(truth.face_handle(h1)));
    const double angle = angle_degrees(n0, n1);
    if (!(angle > options.sharp_angle)) continue;
    const V3 a = to_eigen(truth.point(truth.from_vertex_handle(h0)));
    const V3 b = to_eigen(truth.point(truth.to_vertex_handle(h0)));
    SharpEdge s{0.5 * (a + b), {}, angle, (b - a).norm()};
    const V3 t = (b - a).normalized();
    const auto opposite = [&](TriMesh::HalfedgeHandle h) {
      return to_eigen(truth.point(truth.to_vertex_handle(truth.next_halfedge_handle(h))));
    };
    const V3 c[2] = {opposite(h0), opposite(h1)};
    for (int k = 0; k < 2; ++k) {
      V3 d = c[k] - s.midpoint;
      d -= d.dot(t) * t;
      s.into[k] = d.normalized();
    }
    edges.push_back(s);
  }
  CreaseEvaluation out;
  out.sharp_edges = edges.size();
  if (edges.empty()) return out;
  std::vector<double> result_angle(edges.size());
  parallel_for(0, edges.size(), options.threads, [&](std::size_t i) {
    V3 n[2];
    for (int k = 0; k < 2; ++k) {
      const int f = result_tree.closest_face(edges[i].midpoint + options.probe * diagonal * edges[i].into[k]);
      n[k] = result_normals.row(f);
    }
    result_angle[i] = angle_degrees(n[0], n[1]);
  });
  double total = 0.0, found = 0.0;
  std::vector<double> errors;
  for (std::size_t i = 0; i < edges.size(); ++i) {
    total += edges[i].length;
    if (!(result_angle[i] > options.crease_angle)) continue;
    found += edges[i].length;
    errors.push_back(std::abs(result_angle[i] - edges[i].angle));
  }
  out.found = found / total;
  out.error = distance_stats(std::move(errors));
  return out;
}

}  // namespace

bool EvalOptions::valid(std::string* why) const {
  const auto fail = [&](const char* message) {
    if (why) *why = message;
    return false;
  };
  if (samples < 1) return fail("eval samples must be at least 1");
  if (!(sharp_angle > 0.0 && sharp_angle < 180.0)) return fail("the sharp angle must be in (0, 180) degrees");
  if (!(crease_angle > 0.0 && crease_angle < 180.0)) return fail("the crease angle must be in (0, 180) degrees");
  if (!(probe > 0.0 && probe < 0.5)) return fail("the crease probe must be in (0, 0.5) of the diagonal");
  return true;
}

Evaluation evaluate(const TriMesh& result, const TriMesh& truth, const EvalOptions& options) {
  std::string why;
  if (!options.valid(&why)) throw Error::usage(why);
  const Eigen::MatrixX3d RV = vertex_matrix(result), TV = vertex_matrix(truth);
  const Eigen::MatrixX3i RF = face_matrix(result), TF = face_matrix(truth);
  Evaluation out;
  out.diagonal = mesh_diagonal(TV);
  const SurfaceSamples on_result = sample_surface(result, options.samples, options.seed);
  const SurfaceSamples on_truth = sample_surface(truth, options.samples, options.seed + 1);
  if (!(on_result.area > 0.0)) throw Error::processing("the result surface has no area");
  if (!(on_truth.area > 0.0) || !(out.diagonal > 0.0)) throw Error::processing("the true surface has no area");
  const ClosestFaceTree truth_tree(TV, TF), result_tree(RV, RF);
  out.accuracy = distance_stats(distances(on_result.points, truth_tree, out.diagonal, options.threads));
  out.completeness = distance_stats(distances(on_truth.points, result_tree, out.diagonal, options.threads));
  out.vertex_deviation = distances(RV, truth_tree, out.diagonal, options.threads);
  out.creases = evaluate_creases(truth, face_normals(RV, RF), result_tree, out.diagonal, options);
  return out;
}

std::array<std::uint8_t, 3> deviation_color(double deviation, double full_scale) {
  // Piecewise-linear ramp blue -> cyan -> green -> yellow -> red.
  static const double stops[5][3] = {{0.19, 0.31, 0.85}, {0.2, 0.75, 0.9}, {0.3, 0.8, 0.3},
                                     {0.95, 0.85, 0.2}, {0.85, 0.15, 0.1}};
  const double t = full_scale > 0.0 ? std::clamp(deviation / full_scale, 0.0, 1.0) * 4.0 : 0.0;
  const int i = std::min(3, static_cast<int>(t));
  const double w = t - i;
  std::array<std::uint8_t, 3> rgb{};
  for (int k = 0; k < 3; ++k)
    rgb[k] = static_cast<std::uint8_t>(std::lround(255.0 * ((1 - w) * stops[i][k] + w * stops[i + 1][k])));
  return rgb;
}

}  // namespace sketchsurf
