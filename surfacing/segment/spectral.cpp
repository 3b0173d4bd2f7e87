#include "surfacing/segment/spectral.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <Spectra/SymEigsShiftSolver.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <utility>

#include "surfacing/error.h"
#include "surfacing/parallel.h"

namespace sketchsurf {
namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

// Components below this size are solved with a dense eigen-decomposition.
constexpr int kDenseLimit = 600;
// Shift of the shift-invert Lanczos iteration: just below L_sym's smallest eigenvalue 0, so that
// L - sigma I is positive definite (LDLT works) and the wanted eigenvalues are the largest of
// (L - sigma I)^-1.
constexpr double kShift = -1e-3;

// y = (L - sigma I)^-1 x through a sparse LDLT, for Spectra's SymEigsShiftSolver.
class ShiftSolve {
 public:
  using Scalar = double;
  explicit ShiftSolve(const SparseMatrix& laplacian) : laplacian_(laplacian) {}
  Eigen::Index rows() const { return laplacian_.rows(); }
  Eigen::Index cols() const { return laplacian_.cols(); }
  void set_shift(double sigma) {
    SparseMatrix identity(laplacian_.rows(), laplacian_.cols());
    identity.setIdentity();
    solver_.compute(laplacian_ - sigma * identity);
    if (solver_.info() != Eigen::Success)
      throw Error::processing("spectral clustering: factorising the graph Laplacian failed");
  }
  void perform_op(const double* x_in, double* y_out) const {
    Eigen::Map<Eigen::VectorXd>(y_out, rows()) =
        solver_.solve(Eigen::Map<const Eigen::VectorXd>(x_in, rows()));
  }

