// VIPSS: interpolation, agreement with a brute-force dense reference, determinism, bad input.

#include "surfacing/proxy/vipss.h"

#include <ceres/first_order_function.h>
#include <ceres/gradient_problem.h>
#include <ceres/gradient_problem_solver.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "surfacing/error.h"

namespace sketchsurf {
namespace {

// n points on an ellipsoid-like closed surface, roughly unit diagonal, deterministic.
Eigen::MatrixX3d blob_points(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::MatrixX3d x(n, 3);
  for (int i = 0; i < n; ++i) {
    Eigen::Vector3d d(normal(rng), normal(rng), normal(rng));
    d.normalize();
    const double bump = 1.0 + 0.15 * std::sin(3 * d.x()) * std::cos(2 * d.y());
    x.row(i) = (bump * Eigen::Vector3d(0.3 * d.x(), 0.22 * d.y(), 0.15 * d.z())).transpose();
  }
  return x;
}

// ---- Brute-force reference: explicit saddle inverse, the METHOD.md formula for H, dense
// eigendecomposition, the same energy minimised by the same L-BFGS. ----

double phi(double r) { return r * r * r; }

Eigen::MatrixXd reference_h(const Eigen::MatrixX3d& x, double lambda) {
  const int n = static_cast<int>(x.rows()), m = 4 * n + 4;
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(m, m);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const Eigen::Vector3d d = (x.row(i) - x.row(j)).transpose();
      const double r = d.norm();
      a(i, j) = phi(r);
      for (int l = 0; l < 3; ++l) {
        a(i, n + 3 * j + l) = 3 * r * (-d[l]);  // d/dy_l |x_i - y|^3
        a(n + 3 * j + l, i) = a(i, n + 3 * j + l);
      }
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < 3; ++l)
          a(n + 3 * i + k, n + 3 * j + l) =
              r < 1e-8 ? 0.0 : -(3 * d[k] * d[l] / r + 3 * r * (k == l ? 1.0 : 0.0));
    }
  for (int i = 0; i < n; ++i) {
    a(i, 4 * n) = a(4 * n, i) = 1.0;
    for (int k = 0; k < 3; ++k) {
      a(i, 4 * n + 1 + k) = a(4 * n + 1 + k, i) = x(i, k);
      a(n + 3 * i + k, 4 * n + 1 + k) = a(4 * n + 1 + k, n + 3 * i + k) = 1.0;
    }
  }
  const Eigen::MatrixXd inv = a.fullPivLu().inverse();
  const Eigen::MatrixXd k00 = inv.topLeftCorner(n, n), k01 = inv.block(0, n, n, 3 * n);
  Eigen::MatrixXd h = inv.block(n, n, 3 * n, 3 * n);
  if (lambda > 0)
    h -= lambda * k01.transpose() *
         (Eigen::MatrixXd::Identity(n, n) + lambda * k00).fullPivLu().solve(k01);
  return 0.5 * (h + h.transpose());
}

class DenseEnergy : public ceres::FirstOrderFunction {
 public:
  explicit DenseEnergy(Eigen::MatrixXd h) : h_(std::move(h)) {}
  int NumParameters() const override { return static_cast<int>(2 * (h_.rows() / 3)); }
  bool Evaluate(const double* p, double* cost, double* grad) const override {
    const int n = static_cast<int>(h_.rows() / 3);
    Eigen::VectorXd g(3 * n);
    for (int i = 0; i < n; ++i)
      g.segment<3>(3 * i) << std::sin(p[2 * i]) * std::cos(p[2 * i + 1]),
          std::sin(p[2 * i]) * std::sin(p[2 * i + 1]), std::cos(p[2 * i]);
    const Eigen::VectorXd hg = h_ * g;
    *cost = g.dot(hg);
    if (grad)
      for (int i = 0; i < n; ++i) {
        const double t = p[2 * i], f = p[2 * i + 1];
        const Eigen::Vector3d dh = 2 * hg.segment<3>(3 * i);
        grad[2 * i] = dh.dot(Eigen::Vector3d(std::cos(t) * std::cos(f), std::cos(t) * std::sin(f),
                                             -std::sin(t)));
        grad[2 * i + 1] = dh.dot(Eigen::Vector3d(-std::sin(t) * std::sin(f),
                                                 std::sin(t) * std::cos(f), 0));
      }
    return true;
  }
  Eigen::MatrixXd h_;
};

struct ReferenceResult {
  double energy;
  Eigen::MatrixX3d normals;
};

