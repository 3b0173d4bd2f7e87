#pragma once
// s-t minimum cut / maximum flow on real capacities, for the graph cuts of the segmentation
// (alpha-expansion moves, paper §4.2) and of the open-boundary trim (App. D).
//
// API notes:
// - Nodes are 0..n-1; the source s and sink t are implicit. Terminal weights and edges accumulate
//   (calling add_* twice on the same node or pair adds the capacities).
// - Capacities are finite doubles >= 0, in whatever unit the caller's energy has; the min-cut cost
//   is  sum over nodes on the sink side of their source capacity
//     + sum over nodes on the source side of their sink capacity
//     + sum over edges (u, v) with u on the source side, v on the sink side, of capacity_uv.
// - solve() returns that cost (= the max-flow value); on_source_side(v) reports the cut (nodes that
//   could go either way are put on the sink side). Negative, NaN or infinite capacities and bad node
//   indices throw sketchsurf::Error (Usage); on_source_side before solve() throws too.
// - Solver: our Boykov-Kolmogorov implementation on compressed-sparse-row arrays (about 2.5x
//   faster than Boost.Graph's on expansion graphs); solve(MaxFlowSolver::Boost) runs Boost.Graph's
//   boykov_kolmogorov_max_flow instead, the reference the tests check ours against. clear() keeps
//   the buffers, so one MaxFlow can be reused for many cuts without reallocating.

#include <memory>
#include <vector>

namespace sketchsurf {

namespace detail {
class BoykovKolmogorov;
}

/// Which Boykov-Kolmogorov implementation solve() runs.
enum class MaxFlowSolver {
  Native,  ///< ours (default)
  Boost,   ///< Boost.Graph's boykov_kolmogorov_max_flow (reference)
};

/// s-t max-flow / min-cut on real capacities (Boykov-Kolmogorov: ours, or Boost.Graph's on
/// request). Nodes 0..n-1.
class MaxFlow {
 public:
  explicit MaxFlow(int nodes);
  ~MaxFlow();
  MaxFlow(MaxFlow&&) noexcept;
  MaxFlow& operator=(MaxFlow&&) noexcept;
  /// Capacity s -> node (paid when node ends on the sink side) and node -> t (paid when it ends on
  /// the source side). Both >= 0.
  void add_terminal_weights(int node, double source_capacity, double sink_capacity);
  /// Edge u -> v with capacity_uv (paid when u is on the source side and v on the sink side) and its
  /// reverse v -> u with capacity_vu. Both >= 0, u != v.
  void add_edge(int u, int v, double capacity_uv, double capacity_vu);
  /// Computes the minimum cut; returns the max-flow value = min-cut cost.
  double solve();
  /// The same with a chosen implementation (both give the same cut value).
  double solve(MaxFlowSolver solver);
  /// After solve(): whether `node` is on the source side of the minimum cut.
  bool on_source_side(int node) const;

  /// Number of nodes.
  int node_count() const { return static_cast<int>(source_capacity_.size()); }
  /// Adds a node and returns its index.
  int add_node();
  /// Forgets every node and edge and starts again with `nodes` nodes, keeping the allocations.
  void clear(int nodes);

 private:
  struct Edge {
    int u, v;
    double capacity_uv, capacity_vu;
  };
  void check_node(int node) const;

  std::vector<double> source_capacity_, sink_capacity_;
  std::vector<Edge> edges_;
  std::vector<unsigned char> source_side_;
  bool solved_ = false;
  // Work arrays of solve(), kept between calls.
  std::vector<int> offsets_, arc_head_, arc_sister_, cursor_;
  std::vector<double> arc_residual_, terminal_;
  std::unique_ptr<detail::BoykovKolmogorov> bk_;  // search trees and queues, kept between cuts
};

}  // namespace sketchsurf
