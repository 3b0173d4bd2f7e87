#include "surfacing/proxy/vipss.h"

#include <Eigen/Cholesky>
#include <Eigen/QR>
#include <Spectra/SymEigsSolver.h>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "surfacing/error.h"
#include "surfacing/lbfgs.h"
#include "surfacing/parallel.h"
#include "surfacing/portable_math.h"

namespace sketchsurf {

namespace {

using Mat = Eigen::MatrixXd;
using Vec = Eigen::VectorXd;
using Eigen::Index;

// Tile size of the dense kernels. Work is split into tiles of this fixed size, never by thread
// count, so every floating-point sum is done in the same order whatever the number of threads.
constexpr Index kTile = 128;

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

constexpr int kBoxGrid = 17;  // points per side of each box face checked for a closed zero set
constexpr int kLbfgsRank = 20;  // (s, y) pairs the L-BFGS of the normals keeps (Ceres' default)

Index tiles(Index size) { return (size + kTile - 1) / kTile; }

// The lower tiles (i >= j) of a t x t tiling, as (i, j) pairs.
std::vector<std::pair<Index, Index>> lower_tiles(Index t) {
  std::vector<std::pair<Index, Index>> out;
  out.reserve(t * (t + 1) / 2);
  for (Index i = 0; i < t; ++i)
    for (Index j = 0; j <= i; ++j) out.emplace_back(i, j);
  return out;
}

// In-place lower Cholesky factorisation A = L L^T, right-looking and blocked, with the panel solve
// and the trailing update run tile by tile in parallel. Reads and writes the lower triangle only.
// Returns false when A is not (numerically) positive definite.
bool blocked_cholesky(Mat& A, unsigned threads, const Progress& progress, std::string_view stage) {
  const Index m = A.rows();
  for (Index k = 0; k < m; k += kTile) {
    progress.update(stage, static_cast<double>(k) / m);
    const Index kb = std::min(kTile, m - k);
    Eigen::Ref<Mat> akk = A.block(k, k, kb, kb);
    Eigen::LLT<Eigen::Ref<Mat>> llt(akk);
    if (llt.info() != Eigen::Success) return false;
    const Index start = k + kb, rest = m - start;
    if (rest == 0) break;
    const Index t = tiles(rest);
    parallel_for(0, t, threads, [&](std::size_t i) {
      const Index r0 = start + static_cast<Index>(i) * kTile, rb = std::min(kTile, m - r0);
      auto panel = A.block(r0, k, rb, kb);
      akk.triangularView<Eigen::Lower>().transpose().solveInPlace<Eigen::OnTheRight>(panel);
    });
    const auto pairs = lower_tiles(t);
    parallel_for(0, pairs.size(), threads, [&](std::size_t p) {
      const Index r0 = start + pairs[p].first * kTile, c0 = start + pairs[p].second * kTile;
      const Index rb = std::min(kTile, m - r0), cb = std::min(kTile, m - c0);
      A.block(r0, c0, rb, cb).noalias() -= A.block(r0, k, rb, kb) * A.block(c0, k, cb, kb).transpose();
    });
  }
  progress.update(stage, 1.0);
  return true;
}

// X <- L^-1 X for lower-triangular L, column tiles in parallel.
void lower_solve_columns(const Mat& L, Mat& X, unsigned threads) {
  parallel_for(0, tiles(X.cols()), threads, [&](std::size_t i) {
    const Index c0 = static_cast<Index>(i) * kTile, cb = std::min(kTile, X.cols() - c0);
    auto block = X.middleCols(c0, cb);
    L.triangularView<Eigen::Lower>().solveInPlace(block);
  });
}

// x <- (L L^T)^-1 x with the factor in the lower triangle of L.
void cholesky_solve(const Mat& L, Vec& x) {
  L.triangularView<Eigen::Lower>().solveInPlace(x);
  L.triangularView<Eigen::Lower>().transpose().solveInPlace(x);
}

// y = S x for a symmetric S stored in full, column tiles in parallel (Spectra's operator concept).
class ParallelSymProduct {
 public:
  using Scalar = double;
  ParallelSymProduct(const Mat& s, unsigned threads) : s_(s), threads_(threads) {}
  Index rows() const { return s_.rows(); }
  Index cols() const { return s_.cols(); }
  void perform_op(const double* x_in, double* y_out) const {
    Eigen::Map<const Vec> x(x_in, s_.rows());
    Eigen::Map<Vec> y(y_out, s_.rows());
    parallel_for(0, tiles(s_.cols()), threads_, [&](std::size_t i) {
      const Index c0 = static_cast<Index>(i) * kTile, cb = std::min(kTile, s_.cols() - c0);
      y.segment(c0, cb).noalias() = s_.middleCols(c0, cb).transpose() * x;
    });
  }