 private:
  const SparseMatrix& laplacian_;
  Eigen::SimplicialLDLT<SparseMatrix> solver_;
};

// Portable generator helpers: the same numbers on every platform for a seed.
double uniform01(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

std::uint64_t mix_seed(std::uint64_t seed, std::uint64_t stream) {
  std::uint64_t z = seed + 0x9e3779b97f4a7c15ull * (stream + 1);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}

struct KMeansResult {
  std::vector<int> labels;
  double inertia = std::numeric_limits<double>::infinity();
};

// k-means++ seeding then Lloyd iterations on the columns of xt (d x n: one point per column, so
// that a point's coordinates and its distances to the centres are contiguous), 1 <= k <= n.
// Stops when at most 0.1% of the points change cluster (measured: the cut quality stops improving
// long before Lloyd's iteration fully settles on large graphs) or after `iterations` assignments.
KMeansResult kmeans(const Eigen::MatrixXd& xt, int k, std::uint64_t seed, int iterations) {
  const Eigen::Index n = xt.cols();
  std::mt19937_64 rng(seed);
  const Eigen::RowVectorXd x_norms = xt.colwise().squaredNorm();
  Eigen::MatrixXd centers(xt.rows(), k);  // one centre per column
  Eigen::RowVectorXd nearest(n);

  // k-means++: each new centre drawn with probability proportional to the squared distance to the
  // nearest centre chosen so far.
  const Eigen::Index first = static_cast<Eigen::Index>(rng() % static_cast<std::uint64_t>(n));
  centers.col(0) = xt.col(first);
  nearest = (xt.colwise() - centers.col(0)).colwise().squaredNorm();
  for (int c = 1; c < k; ++c) {
    const double total = nearest.sum();
    Eigen::Index pick = 0;
    if (total > 0.0) {
      double r = uniform01(rng) * total;
      pick = n - 1;
      for (Eigen::Index i = 0; i < n; ++i) {
        r -= nearest[i];
        if (r < 0.0 && nearest[i] > 0.0) {
          pick = i;
          break;
        }
      }
      while (nearest[pick] == 0.0) --pick;  // never a point that is already a centre
    }
    centers.col(c) = xt.col(pick);
    nearest = nearest.cwiseMin((xt.colwise() - centers.col(c)).colwise().squaredNorm());
  }

  KMeansResult result;
  result.labels.assign(n, -1);
  Eigen::RowVectorXd distance(n);
  Eigen::MatrixXd cross(k, n);
  std::vector<Eigen::Index> sizes(k);
  for (int it = 0; it < iterations; ++it) {
    // Assignment: |x - c|^2 = |x|^2 - 2 x.c + |c|^2, the cross terms as one matrix product.
    cross.noalias() = centers.transpose() * xt;
    const Eigen::VectorXd c_norms = centers.colwise().squaredNorm().transpose();
    Eigen::Index changed = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double* column = cross.col(i).data();
      int best = 0;
      double best_d = std::numeric_limits<double>::infinity();
      for (int c = 0; c < k; ++c) {
        const double d = c_norms[c] - 2.0 * column[c];
        if (d < best_d) {
          best_d = d;
          best = c;
        }
      }
      distance[i] = std::max(0.0, best_d + x_norms[i]);
      if (result.labels[i] != best) {
        result.labels[i] = best;
        ++changed;
      }
    }
    result.inertia = distance.sum();
    if (changed * 1000 <= n) break;
    // Update: centroids; an emptied cluster takes the point farthest from its centre.
    centers.setZero();
    std::fill(sizes.begin(), sizes.end(), 0);
    for (Eigen::Index i = 0; i < n; ++i) {
      centers.col(result.labels[i]) += xt.col(i);
      ++sizes[result.labels[i]];
    }
    for (int c = 0; c < k; ++c) {
      if (sizes[c] > 0) {
        centers.col(c) /= static_cast<double>(sizes[c]);
        continue;
      }
      Eigen::Index far = 0;
      distance.maxCoeff(&far);
      centers.col(c) = xt.col(far);
      distance[far] = 0.0;
    }
  }
  return result;
}

// The k smallest eigenvectors (n x k) of the normalised Laplacian of a connected graph.
Eigen::MatrixXd laplacian_eigenvectors(const SparseMatrix& laplacian, int k) {
  const Eigen::Index n = laplacian.rows();
  if (n <= kDenseLimit) {
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig{Eigen::MatrixXd(laplacian)};
    return eig.eigenvectors().leftCols(k);
  }
  ShiftSolve op(laplacian);
  for (int attempt = 0; attempt < 2; ++attempt) {
    const Eigen::Index ncv = std::min<Eigen::Index>(n, std::max(2 * k + 1, k + 20) * (attempt + 1));
    Spectra::SymEigsShiftSolver<ShiftSolve> solver(op, k, ncv, kShift);
    solver.init();
    solver.compute(Spectra::SortRule::LargestMagn, 1000, 1e-5, Spectra::SortRule::SmallestAlge);
    if (solver.info() == Spectra::CompInfo::Successful) return solver.eigenvectors();
  }
  throw Error::processing("spectral clustering: the eigen solver did not converge for k = " +
                          std::to_string(k) + " on a component of " + std::to_string(n) +
                          " vertices");
}

// Connected components through positive-affinity edges; returns the component per vertex.
std::vector<int> components(int n, const std::vector<std::array<int, 2>>& edges,
                            const std::vector<double>& affinities, int* count) {
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (std::size_t e = 0; e < edges.size(); ++e)
    if (affinities[e] > 0.0) {
      const int a = find(edges[e][0]), b = find(edges[e][1]);
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  std::vector<int> component(n, -1), id_of_root(n, -1);
  *count = 0;
  for (int v = 0; v < n; ++v) {
    const int r = find(v);
    if (id_of_root[r] < 0) id_of_root[r] = (*count)++;
    component[v] = id_of_root[r];
  }
  return component;
}

// Clusters per component: all components get one when they outnumber k (the smallest then share);
// otherwise the k - c extra clusters go by largest remainder of k * size / n, capped at the size.
std::vector<int> clusters_per_component(const std::vector<int>& sizes, int k, int n) {
  const int c = static_cast<int>(sizes.size());
  std::vector<int> share(c, 1);
  if (c >= k) return share;
  int left = k - c;
  std::vector<double> remainder(c);
  for (int i = 0; i < c; ++i) {
    const double ideal = static_cast<double>(k) * sizes[i] / n;
    const int extra = std::min(std::max(0, static_cast<int>(ideal) - 1), sizes[i] - 1);
    const int given = std::min(extra, left);
    share[i] += given;
    left -= given;
    remainder[i] = ideal - share[i];
  }
  while (left > 0) {
    int best = -1;
    for (int i = 0; i < c; ++i)
      if (share[i] < sizes[i] && (best < 0 || remainder[i] > remainder[best])) best = i;
    if (best < 0) break;
    ++share[best];
    remainder[best] -= 1.0;
    --left;
  }
  return share;
}

}  // namespace

bool SpectralOptions::valid(std::string* why) const {
  auto fail = [&](const char* what) {
    if (why) *why = what;
    return false;
  };
  if (kmeans_restarts < 1) return fail("kmeans_restarts must be >= 1");
  if (kmeans_iterations < 1) return fail("kmeans_iterations must be >= 1");
  return true;
}

SpectralClustering::SpectralClustering(int num_vertices,
                                       const std::vector<std::array<int, 2>>& edges,
                                       const std::vector<double>& affinities, int max_k,
                                       const SpectralOptions& options)
    : options_(options), max_k_(max_k), vertex_count_(num_vertices) {
  std::string why;
  if (!options.valid(&why)) throw Error::usage("spectral clustering: invalid options: " + why);
  if (num_vertices < 0) throw Error::usage("spectral clustering: negative vertex count");
  if (max_k < 1)
    throw Error::usage("spectral clustering: k must be >= 1, got " + std::to_string(max_k));
  if (affinities.size() != edges.size())
    throw Error::usage("spectral clustering: " + std::to_string(affinities.size()) +
                       " affinities for " + std::to_string(edges.size()) + " edges");
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const auto [u, v] = edges[e];
    if (u < 0 || u >= num_vertices || v < 0 || v >= num_vertices)
      throw Error::usage("spectral clustering: edge " + std::to_string(e) + " (" +
                         std::to_string(u) + ", " + std::to_string(v) +
                         ") has a vertex outside 0.." + std::to_string(num_vertices - 1));
    if (!(std::isfinite(affinities[e]) && affinities[e] >= 0.0))
      throw Error::usage("spectral clustering: affinity of edge " + std::to_string(e) +
                         " must be finite and >= 0");
  }
  const int n = num_vertices;
  int count = 0;
  component_ = components(n, edges, affinities, &count);
  components_.resize(count);
  for (int v = 0; v < n; ++v) components_[component_[v]].members.push_back(v);
  std::vector<int> sizes(count);
  for (int c = 0; c < count; ++c) sizes[c] = static_cast<int>(components_[c].members.size());
  if (count >= max_k) return;  // clustering by components only, no eigenvectors needed

