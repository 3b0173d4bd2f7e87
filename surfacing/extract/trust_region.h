#pragma once
// E_mesh minimised by Ceres' trust-region solvers (Levenberg-Marquardt with sparse normal
// Cholesky or CGNR): the comparison for optimize_mesh()'s L-BFGS, and E_mesh's terms as Ceres cost
// functions whose Jacobians the tests check. Library sketchsurf_extract_ceres, linked by tests and
// benchmarks only: any ceres::Solve pulls Debian's libceres.a objects that need SuiteSparse's
// CHOLMOD (GPL-2+ modules), which the shipped library does not link for this (see README, Licence).

#include <ceres/cost_function.h>

#include <Eigen/Core>

#include "surfacing/extract/energy.h"
#include "surfacing/extract/optimize.h"

namespace sketchsurf {

/// The linear solver of each Levenberg-Marquardt step.
enum class TrustRegionSolver {
  SparseCholesky,      ///< SPARSE_NORMAL_CHOLESKY (SuiteSparse)
  ConjugateGradients,  ///< CGNR with a Jacobi preconditioner
};

/// optimize_mesh() with Ceres' Levenberg-Marquardt instead of L-BFGS after the same start
/// (projection, local-global iterations), the same energy and the same stopping tolerances
/// (options.max_iterations, function_tolerance, gradient_tolerance; no stall test). Throws as
/// optimize_mesh().
OptimizeSummary optimize_mesh_trust_region(LabeledMesh& mesh, const std::vector<ImplicitModel>& models,
                                           const MeshConstraints& constraints, const MeshEnergyOptions& options,
                                           TrustRegionSolver solver, const Progress& progress = {});

namespace detail {

/// ProjectionResidual (energy.h) as a Ceres cost function with automatic derivatives: weight is
/// the term's weight (its square root multiplies the residual), offset its target level set's
/// (0: the zero set). The model must outlive it.
ceres::CostFunction* make_projection_cost(const ImplicitModel& model, double weight, double gradient_floor,
                                          double offset = 0.0);

/// Eq. 9 residual of one vertex: sqrt(weight) P (x_0 - mean(x_1..x_k)), the uniform graph
/// Laplacian (Nealen et al. 2006) of the vertex x_0 with neighbours x_1..x_k (a 1-ring for
/// Delta_2D, the two seam neighbours for Delta_1D). P projects onto a plane (mirror-plane
/// vertices) or is the identity. Linear, so its Jacobian is constant and written out.
class LaplacianCost : public ceres::CostFunction {
 public:
  LaplacianCost(int neighbors, double weight, const Eigen::Matrix3d& projection);
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;
  static ceres::CostFunction* Create(int neighbors, double weight,
                                     const Eigen::Matrix3d& projection = Eigen::Matrix3d::Identity());

 private:
  int neighbors_;
  Eigen::Matrix3d center_jacobian_;    // sqrt(weight) P
  Eigen::Matrix3d neighbor_jacobian_;  // -sqrt(weight) P / k
};

/// Eq. 13 residual: sqrt(weight) (x - p), a boundary vertex to one of its boundary-stroke points.
struct AttractResidual {
  Eigen::Vector3d target = Eigen::Vector3d::Zero();
  double sqrt_weight = 1.0;
  template <typename T>
  bool operator()(const T* x, T* residual) const {
    for (int i = 0; i < 3; ++i) residual[i] = T(sqrt_weight) * (x[i] - T(target[i]));
    return true;
  }
  static ceres::CostFunction* Create(const Eigen::Vector3d& target, double weight);
};

/// Mirror-plane residual: sqrt(weight) (n . x + d), the signed distance to the plane.
struct PlaneResidual {
  Plane plane;
  double sqrt_weight = 1.0;
  template <typename T>
  bool operator()(const T* x, T* residual) const {
    residual[0] = T(sqrt_weight) * (T(plane.normal.x()) * x[0] + T(plane.normal.y()) * x[1] +
                                     T(plane.normal.z()) * x[2] + T(plane.offset));
    return true;
  }
  static ceres::CostFunction* Create(const Plane& plane, double weight);
};

}  // namespace detail

}  // namespace sketchsurf