 private:
  const Mat& s_;
  unsigned threads_;
};

// Unit normals from spherical angles (theta_i, phi_i) stacked in `angles` (2n).
void normals_from_angles(const double* angles, Index n, Vec& g) {
  for (Index i = 0; i < n; ++i) {
    const double st = portable::sin(angles[2 * i]), ct = portable::cos(angles[2 * i]);
    const double sp = portable::sin(angles[2 * i + 1]), cp = portable::cos(angles[2 * i + 1]);
    g.segment<3>(3 * i) << st * cp, st * sp, ct;
  }
}

// E(angles) = g^T H g with H = S^-1 applied through the Cholesky factor of S.
class NormalEnergy : public detail::LbfgsFunction {
 public:
  /// `fixed` (if given, one flag a point): those points' angles keep their start (zero gradient).
  explicit NormalEnergy(const Mat& factor, const std::vector<char>* fixed = nullptr)
      : factor_(factor), fixed_(fixed) {}
  Index size() const override { return 2 * (factor_.rows() / 3); }
  bool evaluate(const double* angles, double* cost, double* gradient) const override {
    const Index n = factor_.rows() / 3;
    Vec g(3 * n);
    normals_from_angles(angles, n, g);
    Vec h = g;
    cholesky_solve(factor_, h);
    *cost = g.dot(h);
    for (Index i = 0; i < n; ++i) {
      const double st = portable::sin(angles[2 * i]), ct = portable::cos(angles[2 * i]);
      const double sp = portable::sin(angles[2 * i + 1]), cp = portable::cos(angles[2 * i + 1]);
      const Eigen::Vector3d dh = 2.0 * h.segment<3>(3 * i);
      gradient[2 * i] = dh.dot(Eigen::Vector3d(ct * cp, ct * sp, -st));
      gradient[2 * i + 1] = dh.dot(Eigen::Vector3d(-st * sp, st * cp, 0.0));
      if (fixed_ && (*fixed_)[static_cast<std::size_t>(i)]) gradient[2 * i] = gradient[2 * i + 1] = 0.0;
    }
    return std::isfinite(*cost);
  }
  bool evaluate_step(const double* angles, double step, const double* d, double* trial, double* cost,
                     double* gradient) const override {
    for (Index k = 0; k < size(); ++k) trial[k] = angles[k] + step * d[k];
    return evaluate(trial, cost, gradient);
  }