ReferenceResult reference_vipss(const Eigen::MatrixX3d& x, double lambda) {
  const int n = static_cast<int>(x.rows());
  const Eigen::MatrixXd h = reference_h(x, lambda);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(h);
  const Eigen::VectorXd v = eig.eigenvectors().col(0);  // smallest eigenvalue first
  std::vector<double> p(2 * n);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d g = v.segment<3>(3 * i).normalized();
    p[2 * i] = std::acos(std::clamp(g.z(), -1.0, 1.0));
    p[2 * i + 1] = std::atan2(g.y(), g.x());
  }
  ceres::GradientProblem problem(new DenseEnergy(h));
  ceres::GradientProblemSolver::Options o;
  o.line_search_direction_type = ceres::LBFGS;
  o.max_num_iterations = 5000;
  o.function_tolerance = 1e-14;
  o.gradient_tolerance = 1e-12;
  o.parameter_tolerance = 1e-16;
  ceres::GradientProblemSolver::Summary s;
  ceres::Solve(o, problem, p.data(), &s);
  ReferenceResult out;
  out.energy = s.final_cost;
  out.normals.resize(n, 3);
  for (int i = 0; i < n; ++i)
    out.normals.row(i) << std::sin(p[2 * i]) * std::cos(p[2 * i + 1]),
        std::sin(p[2 * i]) * std::sin(p[2 * i + 1]), std::cos(p[2 * i]);
  return out;
}

VipssOptions tight() {
  VipssOptions o;
  o.function_tolerance = 1e-14;
  o.gradient_tolerance = 1e-12;
  o.max_iterations = 5000;
  return o;
}

void expect_agreement(double lambda) {
  const Eigen::MatrixX3d x = blob_points(100, 7);
  VipssOptions options = tight();
  options.lambda = lambda;
  const VipssResult fast = solve_vipss(x, options);
  const ReferenceResult ref = reference_vipss(x, lambda);
  const Eigen::MatrixXd h = reference_h(x, lambda);

  // The fast path's energy of its own normals is the reference energy of those normals.
  Eigen::VectorXd g(300);
  for (int i = 0; i < 100; ++i) g.segment<3>(3 * i) = fast.normals.row(i).transpose();
  EXPECT_NEAR(g.dot(h * g), fast.summary.final_energy, 1e-9 * ref.energy);
  // Same minimum energy.
  EXPECT_NEAR(fast.summary.final_energy, ref.energy, 1e-6 * ref.energy);
  // Same normals up to the global sign.
  const double sign = (fast.normals.array() * ref.normals.array()).sum() > 0 ? 1.0 : -1.0;
  const double worst = (fast.normals - sign * ref.normals).rowwise().norm().maxCoeff();
  EXPECT_LT(worst, 1e-3);
}

TEST(Vipss, AgreesWithBruteForceReference) { expect_agreement(0.0); }
TEST(Vipss, AgreesWithBruteForceReferenceWithSmoothing) { expect_agreement(1e-3); }

TEST(Vipss, InterpolatesPointsWithUnitNormals) {
  const Eigen::MatrixX3d x = blob_points(200, 3);
  const VipssResult r = solve_vipss(x, {});
  ASSERT_EQ(r.normals.rows(), 200);
  for (int i = 0; i < 200; ++i) {
    Eigen::Vector3d grad;
    const double f = r.function.value_gradient(x.row(i).transpose(), &grad);
    EXPECT_NEAR(f, 0.0, 1e-8);
    EXPECT_NEAR((grad - r.normals.row(i).transpose()).norm(), 0.0, 1e-6);
    EXPECT_NEAR(r.normals.row(i).norm(), 1.0, 1e-12);
  }
  EXPECT_LE(r.summary.final_energy, r.summary.initial_energy);
  // A closed blob: the normals point consistently (all outward or all inward).
  int outward = 0;
  for (int i = 0; i < 200; ++i) outward += r.normals.row(i).dot(x.row(i)) > 0;
  EXPECT_TRUE(outward == 200 || outward == 0) << outward;
}

// From a start, the fixed normals are kept as given (the interpolant's gradient there), the free
// ones optimised from theirs: no more energy than the start.
TEST(Vipss, AStartKeepsItsFixedNormals) {
  const Eigen::MatrixX3d x = blob_points(120, 5);
  VipssStart start;
  start.normals = x.rowwise().normalized();
  start.fixed.assign(120, 0);
  const Eigen::AngleAxisd tilt(0.5, Eigen::Vector3d::UnitZ());
  for (int i = 0; i < 120; i += 3) {
    start.normals.row(i) = (tilt * Eigen::Vector3d(start.normals.row(i).transpose())).transpose();
    start.fixed[static_cast<std::size_t>(i)] = 1;
  }
  const VipssResult r = solve_vipss(x, {}, {}, &start);
  double moved = 0.0;
  for (int i = 0; i < 120; ++i) {
    Eigen::Vector3d grad;
    EXPECT_NEAR(r.function.value_gradient(x.row(i).transpose(), &grad), 0.0, 1e-8);
    EXPECT_NEAR((grad - r.normals.row(i).transpose()).norm(), 0.0, 1e-6);
    if (start.fixed[static_cast<std::size_t>(i)])
      EXPECT_NEAR((r.normals.row(i) - start.normals.row(i)).norm(), 0.0, 1e-12) << i;
    else
      moved = std::max(moved, (r.normals.row(i) - start.normals.row(i)).norm());
  }
  EXPECT_GT(moved, 0.01) << "the free normals were optimised";
  EXPECT_LE(r.summary.final_energy, r.summary.initial_energy);
  start.fixed.pop_back();
  EXPECT_THROW(solve_vipss(x, {}, {}, &start), Error);
}

