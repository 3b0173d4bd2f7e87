#include "surfacing/extract/optimize.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <sstream>
#include <type_traits>
#include <utility>

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
  if (local_global_iterations < 0) return fail("extract.local_global_iterations must be >= 0");
  if (!(local_global_tolerance > 0.0)) return fail("extract.local_global_tolerance must be > 0");
  if (!(global_step_tolerance > 0.0 && global_step_tolerance < 1.0))
    return fail("extract.global_step_tolerance must be in (0, 1)");
  if (!(function_tolerance > 0.0)) return fail("extract.function_tolerance must be > 0");
  if (stall_window < 0) return fail("extract.stall_window must be >= 0");
  if (!(stall_tolerance >= 0.0 && stall_tolerance < 1.0))
    return fail("extract.stall_tolerance must be in [0, 1)");
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
  parallel_for(0, mesh.mesh.n_vertices(), resolve_threads(options.threads), [&](std::size_t i) {
    const TriMesh::VertexHandle v(static_cast<int>(i));
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
  });
  return w;
}

namespace detail {

ceres::CostFunction* ProjectionResidual::Create(const ImplicitModel& model, double weight,
                                                double gradient_floor) {
  return new ceres::AutoDiffCostFunction<ProjectionResidual, 1, 3>(
      new ProjectionResidual{&model, std::sqrt(weight), gradient_floor});
}

namespace {

/// Index of the monomial with exponents (a, b, c) in implicit_monomials().
int monomial_index(int a, int b, int c) {
  constexpr MonomialExponents kMonomials = implicit_monomials();
  for (std::size_t k = 0; k < kMonomials.size(); ++k)
    if (kMonomials[k][0] == a && kMonomials[k][1] == b && kMonomials[k][2] == c) return static_cast<int>(k);
  return -1;
}

}  // namespace

ModelDerivatives::ModelDerivatives(const ImplicitModel& model)
    : center_(model.center), inverse_scale_(1.0 / model.scale) {
  constexpr MonomialExponents kMonomials = implicit_monomials();
  const std::size_t count = std::min<std::size_t>(model.coefficients.size(), kMonomials.size());
  columns_.assign(count, {});
  const double s = inverse_scale_, s2 = s * s;
  for (std::size_t k = 0; k < count; ++k) {
    const double c = model.coefficients[static_cast<Eigen::Index>(k)];
    const int e[3] = {kMonomials[k][0], kMonomials[k][1], kMonomials[k][2]};
    needed_power_ = std::max({needed_power_, e[0], e[1], e[2]});
    columns_[k][0] += c;
    // d/dy_i of y^e is e_i y^(e - 1_i), a monomial of lower degree, hence earlier in the list.
    // Row `row` gets d/dy_i (and d/dy_j when j >= 0) of c y^e, times `factor` (world units).
    auto add = [&](int row, int i, int j, double factor) {
      int d[3] = {e[0], e[1], e[2]};
      double multiplier = c * factor;
      for (int axis : {i, j}) {
        if (axis < 0) continue;
        if (d[axis] == 0) return;
        multiplier *= d[axis]--;
      }
      columns_[static_cast<std::size_t>(monomial_index(d[0], d[1], d[2]))][row] += multiplier;
    };
    for (int i = 0; i < 3; ++i) {
      add(1 + i, i, -1, s);
      add(4 + i, i, i, s2);
    }
    add(7, 0, 1, s2);
    add(8, 0, 2, s2);
    add(9, 1, 2, s2);
  }
}

namespace {

/// ModelDerivatives::evaluate() for a table of T columns, the loop over the monomials unrolled
/// with compile-time exponents and row counts (T = 0: any count, the loop generic). Column k
/// only feeds the values whose derivative order leaves degree(k) within the model's: the Hessian
/// rows (4..9) columns of degree <= 2 (the first 10), the gradient rows (1..3) those of degree
/// <= 3 (the first 20), f all of them.
template <int Rows, int T, std::size_t Width>
void evaluate_table(const std::vector<std::array<double, Width>>& columns, const Eigen::Vector3d& center,
                    double inverse_scale, int needed_power, const double* x, double* values) {
  constexpr MonomialExponents kMonomials = implicit_monomials();
  const int power = T == 0 ? needed_power : T > 20 ? 4 : T > 10 ? 3 : T > 4 ? 2 : T > 1 ? 1 : 0;
  double p[3][kMaxImplicitDegree + 1];
  for (int i = 0; i < 3; ++i) {
    const double y = (x[i] - center[i]) * inverse_scale;
    p[i][0] = 1.0;
    for (int e = 1; e <= power; ++e) p[i][e] = p[i][e - 1] * y;
  }
  double sum[Rows] = {};
  // Always inlined: GCC 12 kept the 1- and 4-row instances out of line, a call per monomial
  // (01-0-1's terms 81 -> 35 ns each, the same operations).
  auto term = [&](std::size_t k, auto rows) __attribute__((always_inline)) {
    const auto& m = kMonomials[k];
    const double value = p[0][m[0]] * p[1][m[1]] * p[2][m[2]];
    const double* column = columns[k].data();
    for (int r = 0; r < decltype(rows)::value; ++r) sum[r] += column[r] * value;
  };
  constexpr int kGradientRows = std::min(Rows, 4);
  if constexpr (T > 0) {
    [&]<std::size_t... K>(std::index_sequence<K...>) {
      (term(K, std::integral_constant<int, K < 10 ? Rows : K < 20 ? kGradientRows : 1>()), ...);
    }(std::make_index_sequence<T>{});
  } else {
    const std::size_t count = columns.size();
    for (std::size_t k = 0; k < std::min<std::size_t>(10, count); ++k) term(k, std::integral_constant<int, Rows>());
    for (std::size_t k = 10; k < std::min<std::size_t>(20, count); ++k) term(k, std::integral_constant<int, kGradientRows>());
    for (std::size_t k = 20; k < count; ++k) term(k, std::integral_constant<int, 1>());
  }
  for (int r = 0; r < Rows; ++r) values[r] = sum[r];
}

}  // namespace

template <int Rows>
void ModelDerivatives::evaluate(const double* x, double* values) const {
  // The same operations, in the same order, whatever the count.
  switch (columns_.size()) {
    case 4: return evaluate_table<Rows, 4>(columns_, center_, inverse_scale_, needed_power_, x, values);
    case 10: return evaluate_table<Rows, 10>(columns_, center_, inverse_scale_, needed_power_, x, values);
    case 20: return evaluate_table<Rows, 20>(columns_, center_, inverse_scale_, needed_power_, x, values);
    case 35: return evaluate_table<Rows, 35>(columns_, center_, inverse_scale_, needed_power_, x, values);
    default: return evaluate_table<Rows, 0>(columns_, center_, inverse_scale_, needed_power_, x, values);
  }
}

double ModelDerivatives::value_and_gradient(const double* x, double* gradient) const {
  double v[4];
  evaluate<4>(x, v);
  for (int i = 0; i < 3; ++i) gradient[i] = v[1 + i];
  return v[0];
}

double ModelDerivatives::taubin(const double* x, double sqrt_weight, double gradient_floor,
                                double* gradient) const {
  double v[10];
  evaluate<10>(x, v);
  const double f = v[0];
  const Eigen::Vector3d g(v[1], v[2], v[3]);
  Eigen::Matrix3d H;
  H << v[4], v[7], v[8], v[7], v[5], v[9], v[8], v[9], v[6];
  const double norm = std::sqrt(g.squaredNorm() + gradient_floor * gradient_floor);
  Eigen::Map<Eigen::Vector3d> out(gradient);
  out = sqrt_weight * (g / norm - f * (H * g) / (norm * norm * norm));
  return sqrt_weight * f / norm;
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

/// block_conjugate_gradients() on `team`.
template <int K>
std::vector<double> conjugate_gradients(const WorkerTeam& team, const Eigen::SparseMatrix<double, Eigen::RowMajor>& A,
                                        const Eigen::VectorXd& inverse_diagonal, const std::vector<double>& B,
                                        double tolerance) {
  constexpr std::size_t kChunk = 2048;
  const Eigen::Index n = A.rows();
  const std::size_t chunks = (static_cast<std::size_t>(n) + kChunk - 1) / kChunk;
  const std::size_t size = static_cast<std::size_t>(n) * K;
  std::vector<double> X(size, 0.0), R = B, Z(size), P(size), Q(size);
  using Sums = std::array<double, K>;
  std::vector<Sums> first(chunks), second(chunks);
  auto for_chunks = [&](auto&& body) { team.chunks(static_cast<std::size_t>(n), kChunk, body); };
  auto total = [&](const std::vector<Sums>& partial) {
    Sums sum{};
    for (const Sums& p : partial)
      for (int j = 0; j < K; ++j) sum[j] += p[j];
    return sum;
  };
  // x += alpha p, r -= alpha q (alpha = 0 at the start), z = M^-1 r, with the partial sums of
  // r . z (first) and r . r (second).
  auto step = [&](const Sums& alpha) {
    for_chunks([&](std::size_t c, Eigen::Index lo, Eigen::Index hi) {
      Sums rz{}, rr{};
      for (Eigen::Index i = lo; i < hi; ++i)
        for (int j = 0; j < K; ++j) {
          const std::size_t at = static_cast<std::size_t>(i) * K + j;
          X[at] += alpha[j] * P[at];
          R[at] -= alpha[j] * Q[at];
          Z[at] = inverse_diagonal[i] * R[at];
          rz[j] += R[at] * Z[at];
          rr[j] += R[at] * R[at];
        }
      first[c] = rz;
      second[c] = rr;
    });
  };
  Sums alpha{}, beta{}, threshold{};
  std::fill(P.begin(), P.end(), 0.0);
  std::fill(Q.begin(), Q.end(), 0.0);
  step(alpha);
  Sums rz = total(first);
  const Sums bb = total(second);
  std::array<bool, K> active{};
  for (int j = 0; j < K; ++j) {
    threshold[j] = tolerance * tolerance * bb[j];
    active[j] = threshold[j] > 0.0;
  }
  P = Z;
  for (Eigen::Index it = 0; it < 2 * n && std::find(active.begin(), active.end(), true) != active.end(); ++it) {
    for_chunks([&](std::size_t c, Eigen::Index lo, Eigen::Index hi) {
      Sums pq{};
      for (Eigen::Index i = lo; i < hi; ++i) {
        double q[K] = {};
        for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator e(A, i); e; ++e) {
          const double* p = &P[static_cast<std::size_t>(e.col()) * K];
          for (int j = 0; j < K; ++j) q[j] += e.value() * p[j];
        }
        for (int j = 0; j < K; ++j) {
          Q[static_cast<std::size_t>(i) * K + j] = q[j];
          pq[j] += P[static_cast<std::size_t>(i) * K + j] * q[j];
        }
      }
      first[c] = pq;
    });
    const Sums pq = total(first);
    for (int j = 0; j < K; ++j) {
      if (active[j] && !(pq[j] > 0.0)) active[j] = false;  // breakdown: keep the iterate
      alpha[j] = active[j] ? rz[j] / pq[j] : 0.0;
    }
    step(alpha);
    const Sums next = total(first), rr = total(second);
    for (int j = 0; j < K; ++j) {
      if (rr[j] <= threshold[j]) active[j] = false;
      beta[j] = rz[j] != 0.0 ? next[j] / rz[j] : 0.0;
    }
    rz = next;
    for_chunks([&](std::size_t, Eigen::Index lo, Eigen::Index hi) {
      for (Eigen::Index i = lo; i < hi; ++i)
        for (int j = 0; j < K; ++j) {
          const std::size_t at = static_cast<std::size_t>(i) * K + j;
          P[at] = Z[at] + beta[j] * P[at];
        }
    });
  }
  return X;
}

/// normal_matrix() on `team`: entry (j, i) of L^T L adds L_ti L_tj over the rows t in increasing
/// order, starting from the first product, as Eigen's conservative sparse product; an entry
/// missing from one operand of a sum counts as 0.0, as in Eigen's sums; A is symmetric, so its
/// rows are its columns.
RowMajorMatrix normal_matrix_on(const WorkerTeam& team, const Eigen::SparseMatrix<double>& L2,
                                const Eigen::SparseMatrix<double>& L1, const Eigen::VectorXd& d) {
  using ColMatrix = Eigen::SparseMatrix<double>;
  const Eigen::Index n = d.size();
  const RowMajorMatrix R2 = L2, R1 = L1;  // the terms' rows
  constexpr Eigen::Index kBlock = 4096;
  const std::size_t blocks = static_cast<std::size_t>((n + kBlock - 1) / kBlock);
  std::vector<std::vector<int>> columns(blocks);
  std::vector<std::vector<double>> values(blocks);
  std::vector<int> counts(static_cast<std::size_t>(n));
  team.for_each(0, blocks, [&](std::size_t b) {
    std::vector<double> v2(static_cast<std::size_t>(n)), v1(static_cast<std::size_t>(n));
    std::vector<unsigned char> in(static_cast<std::size_t>(n), 0);  // bit 1: in L2^T L2, bit 2: in L1^T L1
    std::vector<int> touched;
    const Eigen::Index begin = static_cast<Eigen::Index>(b) * kBlock, end = std::min(n, begin + kBlock);
    for (Eigen::Index j = begin; j < end; ++j) {
      touched.clear();
      auto add = [&](const ColMatrix& L, const RowMajorMatrix& R, std::vector<double>& v, unsigned char bit) {
        for (ColMatrix::InnerIterator t(L, j); t; ++t) {
          const double y = t.value();
          for (RowMajorMatrix::InnerIterator e(R, t.index()); e; ++e) {
            const auto i = static_cast<std::size_t>(e.index());
            if (!(in[i] & bit)) {
              if (!in[i]) touched.push_back(static_cast<int>(i));
              in[i] |= bit;
              v[i] = e.value() * y;
            } else {
              v[i] += e.value() * y;
            }
          }
        }
      };
      add(L2, R2, v2, 1);
      add(L1, R1, v1, 2);
      if (!in[static_cast<std::size_t>(j)]) touched.push_back(static_cast<int>(j));
      std::sort(touched.begin(), touched.end());
      for (int i : touched) {
        const auto k = static_cast<std::size_t>(i);
        const double sum = ((in[k] & 1) ? v2[k] : 0.0) + ((in[k] & 2) ? v1[k] : 0.0);
        columns[b].push_back(i);
        values[b].push_back(sum + (i == j ? d[j] : 0.0));
        in[k] = 0;
      }
      counts[static_cast<std::size_t>(j)] = static_cast<int>(touched.size());
    }
  });
  std::vector<int> outer(static_cast<std::size_t>(n) + 1, 0), inner;
  std::vector<double> entries;
  for (std::size_t j = 0; j < counts.size(); ++j) outer[j + 1] = outer[j] + counts[j];
  inner.reserve(static_cast<std::size_t>(outer.back()));
  entries.reserve(static_cast<std::size_t>(outer.back()));
  for (std::size_t b = 0; b < blocks; ++b) {
    inner.insert(inner.end(), columns[b].begin(), columns[b].end());
    entries.insert(entries.end(), values[b].begin(), values[b].end());
  }
  return RowMajorMatrix(Eigen::Map<const RowMajorMatrix>(n, n, outer.back(), outer.data(), inner.data(), entries.data()));
}

}  // namespace

