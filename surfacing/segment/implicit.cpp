#include "surfacing/segment/implicit.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "surfacing/error.h"
#include "surfacing/portable_math.h"

namespace sketchsurf {
namespace {

constexpr MonomialExponents kMonomials = implicit_monomials();

// Relative floor on a column's standard deviation (times r^degree, see fit_implicit's comment).
constexpr double kDeviationFloor = 1e-3;

bool all_finite(const Eigen::Ref<const Eigen::MatrixX3d>& m) { return m.allFinite(); }

// Powers y_i^e, e = 0..degree, of the three normalised coordinates.
struct Powers {
  double p[3][kMaxImplicitDegree + 1];
  Powers(const Eigen::Vector3d& y, int degree) {
    for (int i = 0; i < 3; ++i) {
      p[i][0] = 1.0;
      for (int e = 1; e <= degree; ++e) p[i][e] = p[i][e - 1] * y[i];
    }
  }
  double monomial(int k) const {
    const auto& m = kMonomials[k];
    return p[0][m[0]] * p[1][m[1]] * p[2][m[2]];
  }
  // n . grad_y m_k(y).
  double directional(int k, const Eigen::Vector3d& n) const {
    const auto& m = kMonomials[k];
    double d = 0.0;
    if (m[0] > 0) d += n[0] * m[0] * p[0][m[0] - 1] * p[1][m[1]] * p[2][m[2]];
    if (m[1] > 0) d += n[1] * m[1] * p[0][m[0]] * p[1][m[1] - 1] * p[2][m[2]];
    if (m[2] > 0) d += n[2] * m[2] * p[0][m[0]] * p[1][m[1]] * p[2][m[2] - 1];
    return d;
  }
};

int monomial_degree(int k) { return kMonomials[k][0] + kMonomials[k][1] + kMonomials[k][2]; }

}  // namespace

int monomial_count(int degree) {
  if (degree < 0 || degree > kMaxImplicitDegree)
    throw Error::usage("implicit model degree must be in 0..4, got " + std::to_string(degree));
  return (degree + 1) * (degree + 2) * (degree + 3) / 6;
}

bool ImplicitModel::valid(std::string* why) const {
  auto fail = [&](const std::string& what) {
    if (why) *why = what;
    return false;
  };
  if (degree < 1 || degree > kMaxImplicitDegree)
    return fail("degree " + std::to_string(degree) + " outside 1..4");
  if (coefficients.size() != monomial_count(degree))
    return fail(std::to_string(coefficients.size()) + " coefficients for degree " +
                std::to_string(degree) + " (expected " + std::to_string(monomial_count(degree)) +
                ")");
  if (!coefficients.allFinite()) return fail("non-finite coefficient");
  if (!center.allFinite()) return fail("non-finite center");
  if (!(std::isfinite(scale) && scale > 0.0)) return fail("scale must be finite and > 0");
  return true;
}

int ImplicitModel::dimension() const { return static_cast<int>(coefficients.size()); }

double ImplicitModel::value(const Eigen::Vector3d& x) const { return evaluate(x.data()); }

Eigen::Vector3d ImplicitModel::gradient(const Eigen::Vector3d& x) const {
  Eigen::Vector3d g;
  evaluate_gradient(x.data(), g.data());
  return g;
}

double ImplicitModel::distance(const Eigen::Vector3d& x) const {
  const double f = std::abs(value(x));
  if (f == 0.0) return 0.0;
  const double g = gradient(x).norm();
  if (g == 0.0) return std::numeric_limits<double>::infinity();
  return f / g;
}

namespace {

constexpr int kLanes = 4;  // points per block of distances_for()

// Adds monomial K's term of f and of each gradient component over a block's lanes: powers
// [axis][exponent][lane], f[lane], g[axis][lane]; c the coefficients.
template <std::size_t K, int D>
void add_value_term(const double* c, const double (&powers)[3][D + 1][kLanes], double (&f)[kLanes]) {
  constexpr auto m = kMonomials[K];
  for (int l = 0; l < kLanes; ++l)
    f[l] += c[K] * (powers[0][m[0]][l] * powers[1][m[1]][l] * powers[2][m[2]][l]);
}

template <std::size_t K, int D>
void add_gradient_terms(const double* c, const double (&powers)[3][D + 1][kLanes],
                        double (&g)[3][kLanes]) {
  constexpr auto m = kMonomials[K];
  if constexpr (m[0] > 0) {
    const double ck = c[K] * m[0];
    for (int l = 0; l < kLanes; ++l)
      g[0][l] += ck * (powers[0][m[0] - 1][l] * powers[1][m[1]][l] * powers[2][m[2]][l]);
  }
  if constexpr (m[1] > 0) {
    const double ck = c[K] * m[1];
    for (int l = 0; l < kLanes; ++l)
      g[1][l] += ck * (powers[0][m[0]][l] * powers[1][m[1] - 1][l] * powers[2][m[2]][l]);
  }
  if constexpr (m[2] > 0) {
    const double ck = c[K] * m[2];
    for (int l = 0; l < kLanes; ++l)
      g[2][l] += ck * (powers[0][m[0]][l] * powers[1][m[1]][l] * powers[2][m[2] - 1][l]);
  }
}

// implicit_distances for a model of T monomials (4, 10, 20 or 35): the points in blocks of
// kLanes, each operation of distance() done for the block's points in an inner loop over lanes
// (the compiler keeps them in vector registers), the monomials unrolled with compile-time
// exponents. Each lane's operations are distance()'s, in the same order: the same bits. 3.5x
// faster than one point at a time (10.7k points: quartic 80 -> 23 ns per point, quadric 33 -> 9).
template <int T>
void distances_for(const ImplicitModel& model, Eigen::Ref<const Eigen::MatrixX3d> points,
                   double* out) {
  constexpr int kDegree = kMonomials[T - 1][0] + kMonomials[T - 1][1] + kMonomials[T - 1][2];
  const double* c = model.coefficients.data();
  const Eigen::Index n = points.rows(), stride = points.outerStride();
  for (Eigen::Index first = 0; first < n; first += kLanes) {
    const int lanes = static_cast<int>(std::min<Eigen::Index>(kLanes, n - first));
    double powers[3][kDegree + 1][kLanes];  // [axis][exponent][lane]; unused lanes repeat lane 0
    for (int i = 0; i < 3; ++i)
      for (int l = 0; l < kLanes; ++l) {
        const double x = points.data()[i * stride + first + (l < lanes ? l : 0)];
        const double y = (x - model.center[i]) / model.scale;
        powers[i][0][l] = 1.0;
        for (int e = 1; e <= kDegree; ++e) powers[i][e][l] = powers[i][e - 1][l] * y;
      }
    double f[kLanes] = {}, g[3][kLanes] = {};
    [&]<std::size_t... K>(std::index_sequence<K...>) {
      (add_value_term<K, kDegree>(c, powers, f), ...);
    }(std::make_index_sequence<T>{});
    // The gradient (computed for every lane; distance() needs it only where f != 0).
    [&]<std::size_t... K>(std::index_sequence<K...>) {
      (add_gradient_terms<K + 1, kDegree>(c, powers, g), ...);
    }(std::make_index_sequence<T - 1>{});
    for (int l = 0; l < lanes; ++l) {
      const double value = std::abs(f[l]);
      if (value == 0.0) {
        out[first + l] = 0.0;
        continue;
      }
      const Eigen::Vector3d gradient(g[0][l] / model.scale, g[1][l] / model.scale,
                                     g[2][l] / model.scale);
      const double norm = gradient.norm();
      out[first + l] = norm == 0.0 ? std::numeric_limits<double>::infinity() : value / norm;
    }
  }
}

}  // namespace

void implicit_distances(const ImplicitModel& model, Eigen::Ref<const Eigen::MatrixX3d> points,
                        double* out) {
  // The same operations, in the same order, as evaluate(), evaluate_gradient() and distance().
  const Eigen::Index t = std::min<Eigen::Index>(model.coefficients.size(), kMonomials.size());
  switch (t) {
    case 4: return distances_for<4>(model, points, out);
    case 10: return distances_for<10>(model, points, out);
    case 20: return distances_for<20>(model, points, out);
    case 35: return distances_for<35>(model, points, out);
    default:
      for (Eigen::Index p = 0; p < points.rows(); ++p) out[p] = model.distance(points.row(p).transpose());
  }
}

bool FitOptions::valid(std::string* why) const {
  auto fail = [&](const char* what) {
    if (why) *why = what;
    return false;
  };
  if (!(std::isfinite(mu) && mu >= 0.0)) return fail("mu must be finite and >= 0");
  if (!(std::isfinite(lambda) && lambda >= 0.0)) return fail("lambda must be finite and >= 0");
  if (alignment != NormalAlignment::Summed && alignment != NormalAlignment::PerVertex)
    return fail("unknown normal alignment mode");
  if (!(std::isfinite(length_unit) && length_unit >= 0.0))
    return fail("length_unit must be finite and >= 0 (0 = the data's bounding-box diagonal)");
  return true;
}

NormalMoments::NormalMoments(const Eigen::Vector3d& about) : origin(about) {
  lo.setConstant(std::numeric_limits<double>::infinity());
  hi.setConstant(-std::numeric_limits<double>::infinity());
}

void NormalMoments::add(const Eigen::Vector3d& position, const Eigen::Vector3d& normal) {
  const Eigen::Vector3d y = position - origin;
  ++count;
  lo = lo.cwiseMin(position);
  hi = hi.cwiseMax(position);
  sum += y;
  squared += y.squaredNorm();
  const Powers powers(y, 3);
  for (int k = 0; k < kPowers; ++k) {
    const double m = powers.monomial(k);
    for (int i = 0; i < 3; ++i) directional[i][k] += normal[i] * m;
  }
}

NormalMoments& NormalMoments::operator+=(const NormalMoments& other) {
  if (other.origin != origin)
    throw Error::usage("NormalMoments: adding sums about another origin");
  count += other.count;
  lo = lo.cwiseMin(other.lo);
  hi = hi.cwiseMax(other.hi);
  sum += other.sum;
  squared += other.squared;
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < kPowers; ++k) directional[i][k] += other.directional[i][k];
  return *this;
}

