#include "surfacing/extract/trust_region.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <string>
#include <vector>

#include "surfacing/parallel.h"

namespace sketchsurf {

namespace detail {

ceres::CostFunction* make_projection_cost(const ImplicitModel& model, double weight, double gradient_floor,
                                          double offset) {
  return new ceres::AutoDiffCostFunction<ProjectionResidual, 1, 3>(
      new ProjectionResidual{&model, std::sqrt(weight), gradient_floor, offset});
}

LaplacianCost::LaplacianCost(int neighbors, double weight, const Eigen::Matrix3d& projection)
    : neighbors_(neighbors),
      center_jacobian_(std::sqrt(weight) * projection),
      neighbor_jacobian_(-std::sqrt(weight) / neighbors * projection) {
  set_num_residuals(3);
  mutable_parameter_block_sizes()->assign(neighbors + 1, 3);
}

bool LaplacianCost::Evaluate(double const* const* x, double* residuals, double** jacobians) const {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int i = 1; i <= neighbors_; ++i) mean += Eigen::Map<const Eigen::Vector3d>(x[i]);
  mean /= neighbors_;
  const Eigen::Vector3d d = Eigen::Map<const Eigen::Vector3d>(x[0]) - mean;
  Eigen::Map<Eigen::Vector3d> r(residuals);
  r = center_jacobian_ * d;
  if (jacobians) {
    using RowMajor3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
    for (int i = 0; i <= neighbors_; ++i) {
      if (!jacobians[i]) continue;
      Eigen::Map<RowMajor3> J(jacobians[i]);
      J = i == 0 ? center_jacobian_ : neighbor_jacobian_;
    }
  }
  return true;
}

ceres::CostFunction* LaplacianCost::Create(int neighbors, double weight,
                                           const Eigen::Matrix3d& projection) {
  return new LaplacianCost(neighbors, weight, projection);
}

ceres::CostFunction* AttractResidual::Create(const Eigen::Vector3d& target, double weight) {
  return new ceres::AutoDiffCostFunction<AttractResidual, 3, 3>(
      new AttractResidual{target, std::sqrt(weight)});
}

ceres::CostFunction* PlaneResidual::Create(const Plane& plane, double weight) {
  return new ceres::AutoDiffCostFunction<PlaneResidual, 1, 3>(
      new PlaneResidual{plane, std::sqrt(weight)});
}

namespace {

/// The same terms as Ceres residual blocks (trust-region solvers).
void add_residual_blocks(const MeshEnergy& energy, std::vector<double>& x, ceres::Problem& problem) {
  const int n = static_cast<int>(x.size() / 3);
  for (int v = 0; v < n; ++v) problem.AddParameterBlock(&x[3 * v], 3);
  for (const ProjectionTerm& t : energy.project)
    problem.AddResidualBlock(
        make_projection_cost((*energy.models)[t.model], t.weight, t.floor, t.offset), nullptr,
        &x[3 * t.vertex]);
  std::vector<double*> params;
  for (const auto* terms : {&energy.regularize_2d, &energy.regularize_1d})
    for (const LaplacianTerm& t : *terms) {
      params.clear();
      for (int v : t.vertices) params.push_back(&x[3 * v]);
      problem.AddResidualBlock(
          LaplacianCost::Create(static_cast<int>(t.vertices.size()) - 1, t.weight, t.projection),
          nullptr, params);
    }
  for (const AttractTarget& t : energy.attract)
    problem.AddResidualBlock(AttractResidual::Create(t.point, energy.attract_weight * t.weight), nullptr,
                             &x[3 * t.vertex]);
  for (int v : energy.plane_vertices)
    problem.AddResidualBlock(PlaneResidual::Create(*energy.plane, energy.plane_weight), nullptr,
                             &x[3 * v]);
}

/// Reports progress per iteration; a cancellation stops Ceres and is rethrown after Solve.
class CeresProgress final : public ceres::IterationCallback {
 public:
  CeresProgress(const Progress& progress, int max_iterations)
      : progress_(progress), max_iterations_(max_iterations) {}
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    try {
      progress_.update("extract", std::min(1.0, double(summary.iteration) / max_iterations_));
    } catch (...) {
      error_ = std::current_exception();
      return ceres::SOLVER_ABORT;
    }
    return ceres::SOLVER_CONTINUE;
  }
  void rethrow() const {
    if (error_) std::rethrow_exception(error_);
  }

 private:
  const Progress& progress_;
  int max_iterations_;
  std::exception_ptr error_;
};

}  // namespace

}  // namespace detail

OptimizeSummary optimize_mesh_trust_region(LabeledMesh& mesh, const std::vector<ImplicitModel>& models,
                                           const MeshConstraints& constraints, const MeshEnergyOptions& options,
                                           TrustRegionSolver linear_solver, const Progress& progress) {
  auto trust_region = [&](const detail::MeshEnergy& energy, const detail::MeshEnergyFunction& function,
                          const WorkerTeam&, std::vector<double>& x, double size, OptimizeSummary& summary) {
    ceres::Problem problem;
    detail::add_residual_blocks(energy, x, problem);
    ceres::Solver::Options solver;
    solver.max_num_iterations = options.max_iterations;
    solver.function_tolerance = options.function_tolerance;
    solver.gradient_tolerance = options.gradient_tolerance * size;
    solver.parameter_tolerance = 1e-12;
    solver.num_threads = static_cast<int>(resolve_threads(options.threads));
    solver.logging_type = ceres::SILENT;
    solver.minimizer_type = ceres::TRUST_REGION;
    if (linear_solver == TrustRegionSolver::SparseCholesky) {
      solver.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
      solver.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
    } else {
      solver.linear_solver_type = ceres::CGNR;
      solver.preconditioner_type = ceres::JACOBI;
    }
    detail::CeresProgress callback(progress, options.max_iterations);
    solver.callbacks.push_back(&callback);
    ceres::Solver::Summary s;
    ceres::Solve(solver, &problem, &s);
    callback.rethrow();
    summary.final = function.terms(x.data());
    summary.iterations = static_cast<int>(s.iterations.size()) - 1;
    summary.termination = std::string(ceres::TerminationTypeToString(s.termination_type)) + ": " + s.message;
    summary.solver = std::string("TRUST_REGION, ") + ceres::LinearSolverTypeToString(s.linear_solver_type_used);
    summary.usable = s.IsSolutionUsable();
  };
  return detail::optimize_mesh_with(mesh, models, constraints, options, progress, trust_region);
}

}  // namespace sketchsurf
