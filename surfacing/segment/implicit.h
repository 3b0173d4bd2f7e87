#pragma once
// Implicit polynomial surface models of degree 1-4 and their regularised fit (paper §4.2, Eq. 5-6,
// App. B).
//
// API notes (for the PEARL loop and the final-mesh optimisation):
// - A model is f(x) = sum_k c_k m_k((x - center) / scale) with the graded monomials m_k listed in
//   `implicit_monomials()` (1, x, y, z, x^2, xy, xz, y^2, yz, z^2, x^3, ...): the list for degree d
//   is a prefix of the list for d + 1. x is in world (input) units; the zero set Z(f) is the surface.
// - `value`, `gradient` (world units: d f / d x) and `distance` (Taubin, world units) take world
//   points. `distance` is +infinity where f != 0 and the gradient vanishes; clamp before using it as
//   a graph-cut cost. `evaluate<T>` / `evaluate_gradient<T>` are the same for T = double or
//   ceres::Jet (this header does not include Ceres).
// - `fit_implicit` solves Eq. 6 on normalised monomial columns (App. B) and folds the normalisation
//   back into center/scale/coefficients; the fitted f grows along the given proxy normals (on
//   average; the scale of f is arbitrary, the Taubin distance does not depend on it). It throws sketchsurf::Error (Usage) for a degree
//   outside 1..4, invalid options or mismatched shapes, and (Processing) for no stroke points or
//   non-finite input. Cost: O(#P t^2 + #N t^2 + t^3) with t = monomial_count(degree) <= 35.

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cstdint>
#include <string>

namespace sketchsurf {

/// Highest polynomial degree of a model (paper §4.2: d <= 4, t = 35 parameters).
inline constexpr int kMaxImplicitDegree = 4;

/// Monomials of degree <= d in 3 variables: 1, 4, 10, 20, 35 for d = 0..4.
/// Throws sketchsurf::Error (Usage) for d outside 0..4.
int monomial_count(int degree);

/// Exponents (of x, y, z) of the 35 graded monomials up to degree 4, in model coefficient order.
using MonomialExponents = std::array<std::array<std::uint8_t, 3>, 35>;
constexpr MonomialExponents implicit_monomials() {
  MonomialExponents table{};
  int k = 0;
  for (int d = 0; d <= kMaxImplicitDegree; ++d)
    for (int i = d; i >= 0; --i)
      for (int j = d - i; j >= 0; --j)
        table[k++] = {static_cast<std::uint8_t>(i), static_cast<std::uint8_t>(j),
                      static_cast<std::uint8_t>(d - i - j)};
  return table;
}

/// f(x) = sum_k c_k m_k((x - center) / scale), monomials m_k up to `degree` (paper Eq. 5-6).
struct ImplicitModel {
  int degree = 1;
  Eigen::VectorXd coefficients;                     // monomial_count(degree) entries
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  // normalisation of the coordinates (world)
  double scale = 1.0;                               // world length of one normalised unit, > 0

  /// Whether the fields are consistent: 1 <= degree <= 4, monomial_count(degree) finite
  /// coefficients, finite center, finite scale > 0. Says what is wrong in *why (if not null).
  bool valid(std::string* why) const;
  /// dim(theta) used by E_simplicity (Eq. 4): the number of coefficients, 4..35.
  int dimension() const;
  /// f(x) for a world point x.
  double value(const Eigen::Vector3d& x) const;
  /// d f / d x in world units (1 / length times the unit of f).
  Eigen::Vector3d gradient(const Eigen::Vector3d& x) const;
  /// Taubin's first-order distance |f| / |grad f| from x to Z(f) (Eq. 5), world units.
  /// 0 on the zero set; +infinity where f != 0 and grad f = 0.
  double distance(const Eigen::Vector3d& x) const;