  const std::vector<int> share = clusters_per_component(sizes, max_k, n);
  std::vector<int> local(n, -1);
  for (int c = 0; c < count; ++c)
    for (int i = 0; i < sizes[c]; ++i) local[components_[c].members[i]] = i;
  for (int c = 0; c < count; ++c) {
    Component& comp = components_[c];
    const int m = sizes[c];
    comp.max_clusters = share[c];
    if (share[c] == 1 || share[c] >= m) continue;
    // L_sym = I - D^-1/2 W D^-1/2 on this component.
    Eigen::VectorXd degree = Eigen::VectorXd::Zero(m);
    for (std::size_t e = 0; e < edges.size(); ++e) {
      const auto [u, v] = edges[e];
      if (component_[u] != c || affinities[e] == 0.0 || u == v) continue;
      degree[local[u]] += affinities[e];
      degree[local[v]] += affinities[e];
    }
    const Eigen::VectorXd inv_sqrt = degree.cwiseSqrt().cwiseInverse();
    std::vector<Eigen::Triplet<double>> triplets;
    triplets.reserve(2 * edges.size() + m);
    for (int i = 0; i < m; ++i) triplets.emplace_back(i, i, 1.0);
    for (std::size_t e = 0; e < edges.size(); ++e) {
      const auto [u, v] = edges[e];
      if (component_[u] != c || affinities[e] == 0.0 || u == v) continue;
      const double w = -affinities[e] * inv_sqrt[local[u]] * inv_sqrt[local[v]];
      triplets.emplace_back(local[u], local[v], w);
      triplets.emplace_back(local[v], local[u], w);
    }
    SparseMatrix laplacian(m, m);
    laplacian.setFromTriplets(triplets.begin(), triplets.end());
    comp.eigenvectors = laplacian_eigenvectors(laplacian, share[c]).transpose();
  }
}