template <int K>
std::vector<double> block_conjugate_gradients(const Eigen::SparseMatrix<double, Eigen::RowMajor>& A, const Eigen::VectorXd& inverse_diagonal,
                                              const std::vector<double>& B, double tolerance,
                                              unsigned threads) {
  const WorkerTeam team(threads);
  return conjugate_gradients<K>(team, A, inverse_diagonal, B, tolerance);
}

template std::vector<double> block_conjugate_gradients<1>(const Eigen::SparseMatrix<double, Eigen::RowMajor>&,
                                                          const Eigen::VectorXd&, const std::vector<double>&,
                                                          double, unsigned);
template std::vector<double> block_conjugate_gradients<2>(const Eigen::SparseMatrix<double, Eigen::RowMajor>&,
                                                          const Eigen::VectorXd&, const std::vector<double>&,
                                                          double, unsigned);
template std::vector<double> block_conjugate_gradients<3>(const Eigen::SparseMatrix<double, Eigen::RowMajor>&,
                                                          const Eigen::VectorXd&, const std::vector<double>&,
                                                          double, unsigned);

RowMajorMatrix normal_matrix(const Eigen::SparseMatrix<double>& L2, const Eigen::SparseMatrix<double>& L1,
                             const Eigen::VectorXd& d, unsigned threads) {
  const WorkerTeam team(threads);
  return normal_matrix_on(team, L2, L1, d);
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
  std::vector<detail::ModelDerivatives> derivatives;  // one per model
  std::vector<ProjectionTerm> project;
  std::vector<LaplacianTerm> regularize_2d, regularize_1d;
  std::vector<AttractTarget> attract;
  double attract_weight = 1.0;
  std::optional<Plane> plane;
  std::vector<int> plane_vertices;
  double plane_weight = 1.0;
};

using RowMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor>;

/// Coefficient j of a Laplacian term's row (weight w, vertex then its k neighbours): sqrt(w) for
/// the vertex, -sqrt(w) / k for each neighbour.
double laplacian_coefficient(const LaplacianTerm& term, std::size_t j) {
  const double s = std::sqrt(term.weight);
  return j == 0 ? s : -s / static_cast<double>(term.vertices.size() - 1);
}

/// The Laplacian terms with a projection (mirror-plane vertices) as one sparse matrix L (3 rows
/// per term, 3 columns per vertex), so that their energy is |L x|^2 and its gradient 2 L^T L x:
/// the "precomputed gradient matrices for the quadratic terms" of §4.3.
RowMatrix laplacian_matrix(const std::vector<const LaplacianTerm*>& terms, int n) {
  std::vector<Eigen::Triplet<double>> entries;
  for (std::size_t t = 0; t < terms.size(); ++t) {
    const auto& term = *terms[t];
    for (std::size_t j = 0; j < term.vertices.size(); ++j) {
      const double c = laplacian_coefficient(term, j);
      for (int r = 0; r < 3; ++r)
        for (int q = 0; q < 3; ++q)
          if (term.projection(r, q) != 0.0)
            entries.emplace_back(3 * t + r, 3 * term.vertices[j] + q, c * term.projection(r, q));
    }
  }
  RowMatrix L(3 * terms.size(), 3 * n);
  L.setFromTriplets(entries.begin(), entries.end());
  return L;
}

/// The Laplacian terms without projection as one scalar matrix S (a row per term, a column per
/// vertex) that acts on the three coordinates alike: |S X|^2 with X the n x 3 positions. A third
/// of the entries and index loads of laplacian_matrix() for the same products.
RowMatrix scalar_laplacian_matrix(const std::vector<const LaplacianTerm*>& terms, int n) {
  std::vector<Eigen::Triplet<double>> entries;
  for (std::size_t t = 0; t < terms.size(); ++t) {
    const auto& term = *terms[t];
    for (std::size_t j = 0; j < term.vertices.size(); ++j)
      entries.emplace_back(static_cast<int>(t), term.vertices[j], laplacian_coefficient(term, j));
  }
  RowMatrix S(static_cast<Eigen::Index>(terms.size()), n);
  S.setFromTriplets(entries.begin(), entries.end());
  return S;
}

