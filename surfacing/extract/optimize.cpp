#include "surfacing/extract/optimize.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <memory>

#include <Eigen/Sparse>

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
  if (!(gradient_tolerance > 0.0)) return fail("extract.gradient_tolerance must be > 0");
  if (lbfgs_rank < 1) return fail("extract.lbfgs_rank must be at least 1");
  if (projection_steps < 0) return fail("extract.projection_steps must be >= 0");
  if (!(max_projection_step > 0.0)) return fail("extract.max_projection_step must be > 0");
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

/// One Eq. 8 term: vertex, model, 1 / |labels|, gradient floor.
struct ProjectionTerm {
  int vertex = 0;
  int model = 0;
  double weight = 1.0;
  double floor = 0.0;
};

/// One Laplacian term of Eq. 9: the centre vertex first, then its neighbours.
struct LaplacianTerm {
  std::vector<int> vertices;
  double weight = 0.0;
  Eigen::Matrix3d projection = Eigen::Matrix3d::Identity();
};

/// E_mesh as lists of terms: built once, then either handed to Ceres as residual blocks
/// (trust-region solvers) or evaluated in one pass as a first-order function (L-BFGS).
struct MeshEnergy {
  const std::vector<ImplicitModel>* models = nullptr;
  std::vector<ProjectionTerm> project;
  std::vector<LaplacianTerm> regularize_2d, regularize_1d;
  std::vector<AttractTarget> attract;
  double attract_weight = 1.0;
  std::optional<Plane> plane;
  std::vector<int> plane_vertices;
  double plane_weight = 1.0;
};

/// The Laplacian terms as one sparse matrix L (3 rows per term, 3 columns per vertex), so that
/// their energy is |L x|^2 and its gradient 2 L^T L x: the "precomputed gradient matrices for the
/// quadratic terms" of §4.3.
Eigen::SparseMatrix<double, Eigen::RowMajor> laplacian_matrix(const std::vector<LaplacianTerm>& terms,
                                                              int n) {
  std::vector<Eigen::Triplet<double>> entries;
  for (std::size_t t = 0; t < terms.size(); ++t) {
    const auto& term = terms[t];
    const double s = std::sqrt(term.weight);
    const double k = static_cast<double>(term.vertices.size() - 1);
    for (std::size_t j = 0; j < term.vertices.size(); ++j) {
      const double c = j == 0 ? s : -s / k;
      for (int r = 0; r < 3; ++r)
        for (int q = 0; q < 3; ++q)
          if (term.projection(r, q) != 0.0)
            entries.emplace_back(3 * t + r, 3 * term.vertices[j] + q, c * term.projection(r, q));
    }
  }
  Eigen::SparseMatrix<double, Eigen::RowMajor> L(3 * terms.size(), 3 * n);
  L.setFromTriplets(entries.begin(), entries.end());
  return L;
}

/// E_mesh evaluated in one pass for L-BFGS. Cost is half the sum of squares, as in Ceres.
class MeshEnergyFunction final : public ceres::FirstOrderFunction {
 public:
  MeshEnergyFunction(const MeshEnergy& energy, int n, unsigned threads)
      : energy_(energy),
        n_(n),
        threads_(threads),
        l2d_(laplacian_matrix(energy.regularize_2d, n)),
        l1d_(laplacian_matrix(energy.regularize_1d, n)),
        project_values_(energy.project.size()),
        project_gradients_(energy.project.size()) {}

  int NumParameters() const override { return 3 * n_; }

