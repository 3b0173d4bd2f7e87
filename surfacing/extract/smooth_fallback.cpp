#include "surfacing/extract/smooth_fallback.h"

#include <string>

#include "surfacing/closest_face.h"

namespace sketchsurf {

bool SmoothFallbackOptions::valid(std::string* why) const {
  if (!(reach > 0.0 && reach < 1.0)) {
    if (why) *why = "extract smooth_fallback reach must be in (0, 1)";
    return false;
  }
  return true;
}

SmoothFallbackSummary keep_smooth_proxy(TriMesh& mesh, const Eigen::MatrixX3d& start,
                                        const std::vector<std::uint8_t>& sharp,
                                        const StrokeSegments& strokes, double diagonal,
                                        const SmoothFallbackOptions& options) {
  SmoothFallbackSummary summary;
  const Eigen::MatrixX3d now = vertex_matrix(mesh);
  const Eigen::MatrixX3i F = face_matrix(mesh);
  if (!options.enabled || F.rows() == 0 || now.rows() != start.rows() || strokes.points.rows() == 0)
    return summary;

  // Connected parts (through faces) and whether each has a crease vertex.
  const std::vector<int> part = vertex_components(F, now.rows());
  const auto find = [&](int v) { return part[static_cast<std::size_t>(v)]; };
  std::vector<char> creased(part.size(), 0);
  for (std::size_t v = 0; v < part.size(); ++v)
    if (v < sharp.size() && sharp[v]) creased[find(static_cast<int>(v))] = 1;

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
    if (count[r] >= options.min_points && sum_start[r] < sum_now[r]) {
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
  return summary;
}

}  // namespace sketchsurf