/// Y = A X for X, Y of 3 columns stored row by row (x[3 v + c]), each row of A alone on one of
/// `threads` threads.
void multiply_rows3(const RowMatrix& A, const double* x, double* y, const WorkerTeam& team) {
  team.for_each(0, static_cast<std::size_t>(A.rows()), [&](std::size_t r) {
    double sum[3] = {0.0, 0.0, 0.0};
    for (RowMatrix::InnerIterator it(A, static_cast<Eigen::Index>(r)); it; ++it) {
      const double* from = x + 3 * it.col();
      for (int c = 0; c < 3; ++c) sum[c] += it.value() * from[c];
    }
    for (int c = 0; c < 3; ++c) y[3 * r + c] = sum[c];
  });
}

/// The Laplacian terms of E_regularize split by kind: 2D terms without projection, then 1D ones,
/// as rows of one scalar matrix; 2D terms with a projection (mirror-plane vertices) apart.
struct LaplacianSplit {
  std::vector<const LaplacianTerm*> scalar, projected;
  std::size_t scalar_2d = 0;  // the first scalar_2d scalar rows are 2D terms
};

LaplacianSplit split_laplacians(const MeshEnergy& energy) {
  LaplacianSplit split;
  for (const LaplacianTerm& t : energy.regularize_2d)
    (t.projection.isIdentity(0.0) ? split.scalar : split.projected).push_back(&t);
  split.scalar_2d = split.scalar.size();
  for (const LaplacianTerm& t : energy.regularize_1d)
    (t.projection.isIdentity(0.0) ? split.scalar : split.projected).push_back(&t);
  return split;
}

/// E_mesh evaluated in one pass for L-BFGS. Cost is half the sum of squares, as in Ceres.
class MeshEnergyFunction {
 public:
  MeshEnergyFunction(const MeshEnergy& energy, int n, const WorkerTeam& team)
      : energy_(energy), n_(n), team_(team), split_(split_laplacians(energy)),
        scalar_(scalar_laplacian_matrix(split_.scalar, n)),
        scalar_transpose_(scalar_.transpose()),
        projected_(laplacian_matrix(split_.projected, n)),
        projected_transpose_(projected_.transpose()),
        scalar_residuals_(3 * scalar_.rows()),
        projected_residuals_(projected_.rows()),
        product_(3 * n),
        project_values_(energy.project.size()),
        project_gradients_(energy.project.size()),
        first_term_(static_cast<std::size_t>(n) + 1, 0) {
    // The projection terms come vertex by vertex (build_energy): where each vertex's start.
    for (const ProjectionTerm& t : energy.project) ++first_term_[static_cast<std::size_t>(t.vertex) + 1];
    for (std::size_t v = 0; v < static_cast<std::size_t>(n); ++v) first_term_[v + 1] += first_term_[v];
  }

