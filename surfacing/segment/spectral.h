#pragma once
// Normalised-cut spectral clustering of a weighted graph (Shi and Malik 2000; embedding and
// row normalisation as in Ng, Jordan and Weiss 2001), the over-segmentation that seeds PEARL's
// initial models (paper §4.2 "Initialization": k = 20, 30, 40, 50 on the proxy graph with the
// smoothness weights w_e).
//
// API notes:
// - Vertices 0..n-1; edges undirected pairs with affinities >= 0 (higher = more alike; the
//   pipeline passes w_e: 100 for plain edges, 1 for edges crossed by a stroke). Duplicate edges
//   add up; zero-affinity edges connect nothing.
// - Returns one cluster index per vertex, compacted to 0..m-1 (m <= k) in order of first vertex.
//   Connected components never share a cluster unless there are more components than k (then the
//   k-1 largest keep their own cluster and the rest share the last one); k clusters are spread
//   over the components in proportion to their sizes; k >= n gives one cluster per vertex.
// - Per component: the k_i smallest eigenvectors of L_sym = I - D^-1/2 W D^-1/2 (Spectra
//   shift-invert Lanczos with a sparse LDLT factorisation; dense for small components), rows
//   normalised, then k-means++ with `kmeans_restarts` seeded restarts (run in parallel, lowest
//   inertia kept). Deterministic for a seed whatever the thread count.
// - Throws sketchsurf::Error: Usage for n < 0, k < 1, an edge out of range, mismatched or negative
//   / non-finite affinities, invalid options; Processing if the eigen solver does not converge.

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace sketchsurf {

struct SpectralOptions {
  int kmeans_restarts = 4;      // k-means++ restarts, the lowest inertia is kept (>= 1)
  int kmeans_iterations = 15;   // cap on Lloyd iterations per restart (>= 1); they also stop
                                // once at most 0.1% of the vertices change cluster
  unsigned threads = 0;         // worker threads for the restarts (0 = all hardware threads)
  bool valid(std::string* why) const;
};

/// Spectral clustering prepared once for a graph and every k up to max_k: the eigenvectors are
/// computed for max_k and their prefixes reused, so PEARL's k = 20, 30, 40, 50 cost one eigen solve.
/// Throws as spectral_clustering does; cluster() throws sketchsurf::Error (Usage) for k outside
/// 1..max_k.
class SpectralClustering {
 public:
  SpectralClustering(int num_vertices, const std::vector<std::array<int, 2>>& edges,
                     const std::vector<double>& affinities, int max_k,
                     const SpectralOptions& options = {});
  /// At most k clusters, one index per vertex, compacted to 0..m-1 in order of first vertex.
  std::vector<int> cluster(int k, std::uint64_t seed) const;

 private:
  struct Component {
    std::vector<int> members;        // vertices, increasing
    int max_clusters = 1;            // clusters given to it for max_k
    Eigen::MatrixXd eigenvectors;    // max_clusters x #members (smallest first), when needed
  };
  SpectralOptions options_;
  int max_k_ = 1;
  int vertex_count_ = 0;
  std::vector<int> component_;       // per vertex
  std::vector<Component> components_;
};

/// Normalised-cut spectral clustering (Shi-Malik) of a weighted graph into at most k clusters:
/// the k smallest eigenvectors of the normalised Laplacian (Spectra), then seeded k-means.
/// Returns a cluster index in [0, k) per vertex. Deterministic for a seed.
std::vector<int> spectral_clustering(int num_vertices, const std::vector<std::array<int, 2>>& edges,
                                     const std::vector<double>& affinities, int k,
                                     std::uint64_t seed);
/// The same with explicit options.
std::vector<int> spectral_clustering(int num_vertices, const std::vector<std::array<int, 2>>& edges,
                                     const std::vector<double>& affinities, int k,
                                     std::uint64_t seed, const SpectralOptions& options);

}  // namespace sketchsurf