std::vector<int> SpectralClustering::cluster(int k, std::uint64_t seed) const {
  if (k < 1 || k > max_k_)
    throw Error::usage("spectral clustering: k = " + std::to_string(k) + " outside 1.." +
                       std::to_string(max_k_) + " (the k this clustering was prepared for)");
  const int n = vertex_count_, count = static_cast<int>(components_.size());
  std::vector<int> result(n, 0);
  if (count >= k) {
    // More components than clusters: the k-1 largest (ties: lowest first vertex) keep their own.
    std::vector<int> order(count);
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
      return components_[a].members.size() > components_[b].members.size();
    });
    std::vector<int> cluster_of(count);
    for (int i = 0; i < count; ++i) cluster_of[order[i]] = std::min(i, k - 1);
    for (int v = 0; v < n; ++v) result[v] = cluster_of[component_[v]];
  } else {
    std::vector<int> sizes(count);
    for (int c = 0; c < count; ++c) sizes[c] = static_cast<int>(components_[c].members.size());
    const std::vector<int> share = clusters_per_component(sizes, k, n);
    int base = 0;
    for (int c = 0; c < count; ++c) {
      const Component& comp = components_[c];
      const std::vector<int>& vs = comp.members;
      const int m = sizes[c];
      // The eigenvectors were computed for max_k's share; a smaller k never needs more, except
      // for rounding in the share, which is clamped (at most k clusters either way).
      const int kc = std::min(share[c], comp.max_clusters);
      if (kc <= 1) {
        for (int v : vs) result[v] = base;
      } else if (kc >= m) {
        for (int i = 0; i < m; ++i) result[vs[i]] = base + i;
      } else {
        // The kc smallest eigenvectors, one row-normalised point per vertex (one per column).
        Eigen::MatrixXd embedding = comp.eigenvectors.topRows(kc);
        for (int i = 0; i < m; ++i) {
          const double norm = embedding.col(i).norm();
          if (norm > 0.0) embedding.col(i) /= norm;
        }
        std::vector<KMeansResult> runs(options_.kmeans_restarts);
        parallel_for(0, runs.size(), options_.threads, [&](std::size_t r) {
          runs[r] = kmeans(embedding, kc, mix_seed(seed, c * 1000003ull + r),
                           options_.kmeans_iterations);
        });
        std::size_t best = 0;
        for (std::size_t r = 1; r < runs.size(); ++r)
          if (runs[r].inertia < runs[best].inertia) best = r;
        for (int i = 0; i < m; ++i) result[vs[i]] = base + runs[best].labels[i];
      }
      base += kc;
    }
  }

  // Compact to 0..m-1 in order of first vertex.
  std::vector<int> compact(n, -1);
  int next = 0;
  for (int v = 0; v < n; ++v) {
    if (compact[result[v]] < 0) compact[result[v]] = next++;
    result[v] = compact[result[v]];
  }
  return result;
}

std::vector<int> spectral_clustering(int num_vertices, const std::vector<std::array<int, 2>>& edges,
                                     const std::vector<double>& affinities, int k,
                                     std::uint64_t seed, const SpectralOptions& options) {
  return SpectralClustering(num_vertices, edges, affinities, k, options).cluster(k, seed);
}

std::vector<int> spectral_clustering(int num_vertices, const std::vector<std::array<int, 2>>& edges,
                                     const std::vector<double>& affinities, int k,
                                     std::uint64_t seed) {
  return spectral_clustering(num_vertices, edges, affinities, k, seed, SpectralOptions{});
}

}  // namespace sketchsurf