  bool Evaluate(const double* x, double* cost, double* gradient) const override {
    const Eigen::Map<const Eigen::VectorXd> X(x, 3 * n_);
    // Projection: each term alone (in parallel), accumulated in a fixed order.
    using Jet = ceres::Jet<double, 3>;
    parallel_for(0, energy_.project.size(), threads_, [&](std::size_t i) {
      const ProjectionTerm& t = energy_.project[i];
      const detail::ProjectionResidual r{&(*energy_.models)[t.model], std::sqrt(t.weight), t.floor};
      Jet p[3], value;
      for (int c = 0; c < 3; ++c) p[c] = Jet(x[3 * t.vertex + c], c);
      r(p, &value);
      project_values_[i] = value.a;
      project_gradients_[i] = value.v;
    });
    double total = 0.0;
    Eigen::Map<Eigen::VectorXd> G(gradient, gradient ? 3 * n_ : 0);
    if (gradient) G.setZero();
    for (std::size_t i = 0; i < energy_.project.size(); ++i) {
      total += 0.5 * project_values_[i] * project_values_[i];
      if (gradient) G.segment<3>(3 * energy_.project[i].vertex) += project_values_[i] * project_gradients_[i];
    }
    for (const auto* L : {&l2d_, &l1d_}) {
      const Eigen::VectorXd r = (*L) * X;
      total += 0.5 * r.squaredNorm();
      if (gradient) G.noalias() += L->transpose() * r;
    }
    const double sa = energy_.attract_weight;
    for (const AttractTarget& t : energy_.attract) {
      const Eigen::Vector3d d = X.segment<3>(3 * t.vertex) - t.point;
      total += 0.5 * sa * d.squaredNorm();
      if (gradient) G.segment<3>(3 * t.vertex) += sa * d;
    }
    for (int v : energy_.plane_vertices) {
      const double d = energy_.plane->signed_distance(X.segment<3>(3 * v));
      total += 0.5 * energy_.plane_weight * d * d;
      if (gradient) G.segment<3>(3 * v) += energy_.plane_weight * d * energy_.plane->normal;
    }
    *cost = total;
    return std::isfinite(total);
  }

  /// The terms apart, each a plain sum of squares.
  MeshEnergyTerms terms(const double* x) const {
    MeshEnergyTerms e;
    const Eigen::Map<const Eigen::VectorXd> X(x, 3 * n_);
    for (const ProjectionTerm& t : energy_.project) {
      const detail::ProjectionResidual r{&(*energy_.models)[t.model], std::sqrt(t.weight), t.floor};
      double value = 0.0;
      r(x + 3 * t.vertex, &value);
      e.project += value * value;
    }
    e.regularize_2d = (l2d_ * X).squaredNorm();
    e.regularize_1d = (l1d_ * X).squaredNorm();
    for (const AttractTarget& t : energy_.attract)
      e.attract += energy_.attract_weight * (X.segment<3>(3 * t.vertex) - t.point).squaredNorm();
    for (int v : energy_.plane_vertices)
      e.plane += energy_.plane_weight * std::pow(energy_.plane->signed_distance(X.segment<3>(3 * v)), 2);
    return e;
  }

 private:
  const MeshEnergy& energy_;
  int n_;
  unsigned threads_;
  Eigen::SparseMatrix<double, Eigen::RowMajor> l2d_, l1d_;
  mutable std::vector<double> project_values_;
  mutable std::vector<Eigen::Vector3d> project_gradients_;
};