  /// The same value for Ceres: T is double or ceres::Jet. x points to 3 values (world units).
  template <typename T>
  T evaluate(const T* x) const;
  /// d f / d x for Ceres: T is double or ceres::Jet; x and g point to 3 values each.
  template <typename T>
  void evaluate_gradient(const T* x, T* g) const;
};

/// model.distance(x) for every row x of `points` (#P x 3, world units), bit for bit, with the
/// powers of each point computed once for f and grad f: segmentation evaluates every candidate
/// model at every stroke point (chair: a quarter of the segmentation's instructions went to
/// evaluate + evaluate_gradient). out must hold #P values.
void implicit_distances(const ImplicitModel& model, Eigen::Ref<const Eigen::MatrixX3d> points,
                        double* out);

/// How the proxy-normal alignment term of the fit is formed; the paper writes it two ways.
/// Measured on single fits (tests): per-vertex keeps the function well behaved on noisy planar data
/// with exact normals (degree 2 on a noisy plane: half the residual), summed recovers curved
/// surfaces whose exact polynomial has a varying gradient (ellipsoid exact instead of ~10% of its
/// size off; torus at degree 4: 3.5x closer). Measured in PEARL (the default, summed): a rough
/// proxy's normals are tilted, and with per-vertex alignment they pull a plane off exactly coplanar
/// stroke points (bundled cube: a 5 degree tilt, E_fidelity 0.16 instead of ~0), so quartics win
/// flat faces and restarts end far apart (cube: 0.013-0.22, 6-10 regions by seed; summed: every
/// restart 0.008, six planes). On the 14 real sketches summed ends at a 20-80% lower Eq. 1 energy
/// (chair 0.621 -> 0.368, hat 0.315 -> 0.232, torus: one quartic instead of 9 regions) with fewer
/// regions, and segments faster (03-1-2 28.8 s -> 6.9 s).
enum class NormalAlignment {
  /// Eq. 6 as written (and METHOD.md): mu sum_v (1 - n_v . grad f(v))^2. Asks for n . grad f = 1
  /// at every proxy vertex.
  PerVertex,
  /// App. B, Eq. 11-12: mu (1 - sum_v n_v . grad f(v))^2, one summed row M_align. Fixes the sign
  /// and scale of f and leaves the shape to the points: exact quadric fits.
  Summed,
};

struct FitOptions {
  double mu = 0.1;           // weight of the proxy-normal alignment term (Eq. 6); >= 0
  NormalAlignment alignment = NormalAlignment::Summed;  // form of the alignment term (above)
  double lambda = 1.0;       // L2 regularisation on normalised coefficients (Eq. 6, App. B); >= 0
  double length_unit = 0.0;  // world length in which the alignment target n . grad f = 1 is
                             // measured (paper: the sketch's bbox diagonal, its sketches having
                             // diagonal 1; pass it for paper behaviour); 0 = the bbox diagonal of
                             // points and normal_points together, which makes each fit
                             // scale-invariant on its own
  bool valid(std::string* why) const;
};

/// Fits a degree-`degree` model (Eq. 6, App. B: normalised monomial columns).
/// points: #P x 3 stroke points P_a (#P >= 1); normal_points: #N x 3 proxy vertices of the region
/// without stroke points (P'_a); normals: #N x 3 unit proxy normals at those vertices.
/// Minimises sum_P (X(p)^T theta)^2 + alignment + lambda |theta|^2 in the normalised monomial
/// basis: coordinates centred on the points' centroid and divided by the length unit, then each
/// non-constant monomial column centred and divided by its standard deviation over P (the
/// constant column vanishes; its coefficient is the fold-back of the means).
/// The alignment term is App. B's summed row or Eq. 6's per-vertex rows (options.alignment).
/// Without normal points the problem has the trivial solution theta = 0; then the classical
/// algebraic fit is used instead: the unit theta minimising the point term plus lambda |theta|^2.
/// A column whose deviation is below 1e-3 r^deg (r: RMS radius of the data in normalised units),
/// such as z on a plane z = 0, is divided by that floor instead.
/// Throws sketchsurf::Error: Usage (degree outside 1..4, invalid options, #N rows mismatch),
/// Processing (no points, non-finite values).
ImplicitModel fit_implicit(int degree, Eigen::Ref<const Eigen::MatrixX3d> points,
                           Eigen::Ref<const Eigen::MatrixX3d> normal_points,
                           Eigen::Ref<const Eigen::MatrixX3d> normals,
                           const FitOptions& options = {});

/// What the summed alignment (App. B) needs of a set of normal points: sums over them that add up
/// over any partition of the set, so that a region's are the sum of its parts' (PEARL keeps one
/// per labelled-graph vertex instead of visiting every proxy vertex of a region in every fit; on
/// 01-0-1, 82k proxy vertices, those visits were a fifth of the segmentation). The sums are of
/// powers of y = x - origin: keep the origin near the data (fits convert them to each model's
/// frame, which loses about eps (|y| / model scale)^3 relative).
struct NormalMoments {
  /// Monomials y^e with |e| <= 3, in implicit_monomials() order: n . grad m for the quartic's m.
  static constexpr int kPowers = 20;