 private:
  const Mat& factor_;
  const std::vector<char>* fixed_;
};

// Kernel matrix blocks of the r^3 Hermite RBF (METHOD.md section 1):
//   Pv(i, j)        = r^3 (+ lambda on the diagonal)             value-value
//   Gvg(i, 3j + l)  = d/dy_l |x_i - y|^3 at x_j = 3 r (x_j - x_i)_l  value-gradient
//   Ggg(3i+k, 3j+l) = -Hessian = -3 (d_k d_l / r + r delta_kl), d = x_i - x_j (0 for i = j)
void assemble(const Eigen::MatrixX3d& x, double lambda, Mat& pv, Mat& gvg, Mat& ggg,
              unsigned threads) {
  const Index n = x.rows();
  pv.resize(n, n);
  gvg.resize(n, 3 * n);
  ggg.resize(3 * n, 3 * n);
  parallel_for(0, n, threads, [&](std::size_t jj) {
    const Index j = static_cast<Index>(jj);
    for (Index i = 0; i < n; ++i) {
      const Eigen::Vector3d d = (x.row(i) - x.row(j)).transpose();
      const double r = d.norm();
      pv(i, j) = r * r * r + (i == j ? lambda : 0.0);
      gvg.block<1, 3>(i, 3 * j) = -3.0 * r * d.transpose();
      Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
      if (r > 1e-12) h = -3.0 * (d * d.transpose() / r + r * Eigen::Matrix3d::Identity());
      ggg.block<3, 3>(3 * i, 3 * j) = h;
    }
  });
}

}  // namespace

bool VipssOptions::valid(std::string* why) const {
  auto fail = [&](const char* msg) {
    if (why) *why = msg;
    return false;
  };
  if (!(lambda >= 0.0) || !std::isfinite(lambda)) return fail("vipss lambda must be >= 0");
  if (max_iterations < 0) return fail("vipss max_iterations must be >= 0");
  if (!(box_padding > 0.0) || !std::isfinite(box_padding)) return fail("vipss box_padding must be > 0");
  if (!(function_tolerance > 0.0)) return fail("vipss function_tolerance must be > 0");
  if (!(gradient_tolerance > 0.0)) return fail("vipss gradient_tolerance must be > 0");
  return true;
}

namespace {

// Centres are processed in fixed-size blocks of lanes (no heap traffic, vectorised); the arrays
// are padded to a whole number of blocks with zero-coefficient centres, which contribute exactly 0.
constexpr Eigen::Index kRbfBlock = 16;

Eigen::ArrayXd padded(const Eigen::ArrayXd& v, double fill) {
  const Eigen::Index n = (v.size() + kRbfBlock - 1) / kRbfBlock * kRbfBlock;
  Eigen::ArrayXd out = Eigen::ArrayXd::Constant(n, fill);
  out.head(v.size()) = v;
  return out;
}

// rbf_kernel() is compiled for AVX too where the compiler can choose at run time (GCC, Clang on
// x86-64): four lanes per instruction instead of two, same results (see rbf_sum()). rbf_sum() and
// lane_sum() are inlined into each version.
#if defined(__x86_64__) && !defined(__AVX__) && defined(__has_attribute)
#if __has_attribute(target_clones) && __has_attribute(always_inline)
#define SKETCHSURF_RBF_TARGETS __attribute__((target_clones("avx", "default")))
#define SKETCHSURF_RBF_INLINE __attribute__((always_inline))
#endif
#endif
#ifndef SKETCHSURF_RBF_TARGETS
#define SKETCHSURF_RBF_TARGETS
#define SKETCHSURF_RBF_INLINE
#endif

// The sum of a block's lanes in a fixed pairwise order.
SKETCHSURF_RBF_INLINE inline double lane_sum(const double* v) {
  static_assert(kRbfBlock == 16);
  double half[2];
  for (int k = 0; k < 2; ++k)
    half[k] = ((v[k] + v[2 + k]) + (v[4 + k] + v[6 + k])) +
              ((v[8 + k] + v[10 + k]) + (v[12 + k] + v[14 + k]));
  return half[0] + half[1];
}

struct RbfArrays {
  const double *cx, *cy, *cz, *a, *bx, *by, *bz;
  Eigen::Index size;  // a multiple of kRbfBlock
};

// sum_j a r^3 + 3 r b . e with e = x_j - x (and its gradient), written as loops over the lanes of
// a block that the compiler vectorises for any vector width. Each lane sees the same IEEE
// operations in the same order whatever the width (sqrt, division and separate multiplies and
// adds: neither the baseline nor the AVX target has fused multiply-add), and the lanes are summed
// by lane_sum(), so every instruction set gives the same bits.
template <bool kGradient>
SKETCHSURF_RBF_INLINE inline double rbf_sum(const RbfArrays& c, const double* x, double* gradient) {
  constexpr int L = kRbfBlock;
  alignas(64) double f[L] = {}, gx[L] = {}, gy[L] = {}, gz[L] = {};
  for (Eigen::Index j = 0; j < c.size; j += L) {
    alignas(64) double dx[L], dy[L], dz[L], r[L], be[L], q[L];
    for (int l = 0; l < L; ++l) {
      dx[l] = c.cx[j + l] - x[0];
      dy[l] = c.cy[j + l] - x[1];
      dz[l] = c.cz[j + l] - x[2];
      r[l] = std::sqrt(dx[l] * dx[l] + dy[l] * dy[l] + dz[l] * dz[l]);
      be[l] = c.bx[j + l] * dx[l] + c.by[j + l] * dy[l] + c.bz[j + l] * dz[l];
      f[l] += r[l] * (c.a[j + l] * (r[l] * r[l]) + 3.0 * be[l]);
    }
    if constexpr (kGradient) {
      // grad (a r^3) = -3 a r e; grad (3 r b . e) = -3 (b . e) e / r - 3 r b (0 at a centre).
      bool centre = false;
      for (int l = 0; l < L; ++l) {
        q[l] = be[l] / r[l];
        centre |= !(r[l] > 1e-12);
      }
      if (centre)
        for (int l = 0; l < L; ++l)
          if (!(r[l] > 1e-12)) q[l] = 0.0;
      for (int l = 0; l < L; ++l) {
        const double s = -3.0 * (c.a[j + l] * r[l] + q[l]);
        gx[l] += s * dx[l] - 3.0 * r[l] * c.bx[j + l];
        gy[l] += s * dy[l] - 3.0 * r[l] * c.by[j + l];
        gz[l] += s * dz[l] - 3.0 * r[l] * c.bz[j + l];
      }
    }
  }
  if constexpr (kGradient) {
    gradient[0] = lane_sum(gx);
    gradient[1] = lane_sum(gy);
    gradient[2] = lane_sum(gz);
  }
  return lane_sum(f);
}

SKETCHSURF_RBF_TARGETS double rbf_kernel(const RbfArrays& c, const double* x, double* gradient) {
  return gradient ? rbf_sum<true>(c, x, gradient) : rbf_sum<false>(c, x, nullptr);
}

}  // namespace

HermiteRbf::HermiteRbf(const Eigen::MatrixX3d& centers, const Eigen::VectorXd& a,
                       const Eigen::MatrixX3d& b, const Eigen::Vector4d& c)
    : size_(static_cast<std::size_t>(centers.rows())),
      cx_(padded(centers.col(0), centers.rows() ? centers(0, 0) : 0.0)),
      cy_(padded(centers.col(1), centers.rows() ? centers(0, 1) : 0.0)),
      cz_(padded(centers.col(2), centers.rows() ? centers(0, 2) : 0.0)), a_(padded(a, 0.0)),
      bx_(padded(b.col(0), 0.0)), by_(padded(b.col(1), 0.0)), bz_(padded(b.col(2), 0.0)), c_(c) {}

double HermiteRbf::value(const Eigen::Vector3d& x) const { return value_gradient(x, nullptr); }

double HermiteRbf::value_gradient(const Eigen::Vector3d& x, Eigen::Vector3d* gradient) const {
  // f = sum a r^3 + 3 r b . e + c0 + c . x (rbf_sum()).
  const RbfArrays arrays{cx_.data(), cy_.data(), cz_.data(), a_.data(),
                         bx_.data(), by_.data(), bz_.data(), cx_.size()};
  Eigen::Vector3d g;
  const double sum = rbf_kernel(arrays, x.data(), gradient ? g.data() : nullptr);
  if (gradient) *gradient = g + c_.tail<3>();
  return sum + c_[0] + c_.tail<3>().dot(x);
}

void HermiteRbf::values(const Eigen::MatrixX3d& points, Eigen::VectorXd& out,
                        unsigned threads) const {
  out.resize(points.rows());
  constexpr std::size_t kChunk = 64;
  const std::size_t rows = static_cast<std::size_t>(points.rows());
  parallel_for(0, (rows + kChunk - 1) / kChunk, threads, [&](std::size_t c) {
    for (std::size_t i = c * kChunk; i < std::min(rows, (c + 1) * kChunk); ++i)
      out[i] = value(points.row(i).transpose());
  });
}

VipssResult solve_vipss(const Eigen::MatrixX3d& x, const VipssOptions& options,
                        const Progress& progress, const VipssStart* from) {
  std::string why;
  if (!options.valid(&why)) throw Error::usage(why);
  const Index n = x.rows();
  if (n < 5) throw Error::processing("VIPSS needs at least 5 points, got " + std::to_string(n));
  if (!x.allFinite()) throw Error::processing("VIPSS points contain NaN or Inf");
  if (from && (from->normals.rows() != n || from->fixed.size() != static_cast<std::size_t>(n)))
    throw Error::usage("VIPSS start: one normal and one flag a point");
  const unsigned threads = options.threads;
  VipssResult result;
  result.summary.points = static_cast<std::size_t>(n);
  auto t0 = std::chrono::steady_clock::now();

  // Polynomial block: N_v = [1 x] (n x 4); its QR gives Y (range) and Z (null space of N_v^T).
  progress.update("vipss: assembling", 0.0);
  Mat nv(n, 4);
  nv.col(0).setOnes();
  nv.rightCols<3>() = x;
  const Eigen::HouseholderQR<Mat> qr(nv);
  const Eigen::Matrix4d r = qr.matrixQR().topRows<4>().triangularView<Eigen::Upper>();
  const double scale = std::max(1.0, x.cwiseAbs().maxCoeff()) * std::sqrt(static_cast<double>(n));
  if (r.diagonal().cwiseAbs().minCoeff() < 1e-9 * scale)
    throw Error::processing("VIPSS points are (nearly) coplanar: they do not enclose a volume");
  const Mat y = qr.householderQ() * Mat::Identity(n, 4);

  Mat pv, gvg, s;
  assemble(x, options.lambda, pv, gvg, s, threads);
  progress.update("vipss: assembling", 1.0);
  result.summary.assemble_seconds = seconds_since(t0);

  // T = Z^T P_v Z, factorised (positive definite: r^3 is conditionally positive definite of
  // order 2 and the points are not coplanar).
  t0 = std::chrono::steady_clock::now();
  Mat t = pv;
  t.applyOnTheLeft(qr.householderQ().transpose());
  t.applyOnTheRight(qr.householderQ());
  Mat tl = t.bottomRightCorner(n - 4, n - 4);
  t.resize(0, 0);
  if (!blocked_cholesky(tl, threads, progress, "vipss: factorising"))
    throw Error::processing("VIPSS value system is not positive definite (duplicate points?)");

  // Schur complement S = H^-1 = G_gg - B^T A_r^-1 B with A_r = [[P_v, N_v], [N_v^T, 0]],
  // B = [G_vg; N_g^T]. With C = R^-T N_g^T, U = Y^T G_vg, E = G_vg - P_v Y C,
  // F = L^-1 Z^T E:  S = G_gg - F^T F - U^T C - C^T U + C^T (Y^T P_v Y) C.
  const Mat pvy = pv * y;
  Mat ngt = Mat::Zero(4, 3 * n);  // N_g^T: row 0 (constant) is zero, rows 1..3 pick x, y, z
  for (Index i = 0; i < n; ++i) ngt.block<3, 3>(1, 3 * i).setIdentity();
  const Mat c = r.transpose().triangularView<Eigen::Lower>().solve(ngt);
  const Mat u = y.transpose() * gvg;
  gvg.noalias() -= pvy * c;  // gvg now holds E
  gvg.applyOnTheLeft(qr.householderQ().transpose());
  Mat f = gvg.bottomRows(n - 4);
  gvg.resize(0, 0);
  lower_solve_columns(tl, f, threads);
  // Low-rank part as X^T M X with X = [U; C] (8 x 3n), M = [[0, -I], [-I, Y^T P_v Y]].
  Mat xl(8, 3 * n);
  xl << u, c;
  Eigen::Matrix<double, 8, 8> m = Eigen::Matrix<double, 8, 8>::Zero();
  m.topRightCorner<4, 4>() = -Eigen::Matrix4d::Identity();
  m.bottomLeftCorner<4, 4>() = -Eigen::Matrix4d::Identity();
  m.bottomRightCorner<4, 4>() = y.transpose() * pvy;
  const Mat mx = m * xl;
  const auto pairs = lower_tiles(tiles(3 * n));
  parallel_for(0, pairs.size(), threads, [&](std::size_t p) {
    const Index r0 = pairs[p].first * kTile, c0 = pairs[p].second * kTile;
    const Index rb = std::min(kTile, 3 * n - r0), cb = std::min(kTile, 3 * n - c0);
    auto tile = s.block(r0, c0, rb, cb);
    tile.noalias() -= f.middleCols(r0, rb).transpose() * f.middleCols(c0, cb);
    tile.noalias() += xl.middleCols(r0, rb).transpose() * mx.middleCols(c0, cb);
  });
  f.resize(0, 0);
  s.triangularView<Eigen::StrictlyUpper>() = s.transpose();
  result.summary.factor_seconds = seconds_since(t0);

  // Initial normals (unless a start gives them): the eigenvector of H with the smallest eigenvalue,
  // i.e. of S = H^-1 with the largest, by Lanczos (Spectra).
  t0 = std::chrono::steady_clock::now();
  progress.update("vipss: initial normals", 0.0);
  Vec v0;
  if (!from) {
    ParallelSymProduct op(s, threads);
    const Index ncv = std::min<Index>(3 * n, 24);
    Spectra::SymEigsSolver<ParallelSymProduct> eigs(op, 1, ncv);
    eigs.init();
    eigs.compute(Spectra::SortRule::LargestAlge, 3000, 1e-10);
    result.summary.eigen_matvecs = static_cast<int>(eigs.num_operations());
    if (eigs.info() != Spectra::CompInfo::Successful)
      throw Error::processing("VIPSS: the Lanczos iteration for the initial normals did not converge");
    v0 = eigs.eigenvectors().col(0);
  }
  progress.update("vipss: initial normals", 1.0);
  result.summary.eigen_seconds = seconds_since(t0);

  t0 = std::chrono::steady_clock::now();
  if (!blocked_cholesky(s, threads, progress, "vipss: factorising H"))
    throw Error::processing("VIPSS energy matrix is not positive definite");
  result.summary.factor_seconds += seconds_since(t0);

  // L-BFGS over spherical angles from the normalised eigenvector (VIPSS). The energy is not
  // convex: from there a whole face of a sharp sketch can keep flipped normals and the zero set
  // folds through it out to the box (the bundled cube: genus 2-3). When the optimum's zero set
  // does not close inside the padded box, a second start (ours) is tried: the outward normals of
  // the points' inertia ellipsoid. The kept optimum closes in the box if either does, else it has
  // the lower energy (ties keep the first), so it is VIPSS's own local minimum either way.
  t0 = std::chrono::steady_clock::now();
  // Points on the faces of the box around the points, padded as the polygonisation's box.
  Eigen::MatrixX3d box_grid(6 * kBoxGrid * kBoxGrid, 3);
  {
    const Eigen::Vector3d lo = x.colwise().minCoeff().transpose().array() - options.box_padding;
    const Eigen::Vector3d hi = x.colwise().maxCoeff().transpose().array() + options.box_padding;
    Index row = 0;
    for (int axis = 0; axis < 3; ++axis)
      for (const double side : {lo[axis], hi[axis]})
        for (int i1 = 0; i1 < kBoxGrid; ++i1)
          for (int i2 = 0; i2 < kBoxGrid; ++i2) {
            const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
            Eigen::Vector3d p;
            p[axis] = side;
            p[a1] = lo[a1] + (hi[a1] - lo[a1]) * i1 / (kBoxGrid - 1);
            p[a2] = lo[a2] + (hi[a2] - lo[a2]) * i2 / (kBoxGrid - 1);
            box_grid.row(row++) = p.transpose();
          }
  }
  struct Candidate {
    HermiteRbf function;
    Eigen::MatrixX3d normals;
    double energy = 0.0;
    bool closed = false;  // one sign of f all over the box's faces
    std::string termination;
  };
  auto optimum = [&](std::vector<double> angles, std::size_t start) {
    const NormalEnergy energy(s, from ? &from->fixed : nullptr);
    detail::LbfgsOptions lbfgs_options;
    lbfgs_options.rank = kLbfgsRank;
    lbfgs_options.max_iterations = options.max_iterations;
    lbfgs_options.function_tolerance = options.function_tolerance;
    lbfgs_options.gradient_tolerance = options.gradient_tolerance;
    lbfgs_options.stall_window = 0;
    lbfgs_options.scale_initial_hessian = true;
    const char* stage = start == 0 ? "vipss: optimising normals" : "vipss: optimising normals (second start)";
    const double iterations = std::max(1, options.max_iterations);
    const WorkerTeam team(1);  // 2n variables: one vector chunk
    const detail::LbfgsOutcome outcome =
        detail::minimize_lbfgs(energy, angles.data(), lbfgs_options, team, [&](int iteration) {
          progress.update(stage, std::min(1.0, iteration / iterations));
        });
    if (!outcome.usable) throw Error::processing("VIPSS: " + outcome.termination);
    result.summary.lbfgs_iterations += outcome.iterations;
    Candidate made;
    made.termination = outcome.termination;
    // Coefficients: b = H g; [a; c] = -A_r^-1 [G_vg b; N_g^T b] through the null-space factors.
    Vec g(3 * n);
    normals_from_angles(angles.data(), n, g);
    Vec b = g;
    cholesky_solve(s, b);
    made.energy = g.dot(b);
    Vec r1(n);
    parallel_for(0, n, threads, [&](std::size_t ii) {
      const Index i = static_cast<Index>(ii);
      double sum = 0.0;
      for (Index j = 0; j < n; ++j) {
        const Eigen::Vector3d e = (x.row(j) - x.row(i)).transpose();
        sum += 3.0 * e.norm() * e.dot(b.segment<3>(3 * j));
      }
      r1[i] = -sum;
    });
    const Eigen::Vector4d r2 = -(ngt * b);
    const Eigen::Vector4d cr = r.transpose().triangularView<Eigen::Lower>().solve(r2);
    Vec rhs = r1 - pvy * cr;
    rhs.applyOnTheLeft(qr.householderQ().transpose());
    Vec w = rhs.tail(n - 4);
    cholesky_solve(tl, w);
    Vec zw = Vec::Zero(n);
    zw.tail(n - 4) = w;
    zw.applyOnTheLeft(qr.householderQ());
    const Vec a = y * cr + zw;
    const Eigen::Vector4d poly =
        r.triangularView<Eigen::Upper>().solve(y.transpose() * (r1 - pv * a));
    made.normals.resize(n, 3);
    Eigen::MatrixX3d bm(n, 3);
    for (Index i = 0; i < n; ++i) {
      made.normals.row(i) = g.segment<3>(3 * i).transpose();
      bm.row(i) = b.segment<3>(3 * i).transpose();
    }
    made.function = HermiteRbf(x, a, bm, poly);
    Eigen::VectorXd values;
    made.function.values(box_grid, values, threads);
    made.closed = (values.array() > 0.0).all() || (values.array() < 0.0).all();
    return made;
  };
  auto to_angles = [n](const auto& direction) {
    std::vector<double> angles(2 * n);
    for (Index i = 0; i < n; ++i) {
      Eigen::Vector3d g = direction(i);
      g = g.norm() > 0 ? g.normalized() : Eigen::Vector3d::UnitZ();
      angles[2 * i] = portable::acos(std::clamp(g.z(), -1.0, 1.0));
      angles[2 * i + 1] = portable::atan2(g.y(), g.x());
    }
    return angles;
  };
  const std::vector<double> first_start = to_angles([&](Index i) -> Eigen::Vector3d {
    return from ? Eigen::Vector3d(from->normals.row(i).transpose()) : Eigen::Vector3d(v0.segment<3>(3 * i));
  });
  {
    std::vector<double> gradient(first_start.size());
    NormalEnergy(s).evaluate(first_start.data(), &result.summary.initial_energy, gradient.data());
  }
  Candidate best = optimum(first_start, 0);
  if (!best.closed && !from) {
    const Eigen::Vector3d centroid = x.colwise().mean().transpose();
    const Eigen::MatrixX3d centred = x.rowwise() - centroid.transpose();
    const Eigen::Matrix3d shape =
        (centred.transpose() * centred).ldlt().solve(Eigen::Matrix3d::Identity());
    Candidate other = optimum(
        to_angles([&](Index i) -> Eigen::Vector3d { return shape * centred.row(i).transpose(); }), 1);
    if ((other.closed && !best.closed) || (other.closed == best.closed && other.energy < best.energy)) {
      best = std::move(other);
      result.summary.start = 1;
    }
  }
  result.summary.optimise_seconds = seconds_since(t0);
  result.summary.termination = best.termination;
  result.summary.final_energy = best.energy;
  result.summary.closed = best.closed;
  result.normals = std::move(best.normals);
  result.function = std::move(best.function);
  return result;
}

}  // namespace sketchsurf