  /// Half E_mesh at x (3n values) into `cost`, and when `gradient` is not null its gradient
  /// multiplied entry by entry by `gradient_scale` (3n values: in the per-vertex loop that
  /// assembles it when no term is added after that loop, else in a pass of its own). False when
  /// the cost is not finite.
  bool evaluate(const double* x, double* cost, double* gradient, const double* gradient_scale) const {
    const Eigen::Map<const Eigen::VectorXd> X(x, 3 * n_);
    const bool scale_in_loop = projected_.rows() == 0 && energy_.attract.empty() && energy_.plane_vertices.empty();
    // Projection: each term alone (in parallel), accumulated in a fixed order.
    team_.for_each(0, energy_.project.size(), [&](std::size_t i) {
      const ProjectionTerm& t = energy_.project[i];
      project_values_[i] = energy_.derivatives[t.model].taubin(x + 3 * t.vertex, std::sqrt(t.weight), t.floor,
                                                               project_gradients_[i].data());
    });
    double total = 0.0;
    for (std::size_t i = 0; i < energy_.project.size(); ++i) total += 0.5 * project_values_[i] * project_values_[i];
    multiply_rows3(scalar_, x, scalar_residuals_.data(), team_);
    total += 0.5 * scalar_residuals_.squaredNorm();
    Eigen::Map<Eigen::VectorXd> G(gradient, gradient ? 3 * n_ : 0);
    if (gradient) {
      multiply_rows3(scalar_transpose_, scalar_residuals_.data(), product_.data(), team_);
      // Per vertex: its projection terms in order, then the Laplacians' part.
      team_.for_each(0, static_cast<std::size_t>(n_), [&](std::size_t v) {
        Eigen::Vector3d sum = Eigen::Vector3d::Zero();
        for (std::size_t i = first_term_[v]; i < first_term_[v + 1]; ++i)
          sum += project_values_[i] * project_gradients_[i];
        const Eigen::Index at = 3 * static_cast<Eigen::Index>(v);
        const Eigen::Vector3d value = sum + product_.segment<3>(at);
        if (scale_in_loop) G.segment<3>(at) = value.cwiseProduct(Eigen::Map<const Eigen::Vector3d>(gradient_scale + at));
        else G.segment<3>(at) = value;
      });
    }
    if (projected_.rows() > 0) {
      projected_residuals_ = projected_ * X;
      total += 0.5 * projected_residuals_.squaredNorm();
      if (gradient) G += projected_transpose_ * projected_residuals_;
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
    if (gradient && !scale_in_loop)
      team_.for_each(0, static_cast<std::size_t>(n_), [&](std::size_t v) {
        const Eigen::Index at = 3 * static_cast<Eigen::Index>(v);
        G.segment<3>(at).array() *= Eigen::Map<const Eigen::Array3d>(gradient_scale + at);
      });
    *cost = total;
    return std::isfinite(total);
  }

  /// Diagonal of the Gauss-Newton Hessian (3n entries), the projection terms counted isotropically.
  Eigen::VectorXd hessian_diagonal() const {
    Eigen::VectorXd d = Eigen::VectorXd::Zero(3 * n_);
    for (int r = 0; r < scalar_.outerSize(); ++r)
      for (RowMatrix::InnerIterator it(scalar_, r); it; ++it)
        d.segment<3>(3 * it.col()).array() += it.value() * it.value();
    for (int r = 0; r < projected_.outerSize(); ++r)
      for (RowMatrix::InnerIterator it(projected_, r); it; ++it) d[it.col()] += it.value() * it.value();
    for (const ProjectionTerm& t : energy_.project) d.segment<3>(3 * t.vertex).array() += t.weight;
    for (const AttractTarget& t : energy_.attract) d.segment<3>(3 * t.vertex).array() += energy_.attract_weight;
    for (int v : energy_.plane_vertices) d.segment<3>(3 * v) += energy_.plane_weight * energy_.plane->normal.cwiseAbs2();
    return d;
  }

  /// The terms apart, each a plain sum of squares.
  MeshEnergyTerms terms(const double* x) const {
    MeshEnergyTerms e;
    const Eigen::Map<const Eigen::VectorXd> X(x, 3 * n_);
    team_.for_each(0, energy_.project.size(), [&](std::size_t i) {
      const ProjectionTerm& t = energy_.project[i];
      const detail::ProjectionResidual r{&(*energy_.models)[t.model], std::sqrt(t.weight), t.floor};
      r(x + 3 * t.vertex, &project_values_[i]);
    });
    for (double value : project_values_) e.project += value * value;
    Eigen::VectorXd residuals(3 * scalar_.rows());
    multiply_rows3(scalar_, x, residuals.data(), team_);
    const Eigen::Index rows_2d = 3 * static_cast<Eigen::Index>(split_.scalar_2d);
    e.regularize_2d = residuals.head(rows_2d).squaredNorm() + (projected_ * X).squaredNorm();
    e.regularize_1d = residuals.tail(residuals.size() - rows_2d).squaredNorm();
    for (const AttractTarget& t : energy_.attract)
      e.attract += energy_.attract_weight * (X.segment<3>(3 * t.vertex) - t.point).squaredNorm();
    for (int v : energy_.plane_vertices)
      e.plane += energy_.plane_weight * std::pow(energy_.plane->signed_distance(X.segment<3>(3 * v)), 2);
    return e;
  }

 private:
  const MeshEnergy& energy_;
  int n_;
  const WorkerTeam& team_;
  LaplacianSplit split_;
  // The scalar and projected Laplacian matrices and their transposes (row-major, so that every
  // product runs row-parallel), with buffers for their products.
  RowMatrix scalar_, scalar_transpose_, projected_, projected_transpose_;
  mutable Eigen::VectorXd scalar_residuals_, projected_residuals_, product_;
  mutable std::vector<double> project_values_;
  mutable std::vector<Eigen::Vector3d> project_gradients_;
  std::vector<std::size_t> first_term_;  // projection terms of vertex v: [first_term_[v], first_term_[v + 1])
};

/// Chunk length of the L-BFGS vector work: fixed, so its sums do not depend on the thread count.
constexpr std::size_t kVectorChunk = 16384;

/// body(lo, size) over the kVectorChunk-long chunks of [0, n), on `threads` threads.
template <class Body>
void for_vector_chunks(Eigen::Index n, const WorkerTeam& team, Body&& body) {
  team.chunks(static_cast<std::size_t>(n), kVectorChunk,
              [&](std::size_t, Eigen::Index lo, Eigen::Index hi) { body(lo, hi - lo); });
}

/// E_mesh in the variables y = x / s (Jacobi scaling: s = 1 / sqrt(Hessian diagonal)).
class ScaledFunction {
 public:
  ScaledFunction(const MeshEnergyFunction& f, Eigen::VectorXd scale, const WorkerTeam& team)
      : f_(f), scale_(std::move(scale)), x_(scale_.size()), team_(team) {}
  Eigen::Index size() const { return scale_.size(); }
  /// E_mesh and its gradient (in y) at y.
  bool evaluate(const double* y, double* cost, double* gradient) const {
    for_vector_chunks(size(), team_, [&](Eigen::Index lo, Eigen::Index count) {
      x_.segment(lo, count) = scale_.segment(lo, count).cwiseProduct(Eigen::Map<const Eigen::VectorXd>(y + lo, count));
    });
    return f_.evaluate(x_.data(), cost, gradient, scale_.data());
  }
  /// evaluate() at trial = y + step d, written to `trial` in the same pass as the positions.
  bool evaluate_step(const double* y, double step, const double* d, double* trial, double* cost,
                     double* gradient) const {
    for_vector_chunks(size(), team_, [&](Eigen::Index lo, Eigen::Index count) {
      for (Eigen::Index i = lo; i < lo + count; ++i) {
        trial[i] = y[i] + step * d[i];
        x_[i] = scale_[i] * trial[i];
      }
    });
    return f_.evaluate(x_.data(), cost, gradient, scale_.data());
  }