namespace {

// kMonomialIndex[a][b][c]: index in implicit_monomials() of x^a y^b z^c (a + b + c <= 4).
constexpr auto kMonomialIndex = [] {
  std::array<std::array<std::array<int, kMaxImplicitDegree + 1>, kMaxImplicitDegree + 1>,
             kMaxImplicitDegree + 1>
      index{};
  for (int k = 0; k < static_cast<int>(kMonomials.size()); ++k)
    index[kMonomials[k][0]][kMonomials[k][1]][kMonomials[k][2]] = k;
  return index;
}();

// The normal points' share of a fit, in the model's normalised coordinates y = (x - center) /
// scale: sum |y|^2, and the alignment rows n . grad m_k(y), k = 1..t-1 (their sum, and each
// vertex's row for Eq. 6's per-vertex form).
struct NormalTerms {
  double squared = 0.0;
  Eigen::VectorXd align_sum;
  Eigen::MatrixXd align_rows;
};

// From the points themselves.
NormalTerms terms_from_points(const ImplicitModel& frame, Eigen::Ref<const Eigen::MatrixX3d> points,
                              Eigen::Ref<const Eigen::MatrixX3d> normals, bool align,
                              bool per_vertex) {
  const int u = monomial_count(frame.degree) - 1;
  NormalTerms r;
  r.align_sum = Eigen::VectorXd::Zero(u);
  r.align_rows.resize(align && per_vertex ? points.rows() : 0, u);
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    const Eigen::Vector3d y = (points.row(i).transpose() - frame.center) / frame.scale;
    r.squared += y.squaredNorm();
    if (!align) continue;
    const Powers powers(y, frame.degree);
    const Eigen::Vector3d n = normals.row(i).transpose();
    for (int k = 1; k <= u; ++k) {
      const double d = powers.directional(k, n);
      if (per_vertex) r.align_rows(i, k - 1) = d;
      r.align_sum[k - 1] += d;
    }
  }
  return r;
}

