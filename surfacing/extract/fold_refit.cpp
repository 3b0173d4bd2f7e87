#include "surfacing/extract/fold_refit.h"

#include <algorithm>

#include "surfacing/closest_face.h"

namespace sketchsurf {

std::vector<int> fold_regions(const LabeledMesh& mesh, const std::vector<std::array<int, 2>>& folds,
                              double share) {
  std::vector<std::size_t> count;
  std::size_t triangles = 0;
  std::vector<int> labels;
  for (const auto& pair : folds)
    for (const int f : pair) {
      ++triangles;
      labels.clear();
      for (auto v : mesh.mesh.fv_range(mesh.mesh.face_handle(f)))
        labels.insert(labels.end(), mesh.labels[v.idx()].begin(), mesh.labels[v.idx()].end());
      std::sort(labels.begin(), labels.end());
      labels.erase(std::unique(labels.begin(), labels.end()), labels.end());
      for (const int r : labels) {
        if (static_cast<std::size_t>(r) >= count.size()) count.resize(static_cast<std::size_t>(r) + 1, 0);
        ++count[static_cast<std::size_t>(r)];
      }
    }
  std::vector<int> out;
  for (std::size_t r = 0; r < count.size(); ++r)
    if (triangles > 0 && static_cast<double>(count[r]) >= share * static_cast<double>(triangles))
      out.push_back(static_cast<int>(r));
  return out;
}

std::vector<ImplicitModel> refit_regions(const LabeledMesh& mesh, const Eigen::MatrixX3d& positions,
                                         const std::vector<ImplicitModel>& models,
                                         const std::vector<int>& regions, const Eigen::MatrixX3d& strokes,
                                         int degree, double reach, double diagonal, std::size_t least,
                                         std::size_t* refitted) {
  std::vector<ImplicitModel> out = models;
  if (refitted) *refitted = 0;
  std::vector<char> wanted(models.size(), 0);
  for (const int r : regions)
    if (models[static_cast<std::size_t>(r)].degree > degree) wanted[static_cast<std::size_t>(r)] = 1;
  if (std::none_of(wanted.begin(), wanted.end(), [](char w) { return w != 0; })) return out;

  const Eigen::MatrixX3i F = face_matrix(mesh.mesh);
  const ClosestFaceTree tree(positions, F);
  std::vector<std::vector<Eigen::Index>> points(models.size());
  for (Eigen::Index i = 0; i < strokes.rows(); ++i) {
    const Eigen::Vector3d p = strokes.row(i).transpose();
    Eigen::Vector3d q;
    const int f = tree.closest_face(p, &q);
    if (f < 0 || (q - p).norm() > reach) continue;
    const int r = face_region(mesh, F, f);
    if (wanted[static_cast<std::size_t>(r)]) points[static_cast<std::size_t>(r)].push_back(i);
  }
  Eigen::MatrixX3d normals = Eigen::MatrixX3d::Zero(positions.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = positions.row(F(f, 0)), b = positions.row(F(f, 1)), c = positions.row(F(f, 2));
    const Eigen::RowVector3d n = (b - a).cross(c - a).transpose();
    for (int k = 0; k < 3; ++k) normals.row(F(f, k)) += n;
  }
  FitOptions fit;
  fit.length_unit = diagonal;
  for (std::size_t r = 0; r < models.size(); ++r) {
    if (!wanted[r] || points[r].size() < least) continue;
    std::vector<Eigen::Index> own;
    for (std::size_t v = 0; v < mesh.labels.size(); ++v)
      if (mesh.labels[v].size() == 1 && mesh.labels[v].front() == static_cast<int>(r) &&
          normals.row(static_cast<Eigen::Index>(v)).squaredNorm() > 0.0)
        own.push_back(static_cast<Eigen::Index>(v));
    Eigen::MatrixX3d P(static_cast<Eigen::Index>(points[r].size()), 3);
    for (std::size_t i = 0; i < points[r].size(); ++i) P.row(static_cast<Eigen::Index>(i)) = strokes.row(points[r][i]);
    Eigen::MatrixX3d at(static_cast<Eigen::Index>(own.size()), 3), n(static_cast<Eigen::Index>(own.size()), 3);
    for (std::size_t i = 0; i < own.size(); ++i) {
      at.row(static_cast<Eigen::Index>(i)) = positions.row(own[i]);
      n.row(static_cast<Eigen::Index>(i)) = normals.row(own[i]).normalized();
    }
    out[r] = fit_implicit(degree, P, at, n, fit);
    if (refitted) ++*refitted;
  }
  return out;
}

}  // namespace sketchsurf
