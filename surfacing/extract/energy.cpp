#include "surfacing/extract/energy.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <Eigen/Sparse>

#include "surfacing/portable_math.h"

namespace sketchsurf {

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
      w[v.idx()] = std::isfinite(c) ? seam_weight(portable::acos(c), options) : 0.0;
    }
  });
  return w;
}

namespace detail {

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

double laplacian_coefficient(const LaplacianTerm& term, std::size_t j) {
  const double s = std::sqrt(term.weight);
  return j == 0 ? s : -s / static_cast<double>(term.vertices.size() - 1);
}

namespace {

/// The Laplacian terms with a projection (mirror-plane vertices) as one sparse matrix L (3 rows
/// per term, 3 columns per vertex), so that their energy is |L x|^2 and its gradient 2 L^T L x:
/// the "precomputed gradient matrices for the quadratic terms" of §4.3.
RowMajorMatrix laplacian_matrix(const std::vector<const LaplacianTerm*>& terms, int n) {
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
  RowMajorMatrix L(3 * terms.size(), 3 * n);
  L.setFromTriplets(entries.begin(), entries.end());
  return L;
}

/// The Laplacian terms without projection as one scalar matrix S (a row per term, a column per
/// vertex) that acts on the three coordinates alike: |S X|^2 with X the n x 3 positions. A third
/// of the entries and index loads of laplacian_matrix() for the same products.
RowMajorMatrix scalar_laplacian_matrix(const std::vector<const LaplacianTerm*>& terms, int n) {
  std::vector<Eigen::Triplet<double>> entries;
  for (std::size_t t = 0; t < terms.size(); ++t) {
    const auto& term = *terms[t];
    for (std::size_t j = 0; j < term.vertices.size(); ++j)
      entries.emplace_back(static_cast<int>(t), term.vertices[j], laplacian_coefficient(term, j));
  }
  RowMajorMatrix S(static_cast<Eigen::Index>(terms.size()), n);
  S.setFromTriplets(entries.begin(), entries.end());
  return S;
}

/// Y = A X for X, Y of 3 columns stored row by row (x[3 v + c]), each row of A alone on one of
/// `threads` threads.
void multiply_rows3(const RowMajorMatrix& A, const double* x, double* y, const WorkerTeam& team) {
  team.for_each(0, static_cast<std::size_t>(A.rows()), [&](std::size_t r) {
    double sum[3] = {0.0, 0.0, 0.0};
    for (RowMajorMatrix::InnerIterator it(A, static_cast<Eigen::Index>(r)); it; ++it) {
      const double* from = x + 3 * it.col();
      for (int c = 0; c < 3; ++c) sum[c] += it.value() * from[c];
    }
    for (int c = 0; c < 3; ++c) y[3 * r + c] = sum[c];
  });
}

LaplacianSplit split_laplacians(const MeshEnergy& energy) {
  LaplacianSplit split;
  for (const LaplacianTerm& t : energy.regularize_2d)
    (t.projection.isIdentity(0.0) ? split.scalar : split.projected).push_back(&t);
  split.scalar_2d = split.scalar.size();
  for (const LaplacianTerm& t : energy.regularize_1d)
    (t.projection.isIdentity(0.0) ? split.scalar : split.projected).push_back(&t);
  return split;
}

}  // namespace

MeshEnergyFunction::MeshEnergyFunction(const MeshEnergy& energy, int n, const WorkerTeam& team)
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

bool MeshEnergyFunction::evaluate(const double* x, double* cost, double* gradient, const double* gradient_scale) const {
  const Eigen::Map<const Eigen::VectorXd> X(x, 3 * n_);
  const bool scale_in_loop = projected_.rows() == 0 && energy_.attract.empty() && energy_.plane_vertices.empty();
  // Projection: each term alone (in parallel), accumulated in a fixed order.
  team_.for_each(0, energy_.project.size(), [&](std::size_t i) {
    const ProjectionTerm& t = energy_.project[i];
    const double s = std::sqrt(t.weight);
    project_values_[i] = energy_.derivatives[t.model].taubin(x + 3 * t.vertex, s, t.floor,
                                                             project_gradients_[i].data()) +
                         s * t.offset;
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
  for (const AttractTarget& t : energy_.attract) {
    const double sa = energy_.attract_weight * t.weight;
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

Eigen::VectorXd MeshEnergyFunction::hessian_diagonal() const {
  Eigen::VectorXd d = Eigen::VectorXd::Zero(3 * n_);
  for (int r = 0; r < scalar_.outerSize(); ++r)
    for (RowMajorMatrix::InnerIterator it(scalar_, r); it; ++it)
      d.segment<3>(3 * it.col()).array() += it.value() * it.value();
  for (int r = 0; r < projected_.outerSize(); ++r)
    for (RowMajorMatrix::InnerIterator it(projected_, r); it; ++it) d[it.col()] += it.value() * it.value();
  for (const ProjectionTerm& t : energy_.project) d.segment<3>(3 * t.vertex).array() += t.weight;
  for (const AttractTarget& t : energy_.attract) d.segment<3>(3 * t.vertex).array() += energy_.attract_weight * t.weight;
  for (int v : energy_.plane_vertices) d.segment<3>(3 * v) += energy_.plane_weight * energy_.plane->normal.cwiseAbs2();
  return d;
}

MeshEnergyTerms MeshEnergyFunction::terms(const double* x) const {
  MeshEnergyTerms e;
  const Eigen::Map<const Eigen::VectorXd> X(x, 3 * n_);
  team_.for_each(0, energy_.project.size(), [&](std::size_t i) {
    const ProjectionTerm& t = energy_.project[i];
    const ProjectionResidual r{&(*energy_.models)[t.model], std::sqrt(t.weight), t.floor, t.offset};
    r(x + 3 * t.vertex, &project_values_[i]);
  });
  for (double value : project_values_) e.project += value * value;
  Eigen::VectorXd residuals(3 * scalar_.rows());
  multiply_rows3(scalar_, x, residuals.data(), team_);
  const Eigen::Index rows_2d = 3 * static_cast<Eigen::Index>(split_.scalar_2d);
  e.regularize_2d = residuals.head(rows_2d).squaredNorm() + (projected_ * X).squaredNorm();
  e.regularize_1d = residuals.tail(residuals.size() - rows_2d).squaredNorm();
  for (const AttractTarget& t : energy_.attract)
    e.attract += energy_.attract_weight * t.weight * (X.segment<3>(3 * t.vertex) - t.point).squaredNorm();
  for (int v : energy_.plane_vertices) {
    const double off = energy_.plane->signed_distance(X.segment<3>(3 * v));
    e.plane += energy_.plane_weight * off * off;
  }
  return e;
}

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
  std::vector<bool> held(static_cast<std::size_t>(n), false);
  for (int v : constraints.held) held[static_cast<std::size_t>(v)] = true;
  const std::vector<double> offset = inside_offsets(constraints, n);
  for (int v = 0; v < n; ++v)
    if (!held[static_cast<std::size_t>(v)])
      for (int l : lm.labels[v])
        energy.project.push_back({v, l, 1.0 / lm.labels[v].size(), floor[l], offset[static_cast<std::size_t>(v)]});

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

}  // namespace detail

}  // namespace sketchsurf
