#pragma once
// Known-answer inputs for the extract tests: a rounded-cube proxy labelled by the dominant axis of
// each vertex, with the six exact face planes of the cube as models (what a perfect segmentation
// of the cube sketch gives), and unit spheres as models.

#include <Eigen/Core>
#include <vector>

#include "surfacing/mesh.h"
#include "surfacing/segment/implicit.h"

namespace sketchsurf::testing {

/// Plane n . x = offset as a degree-1 model f(x) = n . x - offset.
inline ImplicitModel plane_model(const Eigen::Vector3d& n, double offset) {
  ImplicitModel m;
  m.degree = 1;
  m.coefficients = Eigen::Vector4d(-offset, n.x(), n.y(), n.z());
  return m;
}

/// The unit sphere round `center`: |x - center|^2 - 1.
inline ImplicitModel sphere_model(const Eigen::Vector3d& center = Eigen::Vector3d::Zero()) {
  ImplicitModel m;
  m.degree = 2;
  m.coefficients = Eigen::VectorXd::Zero(10);
  m.coefficients[0] = -1.0;
  m.coefficients[4] = m.coefficients[7] = m.coefficients[9] = 1.0;
  m.center = center;
  return m;
}

/// The six faces of the axis-aligned box with half extents `half`: label 2 * axis + (side < 0).
inline std::vector<ImplicitModel> box_models(const Eigen::Vector3d& half) {
  std::vector<ImplicitModel> models;
  for (int axis = 0; axis < 3; ++axis)
    for (int side : {1, -1}) models.push_back(plane_model(side * Eigen::Vector3d::Unit(axis), half[axis]));
  return models;
}

/// Per vertex, the face of the box its position points to (largest |p_i| / half_i).
inline std::vector<int> box_labels(const TriMesh& mesh, const Eigen::Vector3d& half) {
  std::vector<int> labels;
  for (auto v : mesh.vertices()) {
    const Eigen::Vector3d p = to_eigen(mesh.point(v)).cwiseQuotient(half);
    int axis = 0;
    p.cwiseAbs().maxCoeff(&axis);
    labels.push_back(2 * axis + (p[axis] < 0.0));
  }
  return labels;
}

}  // namespace sketchsurf::testing
