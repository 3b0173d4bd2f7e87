#include "surfacing/extract/global_step.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <Eigen/Sparse>

namespace sketchsurf::detail {

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

namespace {

/// The closest point to x of the level set `offset` inside Z(f) (Taubin distance f / |grad f| =
/// -offset), approximately: Newton steps along the gradient
/// (x -= (f + offset |grad f|) grad f / |grad f|^2), each at most `max_step` long.
Eigen::Vector3d project_onto(const ModelDerivatives& model, Eigen::Vector3d x, double offset, int steps,
                             double max_step) {
  for (int step = 0; step < steps; ++step) {
    Eigen::Vector3d g;
    const double f = model.value_and_gradient(x.data(), g.data());
    const double gg = g.squaredNorm();
    if (!(gg > 0.0)) break;
    Eigen::Vector3d dx = -(f + offset * std::sqrt(gg)) / gg * g;
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
/// Not a sparse Cholesky factorisation: with the 2-ring fill-in it costs more than the whole
/// solve; not an incomplete Cholesky preconditioner either: fewer iterations, but serial
/// triangular solves make each step slower (measured, docs/performance.md).
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
      diagonal[t.vertex] += energy.attract_weight * t.weight;
      constant_rhs_.row(t.vertex) += energy.attract_weight * t.weight * (frame_ * t.point).transpose();
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
      matrix_[s] = normal_matrix_on(team, laplacian_rows(energy.regularize_2d, c),
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
          for (RowMajorMatrix::InnerIterator e(matrix_[s], static_cast<Eigen::Index>(v)); e; ++e)
            sum -= e.value() * y(e.col(), first + j);
          residual[v * count + j] = sum;
        }
      });
      const std::vector<double> change =
          count == 3 ? conjugate_gradients<3>(team, matrix_[s], inverse_diagonal_[s], residual, tolerance_)
          : count == 2 ? conjugate_gradients<2>(team, matrix_[s], inverse_diagonal_[s], residual, tolerance_)
                       : conjugate_gradients<1>(team, matrix_[s], inverse_diagonal_[s], residual, tolerance_);
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
  std::array<RowMajorMatrix, 2> matrix_;
  std::array<Eigen::VectorXd, 2> inverse_diagonal_;
};

}  // namespace

int local_global(const MeshEnergy& energy, int n, int iterations, int projection_steps, double max_step,
                 double tolerance, double solve_tolerance, const WorkerTeam& team, std::vector<double>& x) {
  const GlobalStep global(energy, n, solve_tolerance, team);
  std::vector<Eigen::Vector3d> points(energy.project.size());
  Eigen::MatrixX3d pulled(n, 3);
  std::vector<double> previous;
  for (int it = 1; it <= iterations; ++it) {
    team.for_each(0, energy.project.size(), [&](std::size_t i) {
      const ProjectionTerm& t = energy.project[i];
      points[i] = project_onto(energy.derivatives[t.model], Eigen::Map<const Eigen::Vector3d>(&x[3 * t.vertex]), t.offset,
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

}  // namespace sketchsurf::detail
