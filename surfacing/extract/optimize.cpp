#include "surfacing/extract/optimize.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>

#include "surfacing/error.h"
#include "surfacing/parallel.h"

namespace sketchsurf {

bool MeshEnergyOptions::valid(std::string* why) const {
  auto fail = [&](const char* what) {
    if (why) *why = what;
    return false;
  };
  if (!(gamma_2d >= 0.0)) return fail("extract.gamma_2d must be >= 0");
  if (!(gamma_1d >= 0.0)) return fail("extract.gamma_1d must be >= 0");
  if (!(smooth_angle >= 0.0 && smooth_angle < sharp_angle && sharp_angle <= M_PI / 2.0))
    return fail("extract angles must satisfy 0 <= smooth_angle < sharp_angle <= pi/2");
  if (!(attract_weight >= 0.0)) return fail("extract.attract_weight must be >= 0");
  if (!(plane_weight >= 0.0)) return fail("extract.plane_weight must be >= 0");
  if (max_iterations < 1) return fail("extract.max_iterations must be at least 1");
  if (!(function_tolerance > 0.0)) return fail("extract.function_tolerance must be > 0");
  return true;
}

double seam_weight(double angle, const MeshEnergyOptions& options) {
  if (angle <= options.smooth_angle) return 1.0;
  if (angle >= options.sharp_angle) return 0.0;
  return (options.sharp_angle - angle) / (options.sharp_angle - options.smooth_angle);
}

std::vector<double> regularization_weights(const LabeledMesh& mesh,
                                           const std::vector<ImplicitModel>& models,
                                           const MeshEnergyOptions& options) {
  std::vector<double> w(mesh.mesh.n_vertices(), 1.0);
  for (auto v : mesh.mesh.vertices()) {
    const auto& labels = mesh.labels[v.idx()];
    if (labels.size() >= 3) {
      w[v.idx()] = 0.0;
    } else if (labels.size() == 2) {
      const Eigen::Vector3d x = to_eigen(mesh.mesh.point(v));
      const Eigen::Vector3d na = models[labels[0]].gradient(x).normalized();
      const Eigen::Vector3d nb = models[labels[1]].gradient(x).normalized();
      // Unoriented normals: f and -f describe the same surface.
      const double c = std::min(1.0, std::abs(na.dot(nb)));
      w[v.idx()] = std::isfinite(c) ? seam_weight(std::acos(c), options) : 0.0;
    }
  }
  return w;
}

namespace detail {

ceres::CostFunction* ProjectionResidual::Create(const ImplicitModel& model, double weight,
                                                double gradient_floor) {
  return new ceres::AutoDiffCostFunction<ProjectionResidual, 1, 3>(
      new ProjectionResidual{&model, std::sqrt(weight), gradient_floor});
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

}  // namespace detail

namespace {

using Ids = std::vector<ceres::ResidualBlockId>;

/// The residual blocks of each term, to evaluate the terms apart.
struct TermBlocks {
  Ids project, regularize_2d, regularize_1d, attract, plane;
};

double term_energy(ceres::Problem& problem, const Ids& ids) {
  if (ids.empty()) return 0.0;
  ceres::Problem::EvaluateOptions eval;
  eval.residual_blocks = ids;
  eval.num_threads = 1;
  double cost = 0.0;
  problem.Evaluate(eval, &cost, nullptr, nullptr, nullptr);
  return 2.0 * cost;  // Ceres' cost is half the sum of squares
}

MeshEnergyTerms energies(ceres::Problem& problem, const TermBlocks& blocks) {
  MeshEnergyTerms e;
  e.project = term_energy(problem, blocks.project);
  e.regularize_2d = term_energy(problem, blocks.regularize_2d);
  e.regularize_1d = term_energy(problem, blocks.regularize_1d);
  e.attract = term_energy(problem, blocks.attract);
  e.plane = term_energy(problem, blocks.plane);
  return e;
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

void configure(const MeshEnergyOptions& options, ceres::Solver::Options& solver) {
  solver.max_num_iterations = options.max_iterations;
  solver.function_tolerance = options.function_tolerance;
  solver.gradient_tolerance = 1e-14;
  solver.parameter_tolerance = 1e-12;
  solver.num_threads = static_cast<int>(resolve_threads(options.threads));
  solver.logging_type = ceres::SILENT;
  switch (options.solver) {
    case MeshSolver::SparseCholesky:
      solver.minimizer_type = ceres::TRUST_REGION;
      solver.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
      solver.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
      break;
    case MeshSolver::ConjugateGradients:
      solver.minimizer_type = ceres::TRUST_REGION;
      solver.linear_solver_type = ceres::CGNR;
      solver.preconditioner_type = ceres::JACOBI;
      break;
    case MeshSolver::Lbfgs:
      solver.minimizer_type = ceres::LINE_SEARCH;
      solver.line_search_direction_type = ceres::LBFGS;
      break;
  }
}

}  // namespace

OptimizeSummary optimize_mesh(LabeledMesh& lm, const std::vector<ImplicitModel>& models,
                              const MeshConstraints& constraints, const MeshEnergyOptions& options,
                              const Progress& progress) {
  std::string why;
  if (!options.valid(&why)) throw Error::usage(why);
  TriMesh& mesh = lm.mesh;
  const int n = static_cast<int>(mesh.n_vertices());
  if (static_cast<int>(lm.labels.size()) != n)
    throw Error::usage("optimize_mesh: labels do not match the mesh's vertices");
  for (const auto& labels : lm.labels)
    for (int l : labels)
      if (l < 0 || l >= static_cast<int>(models.size()))
        throw Error::usage("optimize_mesh: label " + std::to_string(l) + " but " +
                           std::to_string(models.size()) + " models");
  auto check_vertex = [&](int v) {
    if (v < 0 || v >= n) throw Error::usage("optimize_mesh: constraint on vertex " + std::to_string(v));
  };
  for (const auto& t : constraints.attract) check_vertex(t.vertex);
  for (int v : constraints.plane_vertices) check_vertex(v);
  if (!constraints.plane_vertices.empty() && !constraints.plane)
    throw Error::usage("optimize_mesh: plane vertices without a plane");

  std::vector<double> x(3 * static_cast<std::size_t>(n));
  for (auto v : mesh.vertices()) {
    const auto& p = mesh.point(v);
    for (int c = 0; c < 3; ++c) x[3 * v.idx() + c] = p[c];
  }

  ceres::Problem problem;
  for (int v = 0; v < n; ++v) problem.AddParameterBlock(&x[3 * v], 3);
  TermBlocks blocks;

  // E_project (Eq. 8). The gradient floor is relative to each model's typical gradient.
  std::vector<std::vector<double>> gradients(models.size());
  for (int v = 0; v < n; ++v)
    for (int l : lm.labels[v])
      gradients[l].push_back(models[l].gradient(to_eigen(mesh.point(TriMesh::VertexHandle(v)))).norm());
  std::vector<double> floor(models.size(), 0.0);
  for (std::size_t l = 0; l < models.size(); ++l) {
    auto& g = gradients[l];
    if (g.empty()) continue;
    std::nth_element(g.begin(), g.begin() + g.size() / 2, g.end());
    floor[l] = 1e-3 * g[g.size() / 2];
  }
  for (int v = 0; v < n; ++v) {
    const double weight = 1.0 / lm.labels[v].size();
    for (int l : lm.labels[v])
      blocks.project.push_back(problem.AddResidualBlock(
          detail::ProjectionResidual::Create(models[l], weight, floor[l]), nullptr, &x[3 * v]));
  }

  // E_regularize (Eq. 9).
  const std::vector<double> w = regularization_weights(lm, models, options);
  std::vector<bool> on_plane(n, false), attracted(n, false);
  for (int v : constraints.plane_vertices) on_plane[v] = true;
  for (const auto& t : constraints.attract) attracted[t.vertex] = true;
  Eigen::Matrix3d in_plane = Eigen::Matrix3d::Identity();
  if (constraints.plane) in_plane -= constraints.plane->normal * constraints.plane->normal.transpose();
  std::vector<double*> params;
  for (auto v : mesh.vertices()) {
    const int i = v.idx();
    const bool boundary = mesh.is_boundary(v);
    if (boundary && !on_plane[i]) {
      // Open boundary: 1D Laplacian along the boundary, unless E_attract holds the vertex (the
      // boundary strokes then give its shape, corners included).
      if (attracted[i]) continue;
      params = {&x[3 * i]};
      for (auto h : v.outgoing_halfedges())
        if (h.is_boundary() || h.opp().is_boundary()) params.push_back(&x[3 * h.to().idx()]);
      if (params.size() == 3 && options.gamma_1d > 0.0)
        blocks.regularize_1d.push_back(problem.AddResidualBlock(
            detail::LaplacianCost::Create(2, options.gamma_1d), nullptr, params));
      continue;
    }
    if (w[i] > 0.0 && options.gamma_2d > 0.0) {
      params = {&x[3 * i]};
      for (auto u : v.vertices()) params.push_back(&x[3 * u.idx()]);
      if (params.size() > 1)
        blocks.regularize_2d.push_back(problem.AddResidualBlock(
            detail::LaplacianCost::Create(static_cast<int>(params.size()) - 1,
                                          options.gamma_2d * w[i],
                                          on_plane[i] ? in_plane : Eigen::Matrix3d::Identity()),
            nullptr, params));
    }
    if (lm.labels[i].size() == 2 && !boundary && options.gamma_1d > 0.0) {
      // 1D Laplacian along the seam: neighbours that are seam vertices of the same two regions.
      params = {&x[3 * i]};
      const auto& mine = lm.labels[i];
      for (auto u : v.vertices()) {
        const auto& theirs = lm.labels[u.idx()];
        if (theirs.size() >= 2 && std::includes(theirs.begin(), theirs.end(), mine.begin(), mine.end()))
          params.push_back(&x[3 * u.idx()]);
      }
      if (params.size() == 3)
        blocks.regularize_1d.push_back(problem.AddResidualBlock(
            detail::LaplacianCost::Create(2, options.gamma_1d), nullptr, params));
    }
  }

  // E_attract (Eq. 13) and the mirror plane.
  for (const auto& t : constraints.attract)
    blocks.attract.push_back(problem.AddResidualBlock(
        detail::AttractResidual::Create(t.point, options.attract_weight), nullptr,
        &x[3 * t.vertex]));
  for (int v : constraints.plane_vertices)
    blocks.plane.push_back(problem.AddResidualBlock(
        detail::PlaneResidual::Create(*constraints.plane, options.plane_weight), nullptr,
        &x[3 * v]));

  OptimizeSummary summary;
  summary.initial = energies(problem, blocks);
  ceres::Solver::Options solver;
  configure(options, solver);
  CeresProgress callback(progress, options.max_iterations);
  solver.callbacks.push_back(&callback);
  solver.update_state_every_iteration = false;
  ceres::Solver::Summary ceres_summary;
  const auto start = std::chrono::steady_clock::now();
  ceres::Solve(solver, &problem, &ceres_summary);
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  callback.rethrow();
  summary.final = energies(problem, blocks);
  summary.iterations = static_cast<int>(ceres_summary.iterations.size()) - 1;
  summary.termination = std::string(ceres::TerminationTypeToString(ceres_summary.termination_type)) +
                        ": " + ceres_summary.message;
  summary.solver = std::string(ceres::MinimizerTypeToString(ceres_summary.minimizer_type)) + ", " +
                   (ceres_summary.minimizer_type == ceres::TRUST_REGION
                        ? ceres::LinearSolverTypeToString(ceres_summary.linear_solver_type_used)
                        : ceres::LineSearchDirectionTypeToString(
                              ceres_summary.line_search_direction_type));
  summary.usable = ceres_summary.IsSolutionUsable();

  for (double value : x)
    if (!std::isfinite(value))
      throw Error::processing("the final mesh optimisation diverged (non-finite positions); "
                              "check that the proxy lies close to the strokes");
  for (auto v : mesh.vertices()) {
    Eigen::Vector3d p(x[3 * v.idx()], x[3 * v.idx() + 1], x[3 * v.idx() + 2]);
    if (on_plane[v.idx()]) p -= constraints.plane->signed_distance(p) * constraints.plane->normal;
    mesh.set_point(v, to_openmesh(p));
  }
  mesh.update_normals();
  return summary;
}

}  // namespace sketchsurf