 private:
  const MeshEnergyFunction& f_;
  Eigen::VectorXd scale_;
  mutable Eigen::VectorXd x_;  // buffer of the unscaled positions (a 2 MB allocation per call)
  const WorkerTeam& team_;
};

/// What minimize_lbfgs() did.
struct LbfgsOutcome {
  int iterations = 0;
  bool converged = false;  ///< a tolerance was met (else the iteration cap or a failed line search)
  bool usable = true;      ///< x holds finite values with the lowest cost found
  std::string termination;
};

/// Limited-memory BFGS (Nocedal and Wright 2006, Alg. 7.4-7.5) with H0 = I (the variables are
/// Jacobi-scaled) and a backtracking Armijo line search from the unit step. What Ceres'
/// GradientProblemSolver did with LBFGS and its Wolfe search, which took the unit step at nearly
/// every iteration on E_mesh; but its vector operations ran on one thread with copies around
/// them (29% of a 01-0-1 extraction's CPU, perf), where these run over fixed chunks of the
/// variables on `threads` threads (the sums in a fixed order: the result does not depend on
/// them), the two-loop recursion fusing each update with the next dot product. Stops as Ceres
/// did (largest gradient entry <= gradient_tolerance, relative cost decrease <=
/// function_tolerance, or max_iterations), or when the cost fell by less than stall_tolerance
/// (relative) over the last stall_window iterations (ours, see MeshSolver). `on_iteration(i)` runs
/// after iteration i (0: the start) and may throw to stop.
template <class Callback>
LbfgsOutcome minimize_lbfgs(const ScaledFunction& f, double* x0, const MeshEnergyOptions& options,
                            double gradient_tolerance, const WorkerTeam& team, Callback&& on_iteration) {
  const int rank = options.lbfgs_rank;
  const Eigen::Index m = f.size();
  const std::size_t chunks = (static_cast<std::size_t>(m) + kVectorChunk - 1) / kVectorChunk;
  std::vector<double> partial(chunks), partial_yy(chunks), partial_max(chunks);
  // sum over chunks of body(lo, hi), each chunk on one thread, added in chunk order.
  auto reduce = [&](auto&& body) {
    team.chunks(static_cast<std::size_t>(m), kVectorChunk,
                [&](std::size_t c, Eigen::Index lo, Eigen::Index hi) { partial[c] = body(lo, hi); });
    double sum = 0.0;
    for (double p : partial) sum += p;
    return sum;
  };
  // Elementwise work (the same numbers whatever the threads) over the same chunks.
  auto for_chunks = [&](auto&& body) { for_vector_chunks(m, team, body); };
  // The iterate, written back to x0 however the minimisation ends.
  Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(x0, m);
  struct WriteBack {
    const Eigen::VectorXd& x;
    double* to;
    ~WriteBack() { std::copy(x.data(), x.data() + x.size(), to); }
  } write_back{x, x0};
  Eigen::VectorXd g(m), d(m), trial(m), trial_gradient(m);
  std::vector<Eigen::VectorXd> S(static_cast<std::size_t>(rank), Eigen::VectorXd(m)), Y = S;
  std::vector<double> rho(static_cast<std::size_t>(rank)), alpha(static_cast<std::size_t>(rank));
  int stored = 0, newest = -1;
  LbfgsOutcome out;
  double cost = 0.0;
  std::vector<double> costs;  // the cost after each iteration, 0 the start
  if (!f.evaluate(x.data(), &cost, g.data())) {
    out.usable = false;
    out.termination = "FAILURE: E_mesh is not finite at the start";
    return out;
  }
  costs.push_back(cost);
  // The largest gradient entry (of g; then of each accepted step's gradient, in the pass that
  // makes the new pair).
  for_chunks([&](Eigen::Index lo, Eigen::Index size) { partial_max[static_cast<std::size_t>(lo) / kVectorChunk] = g.segment(lo, size).cwiseAbs().maxCoeff(); });
  on_iteration(0);
  auto slot = [&](int age) { return static_cast<std::size_t>((newest - age + rank) % rank); };
  for (int it = 1; it <= options.max_iterations; ++it) {
    if (*std::max_element(partial_max.begin(), partial_max.end()) <= gradient_tolerance) {
      out.converged = true;
      out.termination = "CONVERGENCE: gradient tolerance reached";
      return out;
    }
    // Two-loop recursion: d = -H g, newest pair first, then back; each pass updates d with one
    // pair and computes the dot product the next pair needs.
    double dot = 0.0;
    if (stored > 0) dot = reduce([&](Eigen::Index lo, Eigen::Index hi) {
      d.segment(lo, hi - lo) = -g.segment(lo, hi - lo);
      return S[slot(0)].segment(lo, hi - lo).dot(d.segment(lo, hi - lo));
    });
    else d = -g;
    for (int age = 0; age < stored; ++age) {
      const std::size_t i = slot(age);
      alpha[i] = rho[i] * dot;
      const bool last = age + 1 == stored;
      dot = reduce([&](Eigen::Index lo, Eigen::Index hi) {
        auto seg = d.segment(lo, hi - lo);
        seg -= alpha[i] * Y[i].segment(lo, hi - lo);
        return last ? Y[i].segment(lo, hi - lo).dot(seg) : S[slot(age + 1)].segment(lo, hi - lo).dot(seg);
      });
    }
    for (int age = stored - 1; age >= 0; --age) {
      const std::size_t i = slot(age);
      const double beta = rho[i] * dot;
      const bool last = age == 0;
      dot = reduce([&](Eigen::Index lo, Eigen::Index hi) {
        auto seg = d.segment(lo, hi - lo);
        seg += (alpha[i] - beta) * S[i].segment(lo, hi - lo);
        return last ? g.segment(lo, hi - lo).dot(seg) : Y[slot(age - 1)].segment(lo, hi - lo).dot(seg);
      });
    }
    double slope = stored > 0 ? dot : -g.squaredNorm();
    if (!(slope < 0.0)) {  // not a descent direction: forget the pairs, go down the gradient
      stored = 0;
      d = -g;
      slope = -g.squaredNorm();
    }
    // Armijo backtracking from the unit step, halving (or the minimiser of the quadratic through
    // the cost and slope at 0 and the trial cost, kept within [0.1, 0.5] of the step).
    double step = 1.0, trial_cost = 0.0;
    bool accepted = false;
    for (int search = 0; search < 40 && !accepted; ++search) {
      const bool finite = f.evaluate_step(x.data(), step, d.data(), trial.data(), &trial_cost, trial_gradient.data());
      if (finite && trial_cost <= cost + 1e-4 * step * slope) {
        accepted = true;
      } else {
        const double curvature = finite ? trial_cost - cost - slope * step : 0.0;
        const double quadratic = curvature > 0.0 ? -slope * step * step / (2.0 * curvature) : 0.5 * step;
        step = std::clamp(quadratic, 0.1 * step, 0.5 * step);
      }
    }
    if (!accepted) {
      out.termination = "FAILURE: no step along the L-BFGS direction lowers E_mesh";
      return out;
    }
    // The new pair (s, y) if it keeps H positive definite; y.y and the new gradient's largest
    // entry in the same pass.
    const std::size_t next = static_cast<std::size_t>((newest + 1) % rank);
    const double sy = reduce([&](Eigen::Index lo, Eigen::Index hi) {
      auto s = S[next].segment(lo, hi - lo);
      auto y = Y[next].segment(lo, hi - lo);
      s = trial.segment(lo, hi - lo) - x.segment(lo, hi - lo);
      y = trial_gradient.segment(lo, hi - lo) - g.segment(lo, hi - lo);
      const std::size_t c = static_cast<std::size_t>(lo) / kVectorChunk;
      partial_yy[c] = y.squaredNorm();
      partial_max[c] = trial_gradient.segment(lo, hi - lo).cwiseAbs().maxCoeff();
      return s.dot(y);
    });
    double yy = 0.0;
    for (double p : partial_yy) yy += p;
    if (sy > 1e-14 * yy) {
      newest = static_cast<int>(next);
      rho[next] = 1.0 / sy;
      stored = std::min(stored + 1, rank);
    } else if (stored == rank) {
      stored = rank - 1;  // the oldest pair's slot was overwritten
    }
    const double decrease = cost - trial_cost;
    x.swap(trial);
    g.swap(trial_gradient);
    const double previous = cost;
    cost = trial_cost;
    out.iterations = it;
    costs.push_back(cost);
    on_iteration(it);
    if (decrease <= options.function_tolerance * previous) {
      out.converged = true;
      out.termination = "CONVERGENCE: function tolerance reached";
      return out;
    }
    const int window = options.stall_window;
    if (window > 0 && it >= window && costs[it - window] - cost <= options.stall_tolerance * costs[it - window]) {
      out.converged = true;
      std::ostringstream message;
      message << "CONVERGENCE: E_mesh fell by less than " << 100.0 * options.stall_tolerance << "% over the last "
              << window << " iterations";
      out.termination = message.str();
      return out;
    }
  }
  out.termination = "NO_CONVERGENCE: maximum number of iterations reached";
  return out;
}

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

/// The closest point of Z(f) to x, approximately: Newton steps along the gradient
/// (x -= f grad f / |grad f|^2), each at most `max_step` long.
Eigen::Vector3d project_onto(const detail::ModelDerivatives& model, Eigen::Vector3d x, int steps,
                             double max_step) {
  for (int step = 0; step < steps; ++step) {
    Eigen::Vector3d g;
    const double f = model.value_and_gradient(x.data(), g.data());
    const double gg = g.squaredNorm();
    if (!(gg > 0.0)) break;
    Eigen::Vector3d dx = -f / gg * g;
    if (!dx.allFinite()) break;
    const double length = dx.norm();
    if (length > max_step) dx *= max_step / length;
    x += dx;
  }
  return x;
}


/// The global step of local_global(): E_mesh with each Taubin distance replaced by the distance
/// to a fixed point is a quadratic whose normal equations split into one sparse SPD system per
/// coordinate in the frame whose first axis is the mirror plane's normal (there the in-plane
/// projections of the Laplacian terms and the plane penalty are diagonal): one matrix for the three
/// coordinates, two with a mirror plane. The matrices hold the Laplacians' 2-ring products, do not
/// depend on the points and are built once; each solve is an inexact conjugate-gradient one
/// (Jacobi preconditioner, the coordinates of one matrix together: block_conjugate_gradients()).
/// A sparse Cholesky factorisation of the same matrix (Eigen SimplicialLDLT, AMD ordering) took
/// 16.6 s on the 84k-vertex hat proxy, so the start would cost more than the whole solve; an
/// incomplete Cholesky preconditioner (Eigen IncompleteCholesky) cuts the iterations per solve
/// from ~95 to ~34 on the 70k-vertex hat but makes each global step slower (0.45 -> 0.6 s: its
/// triangular solves are serial) after a 0.4 s factorisation (measured, see MeshEnergyOptions).
class GlobalStep {
 public:
  GlobalStep(const MeshEnergy& energy, int n, double tolerance, const WorkerTeam& team)
      : n_(n), plane_(energy.plane.has_value()), tolerance_(tolerance) {
    if (plane_) {
      // Rows: the plane normal, then two in-plane axes.
      const Eigen::Vector3d normal = energy.plane->normal;
      const Eigen::Vector3d u = normal.unitOrthogonal();
      frame_.row(0) = normal.transpose();
      frame_.row(1) = u.transpose();
      frame_.row(2) = normal.cross(u).transpose();
    }
    Eigen::VectorXd diagonal = Eigen::VectorXd::Zero(n);
    for (const ProjectionTerm& t : energy.project) diagonal[t.vertex] += t.weight;
    constant_rhs_ = Eigen::MatrixX3d::Zero(n, 3);
    for (const AttractTarget& t : energy.attract) {
      diagonal[t.vertex] += energy.attract_weight;
      constant_rhs_.row(t.vertex) += energy.attract_weight * (frame_ * t.point).transpose();
    }
    Eigen::VectorXd plane_diagonal = Eigen::VectorXd::Zero(n);
    for (int v : energy.plane_vertices) {
      plane_diagonal[v] += energy.plane_weight;
      constant_rhs_(v, 0) -= energy.plane_weight * energy.plane->offset;
    }
    // System 0: the coordinates without plane terms (all three, or the two in-plane ones);
    // system 1: the plane's normal coordinate.
    for (int s = 0; s < (plane_ ? 2 : 1); ++s) {
      const int c = s == 0 && plane_ ? 1 : 0;
      const Eigen::VectorXd d = s == 1 ? Eigen::VectorXd(diagonal + plane_diagonal) : diagonal;
      matrix_[s] = detail::normal_matrix_on(team, laplacian_rows(energy.regularize_2d, c),
                                            laplacian_rows(energy.regularize_1d, c), d);
      inverse_diagonal_[s] = matrix_[s].diagonal().cwiseMax(std::numeric_limits<double>::min()).cwiseInverse();
    }
  }

