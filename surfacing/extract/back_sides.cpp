#include "surfacing/extract/back_sides.h"

#include <cmath>
#include <string>

namespace sketchsurf {

bool BackSideOptions::valid(std::string* why) const {
  if (!(gap >= 0.0 && gap < 0.1)) {
    if (why) *why = "extract back_sides gap must be in [0, 0.1)";
    return false;
  }
  if (!(facing >= -1.0 && facing <= 0.0)) {
    if (why) *why = "extract back_sides facing must be in [-1, 0]";
    return false;
  }
  return true;
}

std::vector<int> find_back_sides(const LabeledMesh& mesh, const std::vector<ImplicitModel>& models,
                                 const BackSideOptions& options) {
  std::vector<int> back;
  if (!(options.gap > 0.0)) return back;
  const Eigen::MatrixX3d V = vertex_matrix(mesh.mesh);
  const Eigen::MatrixX3d normal = vertex_normals(V, face_matrix(mesh.mesh));
  for (Eigen::Index v = 0; v < V.rows(); ++v) {
    const auto& labels = mesh.labels[v];
    if (labels.size() != 1) continue;
    const Eigen::Vector3d g = models[labels.front()].gradient(V.row(v).transpose());
    const double norm = g.norm();
    if (std::isfinite(norm) && norm > 0.0 && normal.row(v).dot(g) < options.facing * norm)
      back.push_back(static_cast<int>(v));
  }
  return back;
}

}  // namespace sketchsurf
