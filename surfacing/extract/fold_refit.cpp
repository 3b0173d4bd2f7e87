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

RegionSamples region_samples(const LabeledMesh& mesh, const Eigen::MatrixX3d& positions,
                             const std::vector<int>& regions, const Eigen::MatrixX3d& strokes, double reach) {
  RegionSamples out;
  out.regions = regions;
  const std::size_t n = regions.size();
  std::vector<int> slot;  // region -> index into `regions` (-1: none)
  for (std::size_t k = 0; k < n; ++k) {
    const auto r = static_cast<std::size_t>(regions[k]);
    if (r >= slot.size()) slot.resize(r + 1, -1);
    slot[r] = static_cast<int>(k);
  }
  const auto slot_of = [&](int r) { return static_cast<std::size_t>(r) < slot.size() ? slot[static_cast<std::size_t>(r)] : -1; };
  const Eigen::MatrixX3i F = face_matrix(mesh.mesh);
  const ClosestFaceTree tree(positions, F);
  std::vector<std::vector<Eigen::Index>> points(n), own(n);
  for (Eigen::Index i = 0; i < strokes.rows(); ++i) {
    const Eigen::Vector3d p = strokes.row(i).transpose();
    Eigen::Vector3d q;
    const int f = tree.closest_face(p, &q);
    if (f < 0 || (q - p).norm() > reach) continue;
    const int k = slot_of(face_region(mesh, F, f));
    if (k >= 0) points[static_cast<std::size_t>(k)].push_back(i);
  }
  const Eigen::MatrixX3d normals = vertex_normals(positions, F);
  for (std::size_t v = 0; v < mesh.labels.size(); ++v) {
    const int k = mesh.labels[v].size() == 1 ? slot_of(mesh.labels[v].front()) : -1;
    if (k >= 0 && normals.row(static_cast<Eigen::Index>(v)).squaredNorm() > 0.0)
      own[static_cast<std::size_t>(k)].push_back(static_cast<Eigen::Index>(v));
  }
  const auto rows = [](const Eigen::MatrixX3d& from, const std::vector<Eigen::Index>& which) {
    Eigen::MatrixX3d m(static_cast<Eigen::Index>(which.size()), 3);
    for (std::size_t i = 0; i < which.size(); ++i) m.row(static_cast<Eigen::Index>(i)) = from.row(which[i]);
    return m;
  };
  for (std::size_t k = 0; k < n; ++k) {
    out.points.push_back(rows(strokes, points[k]));
    out.vertices.push_back(rows(positions, own[k]));
    out.normals.push_back(rows(normals, own[k]));
  }
  return out;
}

std::vector<ImplicitModel> refit_regions(const std::vector<ImplicitModel>& models, const RegionSamples& samples,
                                         int degree, double diagonal, std::size_t least,
                                         std::size_t* refitted) {
  std::vector<ImplicitModel> out = models;
  if (refitted) *refitted = 0;
  FitOptions fit;
  fit.length_unit = diagonal;
  for (std::size_t k = 0; k < samples.regions.size(); ++k) {
    const auto r = static_cast<std::size_t>(samples.regions[k]);
    if (models[r].degree <= degree || static_cast<std::size_t>(samples.points[k].rows()) < least) continue;
    out[r] = fit_implicit(degree, samples.points[k], samples.vertices[k], samples.normals[k], fit);
    if (refitted) ++*refitted;
  }
  return out;
}

}  // namespace sketchsurf