// From the moments about o: y = (z + d) / s with z = x - o, d = o - center, s = scale, so
// sum n_i y^g = s^-|g| sum_{e <= g} prod_j C(g_j, e_j) d_j^(g_j - e_j) sum n_i z^e.
NormalTerms terms_from_moments(const ImplicitModel& frame, const NormalMoments& m, bool align) {
  const int u = monomial_count(frame.degree) - 1;
  NormalTerms r;
  const Eigen::Vector3d d = m.origin - frame.center;
  const double n = static_cast<double>(m.count);
  r.squared = (m.squared + 2.0 * d.dot(m.sum) + n * d.squaredNorm()) / (frame.scale * frame.scale);
  r.align_sum = Eigen::VectorXd::Zero(u);
  if (!align) return r;
  constexpr double kBinomial[4][4] = {{1, 0, 0, 0}, {1, 1, 0, 0}, {1, 2, 1, 0}, {1, 3, 3, 1}};
  double shift[3][4];  // C(g, e) d^(g - e) is kBinomial[g][e] * shift[j][g - e]
  for (int j = 0; j < 3; ++j) {
    shift[j][0] = 1.0;
    for (int e = 1; e < 4; ++e) shift[j][e] = shift[j][e - 1] * d[j];
  }
  // S[i][g]: sum n_i y^g for the monomials g of degree <= degree - 1 (gradients of degree-d ones).
  const int gradient_monomials = monomial_count(frame.degree - 1);
  double S[3][NormalMoments::kPowers];
  for (int g = 0; g < gradient_monomials; ++g) {
    const auto& ge = kMonomials[g];
    const double unit = portable::pow(frame.scale, -(ge[0] + ge[1] + ge[2]));
    for (int i = 0; i < 3; ++i) {
      double acc = 0.0;
      for (int a = 0; a <= ge[0]; ++a)
        for (int b = 0; b <= ge[1]; ++b)
          for (int c = 0; c <= ge[2]; ++c)
            acc += kBinomial[ge[0]][a] * shift[0][ge[0] - a] * kBinomial[ge[1]][b] *
                   shift[1][ge[1] - b] * kBinomial[ge[2]][c] * shift[2][ge[2] - c] *
                   m.directional[i][kMonomialIndex[a][b][c]];
      S[i][g] = unit * acc;
    }
  }
  for (int k = 1; k <= u; ++k) {
    const auto& me = kMonomials[k];
    double value = 0.0;
    for (int i = 0; i < 3; ++i) {
      if (me[i] == 0) continue;
      auto g = me;
      --g[i];
      value += me[i] * S[i][kMonomialIndex[g[0]][g[1]][g[2]]];
    }
    r.align_sum[k - 1] = value;
  }
  return r;
}