TEST(Vipss, GradientMatchesFiniteDifferences) {
  const VipssResult r = solve_vipss(blob_points(60, 11), {});
  const Eigen::Vector3d p(0.05, -0.1, 0.2);
  Eigen::Vector3d grad;
  r.function.value_gradient(p, &grad);
  for (int k = 0; k < 3; ++k) {
    Eigen::Vector3d e = Eigen::Vector3d::Zero();
    e[k] = 1e-6;
    const double fd = (r.function.value(p + e) - r.function.value(p - e)) / 2e-6;
    EXPECT_NEAR(grad[k], fd, 1e-6 * std::max(1.0, std::abs(fd)));
  }
}

// The vectorised sum against the formula term by term, with a centre count that is not a whole
// number of blocks (padding), at random points and exactly at a centre (where the gradient of
// the r b . e term is taken as 0 instead of 0/0).
TEST(HermiteRbf, MatchesTheFormulaTermByTerm) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-0.5, 0.5);
  const int n = 37;
  Eigen::MatrixX3d centers(n, 3), b(n, 3);
  Eigen::VectorXd a(n);
  for (int j = 0; j < n; ++j) {
    centers.row(j) << u(rng), u(rng), u(rng);
    b.row(j) << u(rng), u(rng), u(rng);
    a[j] = u(rng);
  }
  const Eigen::Vector4d c(0.1, -0.2, 0.3, 0.05);
  const HermiteRbf f(centers, a, b, c);
  EXPECT_EQ(f.size(), 37u);
  for (int q = 0; q <= 50; ++q) {
    const Eigen::Vector3d x =
        q < 50 ? Eigen::Vector3d(u(rng), u(rng), u(rng)) : Eigen::Vector3d(centers.row(7).transpose());
    double value = c[0] + c.tail<3>().dot(x);
    Eigen::Vector3d gradient = c.tail<3>();
    for (int j = 0; j < n; ++j) {
      const Eigen::Vector3d e = centers.row(j).transpose() - x;
      const double r = e.norm();
      const Eigen::Vector3d bj = b.row(j).transpose();
      value += a[j] * r * r * r + 3.0 * r * bj.dot(e);
      gradient += -3.0 * a[j] * r * e - 3.0 * r * bj;
      if (r > 1e-12) gradient += -3.0 * bj.dot(e) / r * e;
    }
    Eigen::Vector3d got;
    EXPECT_NEAR(f.value_gradient(x, &got), value, 1e-12) << q;
    EXPECT_NEAR((got - gradient).norm(), 0.0, 1e-12) << q;
    EXPECT_EQ(f.value(x), f.value_gradient(x, &got)) << q;
  }
}

TEST(Vipss, SameResultWhateverTheThreadCount) {
  const Eigen::MatrixX3d x = blob_points(300, 5);
  VipssOptions one;
  one.threads = 1;
  VipssOptions two = one;
  two.threads = 2;
  VipssOptions five = one;
  five.threads = 5;
  const VipssResult a = solve_vipss(x, one), b = solve_vipss(x, two), c = solve_vipss(x, five);
  EXPECT_EQ(a.summary.final_energy, b.summary.final_energy);
  EXPECT_EQ(a.summary.final_energy, c.summary.final_energy);
  EXPECT_EQ(a.normals, b.normals);
  EXPECT_EQ(a.normals, c.normals);
}

TEST(Vipss, CoplanarPointsAreAProcessingError) {
  Eigen::MatrixX3d x(30, 3);
  for (int i = 0; i < 30; ++i) x.row(i) << std::cos(i * 0.3), std::sin(i * 0.7), 0.0;
  try {
    solve_vipss(x, {});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Processing);
    EXPECT_NE(std::string(e.what()).find("coplanar"), std::string::npos);
  }
  EXPECT_THROW(solve_vipss(x.topRows(4), {}), Error);
  VipssOptions bad;
  bad.lambda = -1;
  EXPECT_THROW(solve_vipss(blob_points(20, 1), bad), Error);
}

}  // namespace
}  // namespace sketchsurf
