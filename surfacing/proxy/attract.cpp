#include "surfacing/proxy/attract.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "surfacing/error.h"
#include "surfacing/parallel.h"

namespace sketchsurf {

namespace {

// Index of the nearest vertex (rows of V) to each target, brute force in parallel over targets.
std::vector<int> nearest_vertices(const Eigen::MatrixX3d& V, const Eigen::MatrixX3d& targets,
                                  unsigned threads, std::vector<double>* distances) {
  std::vector<int> out(static_cast<std::size_t>(targets.rows()));
  if (distances) distances->assign(out.size(), 0.0);
  const Eigen::ArrayXd vx = V.col(0), vy = V.col(1), vz = V.col(2);
  parallel_for(0, out.size(), threads, [&](std::size_t t) {
    const Eigen::Index ti = static_cast<Eigen::Index>(t);
    const Eigen::ArrayXd d2 = (vx - targets(ti, 0)).square() + (vy - targets(ti, 1)).square() +
                              (vz - targets(ti, 2)).square();
    Eigen::Index best = 0;
    const double m = d2.minCoeff(&best);
    out[t] = static_cast<int>(best);
    if (distances) (*distances)[t] = std::sqrt(m);
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
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(A);
    if (solver.info() != Eigen::Success)
      throw Error::processing("least-squares mesh: the sparse system cannot be factorised");
    V = solver.solve(rhs);
    if (!V.allFinite()) throw Error::processing("least-squares mesh: the solve failed");
  }
  for (const auto v : mesh.vertices()) mesh.set_point(v, to_openmesh(V.row(v.idx())));
  mesh.update_normals();
  nearest_vertices(V, targets, options.threads, &distances);
  s.median_after = median(distances);
  if (summary) *summary = s;
  progress.update("attracting proxy", 1.0);
}

}  // namespace sketchsurf