void check_fit_input(int degree, Eigen::Ref<const Eigen::MatrixX3d> points,
                     const FitOptions& options) {
  if (degree < 1 || degree > kMaxImplicitDegree)
    throw Error::usage("fit_implicit: degree must be in 1..4, got " + std::to_string(degree));
  std::string why;
  if (!options.valid(&why)) throw Error::usage("fit_implicit: invalid options: " + why);
  if (points.rows() == 0) throw Error::processing("fit_implicit: no stroke points to fit");
  if (!all_finite(points))
    throw Error::processing("fit_implicit: non-finite point or normal coordinates");
}

// Eq. 6 / App. B once the normal points are reduced to their count, box [lo, hi] and, in the
// model's frame, normal_terms(frame, align) -> NormalTerms.
template <class NormalTermsFn>
ImplicitModel solve_fit(int degree, Eigen::Ref<const Eigen::MatrixX3d> points, Eigen::Index nn,
                        const Eigen::Vector3d& normal_lo, const Eigen::Vector3d& normal_hi,
                        NormalTermsFn&& normal_terms, const FitOptions& options) {
  const Eigen::Index np = points.rows();
  const int t = monomial_count(degree);
  const int u = t - 1;  // unknowns: the non-constant normalised columns

  ImplicitModel model;
  model.degree = degree;
  model.center = points.colwise().mean().transpose();
  if (options.length_unit > 0.0) {
    model.scale = options.length_unit;
  } else {
    Eigen::Vector3d lo = points.colwise().minCoeff().transpose();
    Eigen::Vector3d hi = points.colwise().maxCoeff().transpose();
    if (nn > 0) {
      lo = lo.cwiseMin(normal_lo);
      hi = hi.cwiseMax(normal_hi);
    }
    const double diagonal = (hi - lo).norm();
    model.scale = diagonal > 0.0 ? diagonal : 1.0;
  }

  // Monomial columns over the stroke points, their means and standard deviations (App. B).
  Eigen::MatrixXd columns(np, u);
  double radius2 = 0.0;
  for (Eigen::Index i = 0; i < np; ++i) {
    const Eigen::Vector3d y = (points.row(i).transpose() - model.center) / model.scale;
    radius2 += y.squaredNorm();
    const Powers powers(y, degree);
    for (int k = 1; k < t; ++k) columns(i, k - 1) = powers.monomial(k);
  }
  // The alignment rows n_v . grad X(y_v) (before the column scaling): kept per vertex for Eq. 6's
  // form, only their sum for App. B's (no #N x t matrix: regions have up to ~50k such vertices).
  const bool align = nn > 0 && options.mu > 0.0;
  const bool per_vertex = options.alignment == NormalAlignment::PerVertex;
  NormalTerms normal = normal_terms(static_cast<const ImplicitModel&>(model), align);
  radius2 += normal.squared;
  Eigen::VectorXd& align_sum = normal.align_sum;
  Eigen::MatrixXd& align_rows = normal.align_rows;
  double radius = std::sqrt(radius2 / static_cast<double>(np + nn));
  if (!(radius > 0.0)) radius = 1.0;

  const Eigen::RowVectorXd means = columns.colwise().mean();
  columns.rowwise() -= means;
  Eigen::RowVectorXd deviations =
      (columns.colwise().squaredNorm() / static_cast<double>(np)).cwiseSqrt();
  for (int k = 1; k < t; ++k)
    deviations[k - 1] =
        std::max(deviations[k - 1], kDeviationFloor * portable::pow(radius, monomial_degree(k)));
  columns.array().rowwise() /= deviations.array();

  // Normal equations of Eq. 6 in the normalised basis.
  Eigen::MatrixXd normal_matrix = Eigen::MatrixXd::Zero(u, u);
  normal_matrix.selfadjointView<Eigen::Lower>().rankUpdate(columns.transpose());
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(u);
  if (align) {
    // Both forms in the normalised basis: each column divided by its deviation.
    align_sum.array() /= deviations.transpose().array();
    rhs = options.mu * align_sum;
    if (per_vertex) {
      align_rows.array().rowwise() /= deviations.array();
      normal_matrix.selfadjointView<Eigen::Lower>().rankUpdate(align_rows.transpose(), options.mu);
    } else {
      // App. B, Eq. 11-12: one summed row M_align = sum_v n_v^T grad X(v) / S.
      normal_matrix.selfadjointView<Eigen::Lower>().rankUpdate(align_sum, options.mu);
    }
  }
  normal_matrix.diagonal().array() += options.lambda;
  normal_matrix.triangularView<Eigen::StrictlyUpper>() =
      normal_matrix.triangularView<Eigen::StrictlyLower>().transpose();

  Eigen::VectorXd theta;
  if (rhs.squaredNorm() > 0.0 && options.lambda > 0.0) {
    theta = normal_matrix.llt().solve(rhs);  // symmetric positive definite thanks to lambda
  } else if (rhs.squaredNorm() > 0.0) {
    // lambda = 0: the matrix may be singular; take the minimum-norm solution (the limit of
    // lambda -> 0+).
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(normal_matrix);
    const Eigen::VectorXd& ev = eig.eigenvalues();
    const double cutoff = 1e-12 * std::max(ev.cwiseAbs().maxCoeff(), 1e-300);
    Eigen::VectorXd projected = eig.eigenvectors().transpose() * rhs;
    for (int k = 0; k < u; ++k) projected[k] = ev[k] > cutoff ? projected[k] / ev[k] : 0.0;
    theta = eig.eigenvectors() * projected;
  } else {
    // No alignment data: the smallest eigenvector (classical algebraic fit with |theta| = 1).
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(normal_matrix);
    theta = eig.eigenvectors().col(0);
    // Deterministic sign: the largest-magnitude coefficient is positive.
    Eigen::Index largest = 0;
    theta.cwiseAbs().maxCoeff(&largest);
    if (theta[largest] < 0.0) theta = -theta;
  }

  // Fold the column normalisation back: f(y) = sum_k theta_k (m_k(y) - mean_k) / dev_k.
  model.coefficients.resize(t);
  model.coefficients[0] = 0.0;
  for (int k = 1; k < t; ++k) {
    model.coefficients[k] = theta[k - 1] / deviations[k - 1];
    model.coefficients[0] -= model.coefficients[k] * means[k - 1];
  }
  return model;
}

}  // namespace