  /// x (3n, world units) moves to the minimiser of the quadratic whose pull terms are, per vertex,
  /// its projection-term weights times |x_v - p|^2; `pulled` holds per vertex the weighted sum of
  /// its points p. Solved for the change of x, so that the tolerance is relative to the residual.
  void solve(const Eigen::MatrixX3d& pulled, const WorkerTeam& team, std::vector<double>& x) const {
    const Eigen::MatrixX3d rhs = pulled * frame_.transpose() + constant_rhs_;
    Eigen::MatrixX3d y(n_, 3);
    for (int v = 0; v < n_; ++v) y.row(v) = (frame_ * Eigen::Map<const Eigen::Vector3d>(&x[3 * v])).transpose();
    // System 1 (the plane's normal coordinate) solves column 0, system 0 the others.
    for (int s = 0; s < (plane_ ? 2 : 1); ++s) {
      const int first = s == 0 && plane_ ? 1 : 0, count = plane_ ? (s == 0 ? 2 : 1) : 3;
      // The residual rhs - A y, n x count row-major.
      std::vector<double> residual(static_cast<std::size_t>(n_) * count);
      team.for_each(0, static_cast<std::size_t>(n_), [&](std::size_t v) {
        for (int j = 0; j < count; ++j) {
          double sum = rhs(static_cast<Eigen::Index>(v), first + j);
          for (RowMatrix::InnerIterator e(matrix_[s], static_cast<Eigen::Index>(v)); e; ++e)
            sum -= e.value() * y(e.col(), first + j);
          residual[v * count + j] = sum;
        }
      });
      const std::vector<double> change =
          count == 3 ? detail::conjugate_gradients<3>(team, matrix_[s], inverse_diagonal_[s], residual, tolerance_)
          : count == 2 ? detail::conjugate_gradients<2>(team, matrix_[s], inverse_diagonal_[s], residual, tolerance_)
                       : detail::conjugate_gradients<1>(team, matrix_[s], inverse_diagonal_[s], residual, tolerance_);
      for (int v = 0; v < n_; ++v)
        for (int j = 0; j < count; ++j) y(v, first + j) += change[static_cast<std::size_t>(v) * count + j];
    }
    const Eigen::MatrixX3d world = y * frame_;
    for (int v = 0; v < n_; ++v)
      for (int c = 0; c < 3; ++c) x[3 * v + c] = world(v, c);
  }

