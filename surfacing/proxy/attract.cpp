#include "surfacing/proxy/attract.h"

#include <metis.h>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "surfacing/error.h"
#include "surfacing/parallel.h"
#include "surfacing/proxy/point_grid.h"

namespace sketchsurf {

namespace {

// Fill-reducing ordering for SimplicialLDLT by METIS nested dissection (METIS_NodeND) of the
// matrix graph (Eigen's MetisOrdering ignores METIS errors). METIS runs on one thread with a
// fixed seed: the same permutation whatever the thread count. 01-0-1's user proxy (20.6k
// vertices at twice the edge, |L^T L| = 396k nonzeros): 2.86M nonzeros in the factor with
// Eigen's AMD ordering, 2.24M with METIS; per factorisation 0.25 -> 0.13 s, for 0.11 s more
// ordering once (analysis + three rounds: 0.78 -> 0.53 s; the positions move by < 1.2e-11 of the
// diagonal). Not worth it: factorising disjoint subtrees of the elimination tree on two threads
// (measured: they hold 25% of the work, the top separators' rows 75%).
class MetisOrdering {
 public:
  using PermutationType = Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int>;

  /// A: the full symmetric matrix (both triangles), as SimplicialLDLT passes it.
  template <class Matrix>
  void operator()(const Matrix& A, PermutationType& permutation) const {
    idx_t n = static_cast<idx_t>(A.cols());
    std::vector<idx_t> xadj(static_cast<std::size_t>(n) + 1, 0), adjncy;
    adjncy.reserve(static_cast<std::size_t>(A.nonZeros()));
    for (idx_t j = 0; j < n; ++j) {
      for (typename Matrix::InnerIterator it(A, j); it; ++it)
        if (it.index() != j) adjncy.push_back(static_cast<idx_t>(it.index()));
      xadj[j + 1] = static_cast<idx_t>(adjncy.size());
    }
    idx_t options[METIS_NOPTIONS];
    METIS_SetDefaultOptions(options);
    options[METIS_OPTION_SEED] = 1;
    std::vector<idx_t> perm(static_cast<std::size_t>(n)), iperm(static_cast<std::size_t>(n));
    if (METIS_NodeND(&n, xadj.data(), adjncy.data(), nullptr, options, perm.data(), iperm.data()) !=
        METIS_OK)
      throw Error::processing("least-squares mesh: METIS could not order the sparse system (out "
                              "of memory?)");
    // Eigen's orderings give, for each position of the permuted matrix, the original row (the
    // inverse permutation P^-1 of the factorisation P A P^T): METIS's perm.
    permutation.resize(n);
    for (idx_t i = 0; i < n; ++i) permutation.indices()[i] = static_cast<int>(perm[i]);
  }
};

// Index of the nearest vertex (rows of V) to each target, in parallel over targets.
std::vector<int> nearest_vertices(const Eigen::MatrixX3d& V, const Eigen::MatrixX3d& targets,
                                  unsigned threads, std::vector<double>* distances) {
  std::vector<int> out(static_cast<std::size_t>(targets.rows()));
  if (distances) distances->assign(out.size(), 0.0);
  const PointGrid grid(V);
  parallel_for(0, out.size(), threads, [&](std::size_t t) {
    const auto [v, d2] = grid.nearest(targets.row(static_cast<Eigen::Index>(t)).transpose());
    out[t] = v;
    if (distances) (*distances)[t] = std::sqrt(d2);
  });
  return out;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

}  // namespace

bool AttractOptions::valid(std::string* why) const {
  auto fail = [&](const char* msg) {
    if (why) *why = msg;
    return false;
  };
  if (!(weight > 0.0) || !std::isfinite(weight)) return fail("attraction weight must be > 0");
  if (rounds < 1) return fail("attraction rounds must be >= 1");
  return true;
}

double median_nearest_vertex_distance(const TriMesh& mesh, const Eigen::MatrixX3d& targets,
                                      unsigned threads) {
  std::vector<double> d;
  nearest_vertices(vertex_matrix(mesh), targets, threads, &d);
  return median(std::move(d));
}

void attract_to_points(TriMesh& mesh, const Eigen::MatrixX3d& targets, const AttractOptions& options,
                       const Progress& progress, AttractSummary* summary) {
  std::string why;
  if (!options.valid(&why)) throw Error::usage(why);
  if (mesh.n_vertices() == 0) throw Error::processing("cannot attract an empty mesh");
  if (targets.rows() == 0) throw Error::processing("no stroke points to attract the mesh to");
  const auto n = static_cast<Eigen::Index>(mesh.n_vertices());

  // Uniform Laplacian rows: x_i - mean of its neighbours (isolated vertices get no row).
  std::vector<Eigen::Triplet<double>> lap;
  for (const auto v : mesh.vertices()) {
    const double valence = static_cast<double>(mesh.valence(v));
    if (valence == 0) continue;
    lap.emplace_back(v.idx(), v.idx(), 1.0);
    for (const auto w : v.vertices()) lap.emplace_back(v.idx(), w.idx(), -1.0 / valence);
  }
  Eigen::SparseMatrix<double> L(n, n);
  L.setFromTriplets(lap.begin(), lap.end());
  const Eigen::SparseMatrix<double> LtL = (L.transpose() * L).pruned();

  Eigen::MatrixX3d V = vertex_matrix(mesh);
  std::vector<double> distances;
  const double w2 = options.weight * options.weight;
  AttractSummary s;
  // Every round's matrix is LtL (whose diagonal is stored) plus a diagonal: one symbolic analysis
  // (ordering, elimination tree) serves them all; only the numeric factorisation is repeated.
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>, Eigen::Lower, MetisOrdering> solver;
  solver.analyzePattern(LtL);
  for (int round = 0; round < options.rounds; ++round) {
    progress.update("attracting proxy", static_cast<double>(round) / options.rounds);
    const std::vector<int> nearest = nearest_vertices(V, targets, options.threads, &distances);
    if (round == 0) s.median_before = median(distances);
    Eigen::VectorXd count = Eigen::VectorXd::Zero(n);
    Eigen::MatrixX3d sum = Eigen::MatrixX3d::Zero(n, 3);
    for (std::size_t t = 0; t < nearest.size(); ++t) {
      count[nearest[t]] += 1.0;
      sum.row(nearest[t]) += targets.row(static_cast<Eigen::Index>(t));
    }
    // A tiny pull to the current positions keeps the system definite on parts with no target.
    const double keep = 1e-8 * w2;
    Eigen::SparseMatrix<double> A = LtL;
    Eigen::MatrixX3d rhs = keep * V;
    for (Eigen::Index v = 0; v < n; ++v) A.coeffRef(v, v) += keep;
    s.anchors = 0;
    for (Eigen::Index v = 0; v < n; ++v) {
      if (count[v] == 0) continue;
      ++s.anchors;
      A.coeffRef(v, v) += w2;
      rhs.row(v) += w2 * sum.row(v) / count[v];
    }
    solver.factorize(A);
    if (solver.info() != Eigen::Success)
      throw Error::processing("least-squares mesh: the sparse system cannot be factorised");
    V = solver.solve(rhs);
    if (!V.allFinite()) throw Error::processing("least-squares mesh: the solve failed");
  }
  set_vertex_matrix(mesh, V);
  mesh.update_normals();
  nearest_vertices(V, targets, options.threads, &distances);
  s.median_after = median(distances);
  if (summary) *summary = s;
  progress.update("attracting proxy", 1.0);
}

}  // namespace sketchsurf