ImplicitModel fit_implicit(int degree, Eigen::Ref<const Eigen::MatrixX3d> points,
                           Eigen::Ref<const Eigen::MatrixX3d> normal_points,
                           Eigen::Ref<const Eigen::MatrixX3d> normals, const FitOptions& options) {
  check_fit_input(degree, points, options);
  if (normal_points.rows() != normals.rows())
    throw Error::usage("fit_implicit: " + std::to_string(normal_points.rows()) +
                       " normal points but " + std::to_string(normals.rows()) + " normals");
  if (!all_finite(normal_points) || !all_finite(normals))
    throw Error::processing("fit_implicit: non-finite point or normal coordinates");
  const Eigen::Index nn = normal_points.rows();
  Eigen::Vector3d lo = Eigen::Vector3d::Zero(), hi = Eigen::Vector3d::Zero();
  if (nn > 0) {
    lo = normal_points.colwise().minCoeff().transpose();
    hi = normal_points.colwise().maxCoeff().transpose();
  }
  const bool per_vertex = options.alignment == NormalAlignment::PerVertex;
  return solve_fit(
      degree, points, nn, lo, hi,
      [&](const ImplicitModel& frame, bool align) {
        return terms_from_points(frame, normal_points, normals, align, per_vertex);
      },
      options);
}

ImplicitModel fit_implicit(int degree, Eigen::Ref<const Eigen::MatrixX3d> points,
                           const NormalMoments& normals, const FitOptions& options) {
  check_fit_input(degree, points, options);
  if (options.alignment != NormalAlignment::Summed)
    throw Error::usage("fit_implicit: normal moments give the summed alignment only");
  bool finite = std::isfinite(normals.squared) && normals.sum.allFinite();
  for (const auto& row : normals.directional)
    for (double x : row) finite = finite && std::isfinite(x);
  if (!finite) throw Error::processing("fit_implicit: non-finite normal moments");
  return solve_fit(
      degree, points, normals.count, normals.lo, normals.hi,
      [&](const ImplicitModel& frame, bool align) { return terms_from_moments(frame, normals, align); },
      options);
}

}  // namespace sketchsurf
