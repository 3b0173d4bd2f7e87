#pragma once
// VIPSS (Huang, Carr, Ju 2019): a Hermite RBF implicit surface through unoriented points whose
// normals are chosen to minimise the surface's curvature energy. METHOD.md section 1.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "surfacing/progress.h"

namespace sketchsurf {

/// Options for solve_vipss().
struct VipssOptions {
  double lambda = 0.0;  ///< smoothing weight (VIPSS Eq. 9); 0 = exact interpolation. Absolute, in
                        ///< the units of the points (make_proxy passes points of unit diagonal)
  double box_padding = 0.1;  ///< margin around the points of the box whose faces must see one
                             ///< sign of f (a zero set closed within it), absolute like lambda
  int max_iterations = 2000;           ///< L-BFGS iteration cap
  double function_tolerance = 1e-10;   ///< L-BFGS stops when the relative energy change is below
  double gradient_tolerance = 1e-10;   ///< L-BFGS stops when the gradient max-norm is below
  unsigned threads = 0;                ///< worker threads (0 = all); never changes the result

  /// True when the options can be used; otherwise `why` (if given) says which field is wrong.
  bool valid(std::string* why = nullptr) const;
};

/// The implicit function f(x) = sum_j a_j |x - x_j|^3 + b_j . grad_y |x - y|^3 (y = x_j)
/// + c_0 + c . x, a Hermite RBF with the r^3 kernel and a linear polynomial.
class HermiteRbf {
 public:
  HermiteRbf() = default;
  /// centers #n x 3; a #n; b #n x 3 (gradient coefficients); c (constant, then x, y, z).
  HermiteRbf(const Eigen::MatrixX3d& centers, const Eigen::VectorXd& a, const Eigen::MatrixX3d& b,
             const Eigen::Vector4d& c);

  std::size_t size() const { return size_; }
  double value(const Eigen::Vector3d& x) const;
  /// f(x) and its gradient.
  double value_gradient(const Eigen::Vector3d& x, Eigen::Vector3d* gradient) const;
  /// f at every row of `points` (#P x 3) into `values` (#P), on `threads` threads (0 = all).
  void values(const Eigen::MatrixX3d& points, Eigen::VectorXd& values, unsigned threads) const;

 private:
  // Structure of arrays so that the O(n) sum per point vectorises (padded, see vipss.cpp).
  std::size_t size_ = 0;
  Eigen::ArrayXd cx_, cy_, cz_, a_, bx_, by_, bz_;
  Eigen::Vector4d c_ = Eigen::Vector4d::Zero();
};

/// What the VIPSS solve did (Ceres-style summary), with per-step wall-clock seconds.
struct VipssSummary {
  std::size_t points = 0;        ///< n
  double initial_energy = 0.0;   ///< g^T H g at the normalised smallest eigenvector of H (or at
                                 ///< the given start's normals)
  double final_energy = 0.0;     ///< g^T H g at the optimised unit normals
  int eigen_matvecs = 0;         ///< Lanczos products with H^-1 for the initial normals
  int lbfgs_iterations = 0;      ///< L-BFGS iterations, both starts
  int start = 0;                 ///< start of the kept normals: 0 the eigenvector, 1 the ellipsoid
  bool closed = false;           ///< the kept f has one sign all over the padded box's faces
  std::string termination;       ///< why L-BFGS stopped
  double assemble_seconds = 0, factor_seconds = 0, eigen_seconds = 0, optimise_seconds = 0;
};

/// The result of solve_vipss().
struct VipssResult {
  HermiteRbf function;      ///< zero set through the points, gradient along `normals` at them
  Eigen::MatrixX3d normals; ///< #n x 3 unit normals (global sign arbitrary)
  VipssSummary summary;
};

/// Normals to start VIPSS's optimisation from, some of them kept as they are.
struct VipssStart {
  Eigen::MatrixX3d normals;  ///< #n x 3 unit normals
  std::vector<char> fixed;   ///< #n flags: these normals are not optimised
};

/// VIPSS on unoriented points (#n x 3, n >= 5, not all on one plane).
///
/// Unknowns: a value and a gradient per point. With the saddle matrix A = [[M, N], [N^T, 0]] (M the
/// Hermite kernel matrix, N the linear polynomial), K = top-left 4n x 4n block of A^-1 and
/// H = K_gg (lambda = 0) or K_gg - lambda K_vg^T (I + lambda K_vv)^-1 K_vg, the normals minimise
/// g^T H g over unit g. We never form K or H: H^-1 is the Schur complement of the value and
/// polynomial block (with lambda added to the value-value diagonal), which is formed with a
/// null-space Cholesky factorisation of the small block and then factorised itself (blocked,
/// parallel, deterministic). The smallest eigenvector of H (largest of H^-1, by Lanczos) gives the
/// initial normals; L-BFGS over spherical angles from them and from the outward normals of the
/// points' inertia ellipsoid gives two local optima; the one whose zero set closes inside the
/// padded box is kept, else the lower energy; and the gradient coefficients are
/// b = H g, the value ones a back-substitution. With `start`, the optimisation runs once, from its
/// normals, with its fixed ones kept (no eigenvector, no second start).
/// @throws Error (Usage) for invalid options or a start without one normal and one flag a point;
///         Error (Processing) when the points are too few, (nearly) coplanar, or the system is not
///         positive definite; Error (Cancelled).
VipssResult solve_vipss(const Eigen::MatrixX3d& points, const VipssOptions& options,
                        const Progress& progress = {}, const VipssStart* start = nullptr);

}  // namespace sketchsurf