 private:
  /// L_c: the terms' Laplacian rows for coordinate c of the frame (a row per term, empty for the
  /// terms that do not act on it).
  Eigen::SparseMatrix<double> laplacian_rows(const std::vector<LaplacianTerm>& terms, int c) const {
    std::vector<Eigen::Triplet<double>> entries;
    for (std::size_t t = 0; t < terms.size(); ++t) {
      const LaplacianTerm& term = terms[t];
      // The projection is I or I - n n^T: its (c, c) entry in the frame is 1 or 0.
      if ((frame_ * term.projection * frame_.transpose())(c, c) < 0.5) continue;
      for (std::size_t j = 0; j < term.vertices.size(); ++j)
        entries.emplace_back(static_cast<int>(t), term.vertices[j], laplacian_coefficient(term, j));
    }
    Eigen::SparseMatrix<double> L(static_cast<int>(terms.size()), n_);
    L.setFromTriplets(entries.begin(), entries.end());
    return L;
  }

  int n_;
  bool plane_;
  Eigen::Matrix3d frame_ = Eigen::Matrix3d::Identity();
  Eigen::MatrixX3d constant_rhs_;
  double tolerance_;
  std::array<RowMatrix, 2> matrix_;
  std::array<Eigen::VectorXd, 2> inverse_diagonal_;
};

/// Local-global start (ours, after projective dynamics, Bouaziz et al. 2014): E_project's
/// distance to Z(f_a) is the distance to the closest point of Z(f_a), so alternately moving each
/// vertex's points onto its surfaces (local step: project_onto(), in parallel) and minimising
/// over the vertices with the points fixed (global step: GlobalStep) lowers E_mesh. Global steps
/// spread a change over the whole mesh where L-BFGS needs hundreds of iterations (the Laplacian
/// terms make E_mesh stiff); the sliding of vertices along the surfaces stays slow in both, and
/// the L-BFGS solve does it. Runs `iterations` times or until no vertex moves more than
/// `tolerance` (mesh units); returns the iterations made.
int local_global(const MeshEnergy& energy, int n, int iterations, int projection_steps, double max_step,
                 double tolerance, double solve_tolerance, const WorkerTeam& team, std::vector<double>& x) {
  const GlobalStep global(energy, n, solve_tolerance, team);
  std::vector<Eigen::Vector3d> points(energy.project.size());
  Eigen::MatrixX3d pulled(n, 3);
  std::vector<double> previous;
  for (int it = 1; it <= iterations; ++it) {
    team.for_each(0, energy.project.size(), [&](std::size_t i) {
      const ProjectionTerm& t = energy.project[i];
      points[i] = project_onto(energy.derivatives[t.model], Eigen::Map<const Eigen::Vector3d>(&x[3 * t.vertex]),
                               projection_steps, max_step);
    });
    pulled.setZero();
    for (std::size_t i = 0; i < points.size(); ++i)
      pulled.row(energy.project[i].vertex) += energy.project[i].weight * points[i].transpose();
    previous = x;
    global.solve(pulled, team, x);
    double moved = 0.0;
    for (int v = 0; v < n; ++v)
      moved = std::max(moved, (Eigen::Map<const Eigen::Vector3d>(&x[3 * v]) -
                               Eigen::Map<const Eigen::Vector3d>(&previous[3 * v])).squaredNorm());
    if (std::sqrt(moved) <= tolerance) return it;
  }
  return iterations;
}

/// Builds the terms of E_mesh for the mesh at its current positions.
MeshEnergy build_energy(const LabeledMesh& lm, const std::vector<ImplicitModel>& models,
                        const MeshConstraints& constraints, const MeshEnergyOptions& options) {
  const TriMesh& mesh = lm.mesh;
  const int n = static_cast<int>(mesh.n_vertices());
  MeshEnergy energy;
  energy.models = &models;
  for (const ImplicitModel& model : models) energy.derivatives.emplace_back(model);

  // E_project (Eq. 8). The gradient floor is relative to each model's typical gradient.
  std::vector<std::vector<double>> norms(static_cast<std::size_t>(n));
  parallel_for(0, static_cast<std::size_t>(n), resolve_threads(options.threads), [&](std::size_t v) {
    const Eigen::Vector3d p = to_eigen(mesh.point(TriMesh::VertexHandle(static_cast<int>(v))));
    for (int l : lm.labels[v]) norms[v].push_back(models[l].gradient(p).norm());
  });
  std::vector<std::vector<double>> gradients(models.size());
  for (int v = 0; v < n; ++v)
    for (std::size_t a = 0; a < lm.labels[v].size(); ++a) gradients[lm.labels[v][a]].push_back(norms[v][a]);
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
  const WorkerTeam team(threads);
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
  summary.initial = MeshEnergyFunction(initial_energy, n, team).terms(x.data());
  const auto start = std::chrono::steady_clock::now();
  if (options.projection_steps > 0) {
    project_vertices(lm, models, options.projection_steps, options.max_projection_step * size, threads);
    load();
  }
  const MeshEnergy energy = build_energy(lm, models, constraints, options);
  if (options.local_global_iterations > 0) {
    double edges = 0.0;
    for (auto e : mesh.edges()) edges += mesh.calc_edge_length(e);
    const double mean_edge = mesh.n_edges() > 0 ? edges / mesh.n_edges() : size;
    summary.local_global_iterations = local_global(
        energy, n, options.local_global_iterations, std::max(1, options.projection_steps),
        options.max_projection_step * size, options.local_global_tolerance * mean_edge,
        options.global_step_tolerance, team, x);
  }
  const MeshEnergyFunction function(energy, n, team);

  if (options.solver == MeshSolver::Lbfgs) {
    // Jacobi scaling: L-BFGS runs on y = x / s.
    const Eigen::VectorXd scale = function.hessian_diagonal().cwiseMax(1e-12).cwiseSqrt().cwiseInverse();
    Eigen::Map<Eigen::VectorXd> X(x.data(), 3 * n);
    X.array() /= scale.array();
    const ScaledFunction scaled(function, scale, team);
    const LbfgsOutcome outcome = minimize_lbfgs(
        scaled, x.data(), options, options.gradient_tolerance * size, team, [&](int iteration) {
          progress.update("extract", std::min(1.0, double(iteration) / options.max_iterations));
        });
    X.array() *= scale.array();
    summary.final = function.terms(x.data());
    summary.iterations = outcome.iterations;
    summary.termination = outcome.termination;
    summary.solver = "LINE_SEARCH, LBFGS (ours, Armijo)";
    summary.usable = outcome.usable;
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
    CeresProgress callback(progress, options.max_iterations);
    solver.callbacks.push_back(&callback);
    ceres::Solver::Summary s;
    ceres::Solve(solver, &problem, &s);
    callback.rethrow();
    summary.final = function.terms(x.data());
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
