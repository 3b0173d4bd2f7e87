#include "surfacing/extract/smooth_fallback.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "surfacing/closest_face.h"

namespace sketchsurf {

bool SmoothFallbackOptions::valid(std::string* why) const {
  if (!(reach > 0.0 && reach < 1.0)) {
    if (why) *why = "extract smooth_fallback reach must be in (0, 1)";
    return false;
  }
  if (!(margin >= 0.0)) {
    if (why) *why = "extract smooth_fallback margin must be >= 0";
    return false;
  }
  if (!(rounded_margin > -1.0 && rounded_margin <= margin)) {
    if (why) *why = "extract smooth_fallback rounded_margin must be in (-1, margin]";
    return false;
  }
  if (rounded_degree < 0 || rounded_degree > 4) {
    if (why) *why = "extract smooth_fallback rounded_degree must be in [0, 4]";
    return false;
  }
  if (!(agree > 0.0)) {
    if (why) *why = "extract smooth_fallback agree must be > 0";
    return false;
  }
  if (!(pull_ratio >= 1.0)) {
    if (why) *why = "extract smooth_fallback pull_ratio must be >= 1";
    return false;
  }
  if (!(pull_weight >= 0.0)) {
    if (why) *why = "extract smooth_fallback pull_weight must be >= 0";
    return false;
  }
  if (!(pull_curvature >= 0.0)) {
    if (why) *why = "extract smooth_fallback pull_curvature must be >= 0";
    return false;
  }
  return true;
}

namespace {

// The smaller absolute principal curvature of the level set of `model` through x (1 / length):
// the eigenvalues of the unit normal's derivative in the tangent plane, by central differences
// of step h. 0 on a plane, a cylinder or a cone; 1 / r on a sphere of radius r.
double smaller_curvature(const ImplicitModel& model, const Eigen::Vector3d& x, double h) {
  const auto unit_normal = [&](const Eigen::Vector3d& y) {
    const Eigen::Vector3d g = model.gradient(y);
    const double length = g.norm();
    return length > 0.0 ? Eigen::Vector3d(g / length) : Eigen::Vector3d::Zero();
  };
  const Eigen::Vector3d n = unit_normal(x);
  if (n.isZero()) return 0.0;
  Eigen::Matrix3d J;
  for (int c = 0; c < 3; ++c) {
    const Eigen::Vector3d e = h * Eigen::Vector3d::Unit(c);
    J.col(c) = (unit_normal(x + e) - unit_normal(x - e)) / (2.0 * h);
  }
  const Eigen::Vector3d t1 = n.unitOrthogonal(), t2 = n.cross(t1);
  const double a = t1.dot(J * t1), d = t2.dot(J * t2), b = 0.5 * (t1.dot(J * t2) + t2.dot(J * t1));
  const double mean = 0.5 * (a + d), spread = std::sqrt(0.25 * (a - d) * (a - d) + b * b);
  return std::min(std::abs(mean + spread), std::abs(mean - spread));
}

}  // namespace

std::vector<char> regions_at_proxy(const LabeledMesh& mesh, const std::vector<ImplicitModel>& models,
                                   const StrokeSegments& strokes, double diagonal,
                                   const SmoothFallbackOptions& options, const MeshEnergyOptions& energy,
                                   SmoothFallbackSummary* summary) {
  std::vector<char> kept(models.size(), 0);
  SmoothFallbackSummary local;
  SmoothFallbackSummary& out = summary ? *summary : local;
  out.regions = out.kept = out.held = out.pulled = 0;
  const Eigen::MatrixX3d V = vertex_matrix(mesh.mesh);
  const Eigen::MatrixX3i F = face_matrix(mesh.mesh);
  if (!options.enabled || F.rows() == 0 || strokes.points.rows() == 0) return kept;

  const ClosestFaceTree tree(V, F);
  const double reach = options.reach * diagonal;
  std::vector<double> to_proxy(models.size(), 0.0), to_model(models.size(), 0.0);
  std::vector<std::size_t> count(models.size(), 0);
  for (Eigen::Index i = 0; i < strokes.points.rows(); ++i) {
    const Eigen::Vector3d p = strokes.points.row(i).transpose();
    Eigen::Vector3d q;
    const int f = tree.closest_face(p, &q);
    const double d = (q - p).norm();
    if (f < 0 || d > reach) continue;
    const int r = face_region(mesh, F, f);
    const double m = models[static_cast<std::size_t>(r)].distance(p);
    to_proxy[r] += d * d;
    to_model[r] += std::isfinite(m) ? std::min(m * m, reach * reach) : reach * reach;
    ++count[r];
  }
  // Curved regions with enough points: the proxy closer to their strokes, or only a little
  // farther (a candidate for the pull).
  std::vector<char> closer(models.size(), 0), nearly(models.size(), 0);
  for (std::size_t r = 0; r < models.size(); ++r) {
    if (count[r] < options.min_points || models[r].degree <= 1) continue;
    const bool low = options.rounded && models[r].degree <= options.rounded_degree;
    const double margin = low ? options.rounded_margin : options.margin;
    closer[r] = options.hold_curved || to_proxy[r] < (1.0 + margin) * to_model[r];
    nearly[r] = !closer[r] && !low && to_proxy[r] < options.pull_ratio * to_model[r];
  }
  out.regions = static_cast<std::size_t>(
      std::count_if(count.begin(), count.end(), [&](std::size_t c) { return c >= options.min_points; }));
  // The candidates are pulled when doubly curved at their own vertices.
  std::vector<char> pull(models.size(), 0);
  std::vector<std::vector<double>> curvatures(models.size());
  for (std::size_t v = 0; v < mesh.labels.size(); ++v) {
    if (mesh.labels[v].size() != 1) continue;
    const int r = mesh.labels[v].front();
    if (nearly[r])
      curvatures[r].push_back(
          smaller_curvature(models[r], V.row(static_cast<Eigen::Index>(v)).transpose(), 1e-3 * diagonal));
  }
  for (std::size_t r = 0; r < models.size(); ++r) {
    auto& k = curvatures[r];
    if (k.empty()) continue;
    const auto median = k.begin() + static_cast<std::ptrdiff_t>(k.size() / 2);
    std::nth_element(k.begin(), median, k.end());
    pull[r] = *median * diagonal >= options.pull_curvature;
  }
  const auto any = [](const std::vector<char>& flags) {
    return std::any_of(flags.begin(), flags.end(), [](char c) { return c != 0; });
  };
  if (!any(closer) && !any(pull)) return kept;

  // How far the start of the solve (optimize.h) would move each region's own vertices (not
  // asked when every curved region is held).
  std::vector<std::vector<double>> moves(models.size());
  if (!options.hold_curved) {
    LabeledMesh projected = mesh;
    project_vertices(projected, models, energy.projection_steps, energy.max_projection_step * diagonal,
                     energy.threads, std::vector<char>(mesh.labels.size(), 0));
    for (auto v : mesh.mesh.vertices())
      if (mesh.labels[v.idx()].size() == 1)
        moves[mesh.labels[v.idx()].front()].push_back(
            (to_eigen(mesh.mesh.point(v)) - to_eigen(projected.mesh.point(v))).norm());
  }
  for (std::size_t r = 0; r < models.size(); ++r) {
    if (!closer[r] && !pull[r]) continue;
    auto& m = moves[r];
    const auto p95 = m.begin() + static_cast<std::ptrdiff_t>(m.size() * 95 / 100);
    if (p95 != m.end()) std::nth_element(m.begin(), p95, m.end());
    // The model reshapes it; not asked of a region held at a proxy that follows its strokes
    // (rounded): there a model reshaping it strays from them between them.
    if (!(options.rounded && closer[r]) && p95 != m.end() && *p95 > options.agree * diagonal) continue;
    kept[r] = closer[r] ? kRegionHeld : kRegionPulled;
    ++(closer[r] ? out.kept : out.pulled);
  }
  for (const auto& labels : mesh.labels)
    out.held += std::any_of(labels.begin(), labels.end(), [&](int l) { return kept[l] == kRegionHeld; });
  return kept;
}

void keep_smooth_proxy(TriMesh& mesh, const Eigen::MatrixX3d& start, const std::vector<std::uint8_t>& sharp,
                       const std::vector<char>& held, const StrokeSegments& strokes, double diagonal,
                       const SmoothFallbackOptions& options, SmoothFallbackSummary* out) {
  SmoothFallbackSummary local;
  SmoothFallbackSummary& summary = out ? *out : local;
  summary.parts = summary.reverted = summary.vertices = 0;
  const Eigen::MatrixX3d now = vertex_matrix(mesh);
  const Eigen::MatrixX3i F = face_matrix(mesh);
  if (!options.enabled || F.rows() == 0 || now.rows() != start.rows() || strokes.points.rows() == 0)
    return;

  // Connected parts (through faces) and whether each has a crease vertex.
  const std::vector<int> part = vertex_components(F, now.rows());
  const auto find = [&](int v) { return part[static_cast<std::size_t>(v)]; };
  std::vector<char> creased(part.size(), 0), all_held(part.size(), 1);
  for (std::size_t v = 0; v < part.size(); ++v) {
    if (v < sharp.size() && sharp[v]) creased[find(static_cast<int>(v))] = 1;
    if (!(v < held.size() && held[v])) all_held[find(static_cast<int>(v))] = 0;
  }

  // Squared distances of the stroke points near each part, now and at the start.
  const ClosestFaceTree tree_now(now, F), tree_start(start, F);
  const double reach = options.reach * diagonal;
  std::vector<double> sum_now(part.size(), 0.0), sum_start(part.size(), 0.0);
  std::vector<std::size_t> count(part.size(), 0);
  for (Eigen::Index i = 0; i < strokes.points.rows(); ++i) {
    const Eigen::Vector3d p = strokes.points.row(i).transpose();
    Eigen::Vector3d q_now, q_start;
    const int f = tree_now.closest_face(p, &q_now);
    if (f < 0 || (q_now - p).norm() > reach) continue;
    const int r = find(F(f, 0));
    if (creased[r]) continue;
    tree_start.closest_face(p, &q_start);
    sum_now[r] += (q_now - p).squaredNorm();
    sum_start[r] += (q_start - p).squaredNorm();
    ++count[r];
  }
  std::vector<char> revert(part.size(), 0);
  for (std::size_t r = 0; r < part.size(); ++r) {
    if (find(static_cast<int>(r)) != static_cast<int>(r) || creased[r]) continue;
    ++summary.parts;
    if (all_held[r] || (count[r] >= options.min_points && sum_start[r] < sum_now[r])) {
      revert[r] = 1;
      ++summary.reverted;
    }
  }
  for (const auto v : mesh.vertices())
    if (revert[find(v.idx())]) {
      mesh.set_point(v, to_openmesh(Eigen::Vector3d(start.row(v.idx()).transpose())));
      ++summary.vertices;
    }
  if (summary.vertices > 0) mesh.update_normals();
}

}  // namespace sketchsurf