  explicit NormalMoments(const Eigen::Vector3d& about = Eigen::Vector3d::Zero());
  /// Adds the normal point `position` with unit normal `normal`.
  void add(const Eigen::Vector3d& position, const Eigen::Vector3d& normal);
  /// Adds another set's sums; throws Error (Usage) when its origin differs.
  NormalMoments& operator+=(const NormalMoments& other);

  Eigen::Vector3d origin;
  long count = 0;
  Eigen::Vector3d lo, hi;                 ///< bounding box of the positions (count > 0)
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();  ///< sum of y
  double squared = 0.0;                   ///< sum of |y|^2
  std::array<std::array<double, kPowers>, 3> directional{};  ///< [i][k]: sum of n_i y^e_k
};

/// fit_implicit with the normal points given by their moments: the summed alignment only
/// (options.alignment must be Summed; Usage error otherwise). The same fit as from the points
/// themselves, up to rounding.
ImplicitModel fit_implicit(int degree, Eigen::Ref<const Eigen::MatrixX3d> points,
                           const NormalMoments& normals, const FitOptions& options = {});

// ------------------------------------------------------------------------------------------------
// Template definitions.

namespace detail {

// Powers 0..d of each normalised coordinate (x - center) / scale, for d the degree the model's
// coefficients need (not trusting `degree`); returns how many monomials (at most 35) to sum.
template <typename T>
Eigen::Index implicit_powers(const ImplicitModel& model, const T* x,
                             T (&powers)[3][kMaxImplicitDegree + 1]) {
  constexpr MonomialExponents kMonomials = implicit_monomials();
  const Eigen::Index t = std::min<Eigen::Index>(model.coefficients.size(), kMonomials.size());
  const int needed = t > 0 ? kMonomials[t - 1][0] + kMonomials[t - 1][1] + kMonomials[t - 1][2] : 0;
  for (int i = 0; i < 3; ++i) {
    const T y = (x[i] - T(model.center[i])) / T(model.scale);
    powers[i][0] = T(1.0);
    for (int e = 1; e <= needed; ++e) powers[i][e] = powers[i][e - 1] * y;
  }
  return t;
}

}  // namespace detail

template <typename T>
T ImplicitModel::evaluate(const T* x) const {
  constexpr MonomialExponents kMonomials = implicit_monomials();
  T powers[3][kMaxImplicitDegree + 1];
  const Eigen::Index t = detail::implicit_powers(*this, x, powers);
  T f = T(0.0);
  for (Eigen::Index k = 0; k < t; ++k) {
    const auto& m = kMonomials[k];
    f += coefficients[k] * (powers[0][m[0]] * powers[1][m[1]] * powers[2][m[2]]);
  }
  return f;
}

template <typename T>
void ImplicitModel::evaluate_gradient(const T* x, T* g) const {
  constexpr MonomialExponents kMonomials = implicit_monomials();
  T powers[3][kMaxImplicitDegree + 1];
  const Eigen::Index t = detail::implicit_powers(*this, x, powers);
  for (int i = 0; i < 3; ++i) g[i] = T(0.0);
  for (Eigen::Index k = 1; k < t; ++k) {
    const auto& m = kMonomials[k];
    const double c = coefficients[k];
    if (m[0] > 0) g[0] += (c * m[0]) * (powers[0][m[0] - 1] * powers[1][m[1]] * powers[2][m[2]]);
    if (m[1] > 0) g[1] += (c * m[1]) * (powers[0][m[0]] * powers[1][m[1] - 1] * powers[2][m[2]]);
    if (m[2] > 0) g[2] += (c * m[2]) * (powers[0][m[0]] * powers[1][m[1]] * powers[2][m[2] - 1]);
  }
  for (int i = 0; i < 3; ++i) g[i] = g[i] / T(scale);
}

}  // namespace sketchsurf
