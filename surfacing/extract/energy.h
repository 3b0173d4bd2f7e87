#pragma once
// E_mesh (paper §4.3, Eq. 7-9, and App. D Eq. 13) as lists of terms, and its evaluation in one
// pass with its gradient: what the L-BFGS solve and the local-global start of optimize_mesh()
// work on. Private to the extract room.

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <cstddef>
#include <optional>
#include <vector>

#include "surfacing/extract/optimize.h"
#include "surfacing/parallel.h"

namespace sketchsurf::detail {

/// Eq. 8 residual of one vertex and one of its labels: sqrt(weight) (f(x) / |grad f(x)| + offset),
/// the signed Taubin distance to the level set `offset` inside the zero set (0: the zero set
/// itself; > 0 for a thin part's far side, back_sides.h). Signed (not |f|) so that the residual
/// is smooth across the surface; `gradient_floor` (f units per length) keeps it finite where
/// grad f vanishes.
struct ProjectionResidual {
  const ImplicitModel* model = nullptr;
  double sqrt_weight = 1.0;
  double gradient_floor = 0.0;
  double offset = 0.0;

  template <typename T>
  bool operator()(const T* x, T* residual) const {
    const T f = model->evaluate(x);
    T g[3];
    model->evaluate_gradient(x, g);
    using std::sqrt;
    const T norm = sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2] + T(gradient_floor * gradient_floor));
    residual[0] = T(sqrt_weight) * (f / norm + T(offset));
    return true;
  }
};

/// f, its gradient and its Hessian (world units) of one ImplicitModel from one dense table: the
/// ten values (f, f_x, f_y, f_z, f_xx, f_yy, f_zz, f_xy, f_xz, f_yz) are C m(y), m the model's
/// monomials of the normalised coordinates y = (x - center) / scale and C its coefficients
/// differentiated term by term, in world units, built once per model. What the L-BFGS evaluation
/// and the local steps use: products of short dense columns that vectorise, skipping the blocks
/// that are zero (Hessian rows beyond degree 2, gradient rows beyond degree 3), instead of
/// differentiating each monomial at every call (half the CPU of the projection terms, see
/// docs/performance.md).
class ModelDerivatives {
 public:
  explicit ModelDerivatives(const ImplicitModel& model);
  /// f(x) and grad f(x) (3 values) at a world point.
  double value_and_gradient(const double* x, double* gradient) const;
  /// The signed Taubin residual sqrt_weight f / sqrt(|grad f|^2 + floor^2) of ProjectionResidual
  /// at x and its gradient (3 values): grad f / N - f (H grad f) / N^3.
  double taubin(const double* x, double sqrt_weight, double gradient_floor, double* gradient) const;

 private:
  static constexpr int kRows = 12;  // the ten values, padded for vector loads
  template <int Rows>
  void evaluate(const double* x, double* values) const;
  std::vector<std::array<double, kRows>> columns_;  // per monomial: its share of each value
  Eigen::Vector3d center_;
  double inverse_scale_ = 1.0;
  int needed_power_ = 0;  // highest power of a coordinate among the monomials
};

using RowMajorMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor>;

/// One Eq. 8 term: vertex, model, 1 / |labels|, gradient floor, and the offset of its target
/// level set inside the zero set (ProjectionResidual).
struct ProjectionTerm {
  int vertex = 0;
  int model = 0;
  double weight = 1.0;
  double floor = 0.0;
  double offset = 0.0;
};

/// One Laplacian term of Eq. 9: the centre vertex first, then its neighbours.
struct LaplacianTerm {
  std::vector<int> vertices;
  double weight = 0.0;
  Eigen::Matrix3d projection = Eigen::Matrix3d::Identity();
};

/// E_mesh as lists of terms: built once, then evaluated in one pass as a first-order function
/// (MeshEnergyFunction), turned into the global step's matrices (global_step.h), or handed to
/// Ceres as residual blocks (trust_region.h).
struct MeshEnergy {
  const std::vector<ImplicitModel>* models = nullptr;
  std::vector<ModelDerivatives> derivatives;  // one per model
  std::vector<ProjectionTerm> project;        // vertex by vertex, in vertex order
  std::vector<LaplacianTerm> regularize_2d, regularize_1d;
  std::vector<AttractTarget> attract;
  double attract_weight = 1.0;
  std::optional<Plane> plane;
  std::vector<int> plane_vertices;
  double plane_weight = 1.0;
};

/// Builds the terms of E_mesh for the mesh at its current positions (the gradient floors and the
/// seam weights w_v depend on them).
MeshEnergy build_energy(const LabeledMesh& mesh, const std::vector<ImplicitModel>& models,
                        const MeshConstraints& constraints, const MeshEnergyOptions& options);

/// Coefficient j of a Laplacian term's row (weight w, vertex then its k neighbours): sqrt(w) for
/// the vertex, -sqrt(w) / k for each neighbour.
double laplacian_coefficient(const LaplacianTerm& term, std::size_t j);

/// The Laplacian terms of E_regularize split by kind: 2D terms without projection, then 1D ones,
/// as rows of one scalar matrix; 2D terms with a projection (mirror-plane vertices) apart.
struct LaplacianSplit {
  std::vector<const LaplacianTerm*> scalar, projected;
  std::size_t scalar_2d = 0;  // the first scalar_2d scalar rows are 2D terms
};

/// E_mesh evaluated in one pass, with its gradient, for L-BFGS: the projection terms in parallel
/// from the models' derivative tables, the Laplacian terms as precomputed sparse matrices (the
/// "precomputed gradient matrices for the quadratic terms" of §4.3), row-parallel. Cost is half
/// the sum of squares, as in Ceres. Every sum runs in a fixed order: the result does not depend
/// on the team's size. Keeps references to `energy` and `team`.
class MeshEnergyFunction {
 public:
  MeshEnergyFunction(const MeshEnergy& energy, int n, const WorkerTeam& team);

  /// Half E_mesh at x (3n values) into `cost`, and when `gradient` is not null its gradient
  /// multiplied entry by entry by `gradient_scale` (3n values: in the per-vertex loop that
  /// assembles it when no term is added after that loop, else in a pass of its own). False when
  /// the cost is not finite.
  bool evaluate(const double* x, double* cost, double* gradient, const double* gradient_scale) const;

  /// Diagonal of the Gauss-Newton Hessian (3n entries), the projection terms counted isotropically.
  Eigen::VectorXd hessian_diagonal() const;

  /// The terms apart, each a plain sum of squares.
  MeshEnergyTerms terms(const double* x) const;

 private:
  const MeshEnergy& energy_;
  int n_;
  const WorkerTeam& team_;
  LaplacianSplit split_;
  // The scalar and projected Laplacian matrices and their transposes (row-major, so that every
  // product runs row-parallel), with buffers for their products.
  RowMajorMatrix scalar_, scalar_transpose_, projected_, projected_transpose_;
  mutable Eigen::VectorXd scalar_residuals_, projected_residuals_, product_;
  mutable std::vector<double> project_values_;
  mutable std::vector<Eigen::Vector3d> project_gradients_;
  std::vector<std::size_t> first_term_;  // projection terms of vertex v: [first_term_[v], first_term_[v + 1])
};

}  // namespace sketchsurf::detail