/// The same terms as Ceres residual blocks (trust-region solvers).
void add_residual_blocks(const MeshEnergy& energy, std::vector<double>& x, ceres::Problem& problem) {
  const int n = static_cast<int>(x.size() / 3);
  for (int v = 0; v < n; ++v) problem.AddParameterBlock(&x[3 * v], 3);
  for (const ProjectionTerm& t : energy.project)
    problem.AddResidualBlock(
        detail::ProjectionResidual::Create((*energy.models)[t.model], t.weight, t.floor), nullptr,
        &x[3 * t.vertex]);
  std::vector<double*> params;
  for (const auto* terms : {&energy.regularize_2d, &energy.regularize_1d})
    for (const LaplacianTerm& t : *terms) {
      params.clear();
      for (int v : t.vertices) params.push_back(&x[3 * v]);
      problem.AddResidualBlock(
          detail::LaplacianCost::Create(static_cast<int>(t.vertices.size()) - 1, t.weight, t.projection),
          nullptr, params);
    }
  for (const AttractTarget& t : energy.attract)
    problem.AddResidualBlock(detail::AttractResidual::Create(t.point, energy.attract_weight), nullptr,
                             &x[3 * t.vertex]);
  for (int v : energy.plane_vertices)
    problem.AddResidualBlock(detail::PlaneResidual::Create(*energy.plane, energy.plane_weight), nullptr,
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

/// Moves each vertex onto the intersection of its labels' surfaces by damped Gauss-Newton steps
/// (least-norm dx with f_i + grad f_i . dx = 0), each step at most `max_step` long: a cheap start
/// that leaves L-BFGS mostly the regularisation to do.
void project_vertices(LabeledMesh& lm, const std::vector<ImplicitModel>& models, int steps,
                      double max_step, unsigned threads) {
  TriMesh& mesh = lm.mesh;
  parallel_for(0, mesh.n_vertices(), threads, [&](std::size_t i) {
    const TriMesh::VertexHandle v(static_cast<int>(i));
    Eigen::Vector3d x = to_eigen(mesh.point(v));
    const auto& labels = lm.labels[i];
    const int k = static_cast<int>(labels.size());
    for (int step = 0; step < steps; ++step) {
      Eigen::MatrixXd J(k, 3);
      Eigen::VectorXd f(k);
      for (int a = 0; a < k; ++a) {
        f[a] = models[labels[a]].value(x);
        J.row(a) = models[labels[a]].gradient(x).transpose();
      }
      Eigen::MatrixXd JJt = J * J.transpose();
      const double damping = 1e-6 * JJt.trace() + std::numeric_limits<double>::min();
      JJt.diagonal().array() += damping;
      Eigen::Vector3d dx = -J.transpose() * JJt.ldlt().solve(f);
      if (!dx.allFinite()) break;
      if (dx.norm() > max_step) dx *= max_step / dx.norm();
      x += dx;
    }
    mesh.set_point(v, to_openmesh(x));
  });
}

/// Builds the terms of E_mesh for the mesh at its current positions.
MeshEnergy build_energy(const LabeledMesh& lm, const std::vector<ImplicitModel>& models,
                        const MeshConstraints& constraints, const MeshEnergyOptions& options) {
  const TriMesh& mesh = lm.mesh;
  const int n = static_cast<int>(mesh.n_vertices());
  MeshEnergy energy;
  energy.models = &models;

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
  for (int v = 0; v < n; ++v)
    for (int l : lm.labels[v]) energy.project.push_back({v, l, 1.0 / lm.labels[v].size(), floor[l]});

  // E_regularize (Eq. 9).
  const std::vector<double> w = regularization_weights(lm, models, options);
  std::vector<bool> on_plane(n, false), attracted(n, false);
  for (int v : constraints.plane_vertices) on_plane[v] = true;
  for (const auto& t : constraints.attract) attracted[t.vertex] = true;
  Eigen::Matrix3d in_plane = Eigen::Matrix3d::Identity();
  if (constraints.plane) in_plane -= constraints.plane->normal * constraints.plane->normal.transpose();
  for (auto v : mesh.vertices()) {
    const int i = v.idx();
    const bool boundary = mesh.is_boundary(v);
    if (boundary && !on_plane[i]) {
      // Open boundary: 1D Laplacian along the boundary, unless E_attract holds the vertex (the
      // boundary strokes then give its shape, corners included).
      if (attracted[i]) continue;
      LaplacianTerm term{{i}, options.gamma_1d, Eigen::Matrix3d::Identity()};
      for (auto h : v.outgoing_halfedges())
        if (h.is_boundary() || h.opp().is_boundary()) term.vertices.push_back(h.to().idx());
      if (term.vertices.size() == 3 && options.gamma_1d > 0.0) energy.regularize_1d.push_back(term);
      continue;
    }
    if (w[i] > 0.0 && options.gamma_2d > 0.0) {
      LaplacianTerm term{{i}, options.gamma_2d * w[i],
                         on_plane[i] ? in_plane : Eigen::Matrix3d::Identity()};
      for (auto u : v.vertices()) term.vertices.push_back(u.idx());
      if (term.vertices.size() > 1) energy.regularize_2d.push_back(std::move(term));
    }
    if (lm.labels[i].size() == 2 && !boundary && options.gamma_1d > 0.0) {
      // 1D Laplacian along the seam: neighbours that are seam vertices of the same two regions.
      LaplacianTerm term{{i}, options.gamma_1d, Eigen::Matrix3d::Identity()};
      const auto& mine = lm.labels[i];
      for (auto u : v.vertices()) {
        const auto& theirs = lm.labels[u.idx()];
        if (theirs.size() >= 2 && std::includes(theirs.begin(), theirs.end(), mine.begin(), mine.end()))
          term.vertices.push_back(u.idx());
      }
      if (term.vertices.size() == 3) energy.regularize_1d.push_back(std::move(term));
    }
  }

  // E_attract (Eq. 13) and the mirror plane.
  energy.attract = constraints.attract;
  energy.attract_weight = options.attract_weight;
  energy.plane = constraints.plane;
  energy.plane_vertices = constraints.plane_vertices;
  energy.plane_weight = options.plane_weight;
  return energy;
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

  // Length scale of the stopping test and of the start: the mesh's bounding-box diagonal.
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (auto v : mesh.vertices()) {
    lo = lo.cwiseMin(to_eigen(mesh.point(v)));
    hi = hi.cwiseMax(to_eigen(mesh.point(v)));
  }
  const double size = n > 0 ? (hi - lo).norm() : 1.0;
  const unsigned threads = resolve_threads(options.threads);
  const MeshEnergy initial_energy = build_energy(lm, models, constraints, options);
  std::vector<double> x(3 * static_cast<std::size_t>(n));
  auto load = [&] {
    for (auto v : mesh.vertices()) {
      const auto& p = mesh.point(v);
      for (int c = 0; c < 3; ++c) x[3 * v.idx() + c] = p[c];
    }
  };
  load();
  OptimizeSummary summary;
  summary.initial = MeshEnergyFunction(initial_energy, n, threads).terms(x.data());
  if (options.projection_steps > 0) {
    project_vertices(lm, models, options.projection_steps, options.max_projection_step * size, threads);
    load();
  }
  const MeshEnergy energy = build_energy(lm, models, constraints, options);
  // Owned by `gradient_problem` below on the L-BFGS path, by this pointer otherwise.
  auto* function = new MeshEnergyFunction(energy, n, threads);
  std::unique_ptr<ceres::FirstOrderFunction> owned_function(function);

  CeresProgress callback(progress, options.max_iterations);
  const auto start = std::chrono::steady_clock::now();
  if (options.solver == MeshSolver::Lbfgs) {
    ceres::GradientProblem gradient_problem(owned_function.release());
    ceres::GradientProblemSolver::Options solver;
    solver.line_search_direction_type = ceres::LBFGS;
    solver.max_lbfgs_rank = options.lbfgs_rank;
    solver.max_num_iterations = options.max_iterations;
    solver.function_tolerance = options.function_tolerance;
    solver.gradient_tolerance = options.gradient_tolerance * size;
    solver.parameter_tolerance = 1e-12;
    solver.logging_type = ceres::SILENT;
    solver.callbacks.push_back(&callback);
    ceres::GradientProblemSolver::Summary s;
    ceres::Solve(solver, gradient_problem, x.data(), &s);
    callback.rethrow();
    summary.final = function->terms(x.data());
    summary.iterations = static_cast<int>(s.iterations.size()) - 1;
    summary.termination = std::string(ceres::TerminationTypeToString(s.termination_type)) + ": " + s.message;
    summary.solver = "LINE_SEARCH, LBFGS";
    summary.usable = s.IsSolutionUsable();
  } else {
    ceres::Problem problem;
    add_residual_blocks(energy, x, problem);
    ceres::Solver::Options solver;
    solver.max_num_iterations = options.max_iterations;
    solver.function_tolerance = options.function_tolerance;
    solver.gradient_tolerance = options.gradient_tolerance * size;
    solver.parameter_tolerance = 1e-12;
    solver.num_threads = static_cast<int>(threads);
    solver.logging_type = ceres::SILENT;
    solver.minimizer_type = ceres::TRUST_REGION;
    if (options.solver == MeshSolver::SparseCholesky) {
      solver.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
      solver.sparse_linear_algebra_library_type = ceres::SUITE_SPARSE;
    } else {
      solver.linear_solver_type = ceres::CGNR;
      solver.preconditioner_type = ceres::JACOBI;
    }
    solver.callbacks.push_back(&callback);
    ceres::Solver::Summary s;
    ceres::Solve(solver, &problem, &s);
    callback.rethrow();
    summary.final = function->terms(x.data());
    summary.iterations = static_cast<int>(s.iterations.size()) - 1;
    summary.termination = std::string(ceres::TerminationTypeToString(s.termination_type)) + ": " + s.message;
    summary.solver = std::string("TRUST_REGION, ") + ceres::LinearSolverTypeToString(s.linear_solver_type_used);
    summary.usable = s.IsSolutionUsable();
  }
  summary.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  for (double value : x)
    if (!std::isfinite(value))
      throw Error::processing("the final mesh optimisation diverged (non-finite positions); "
                              "check that the proxy lies close to the strokes");
  std::vector<bool> on_plane(n, false);
  for (int v : constraints.plane_vertices) on_plane[v] = true;
  for (auto v : mesh.vertices()) {
    Eigen::Vector3d p(x[3 * v.idx()], x[3 * v.idx() + 1], x[3 * v.idx() + 2]);
    if (on_plane[v.idx()]) p -= constraints.plane->signed_distance(p) * constraints.plane->normal;
    mesh.set_point(v, to_openmesh(p));
  }
  mesh.update_normals();
  return summary;
}

}  // namespace sketchsurf
