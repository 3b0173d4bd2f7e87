#include "surfacing/segment/expansion.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

#include "surfacing/error.h"
#include "surfacing/segment/maxflow.h"

namespace sketchsurf {
namespace {

void check_labels(const LabelingProblem& problem, const std::vector<int>& labels) {
  if (static_cast<int>(labels.size()) != problem.vertex_count())
    throw Error::usage("labeling: " + std::to_string(labels.size()) + " labels for " +
                       std::to_string(problem.vertex_count()) + " vertices");
  for (std::size_t v = 0; v < labels.size(); ++v)
    if (labels[v] < 0 || labels[v] >= problem.label_count())
      throw Error::usage("labeling: vertex " + std::to_string(v) + " has label " +
                         std::to_string(labels[v]) + ", outside 0.." +
                         std::to_string(problem.label_count() - 1));
}

// One alpha-expansion move at a time on a fixed problem; buffers are reused between moves.
//
// Each move is the binary problem of Delong et al. (2012): x_v = 0 switches v to alpha, 1 keeps
// its label b. Before building the cut graph, the vertices whose side is the same in every
// minimiser of that binary problem are decided (persistency). With c0 - c1 the cost of switching
// minus keeping from v's data term and its edges to decided vertices, and U_v the weight of its
// edges to undecided vertices (which change by at most U_v whatever those do):
// - c1 - c0 > U_v: switching wins (switching can only drop b's label cost), v switches;
// - c0 - c1 > U_v + h_b: keeping wins, label cost included, so v keeps and b certainly survives
//   ("anchored"); once b is anchored, its label cost is paid anyway and the test drops h_b.
// - a label b whose vertices would all switch only at a loss: sum over b's vertices of
//   (D(v, alpha) - D(v, b) - cut_v) > h_b, cut_v the weight of v's edges to other labels (the only
//   edges that can stop being cut), is anchored as a whole (chair: 1694 -> 1089 cut nodes per
//   move; 11-2-2: 625 -> 590).
// Deciding a vertex updates its neighbours' sums and may decide them in turn. The minimisers of
// the reduced problem are those of the full one restricted to the undecided vertices, so the cut
// (its smallest source side) is the same, on a much smaller graph: on PEARL's problems, mostly the
// vertices where alpha's surface competes with the current one.
class Expander {
 public:
  Expander(const LabelingProblem& problem, std::vector<int> labels, bool reduce)
      : problem_(problem), reduce_(reduce), labels_(std::move(labels)),
        counts_(problem.label_count(), 0) {
    for (int l : labels_) ++counts_[l];
    energy_ = labeling_energy(problem_, labels_);
    const int n = problem_.vertex_count();
    current_cost_.resize(n);
    for (int v = 0; v < n; ++v) current_cost_[v] = problem_.data_cost(v, labels_[v]);
    // Adjacency (compressed rows) of the positive-weight edges, and each vertex's weight sum.
    offsets_.assign(n + 1, 0);
    for (std::size_t e = 0; e < problem_.edges.size(); ++e)
      if (problem_.edge_weights[e] > 0.0) {
        ++offsets_[problem_.edges[e][0] + 1];
        ++offsets_[problem_.edges[e][1] + 1];
      }
    for (int v = 0; v < n; ++v) offsets_[v + 1] += offsets_[v];
    neighbour_.resize(offsets_[n]);
    weight_.resize(offsets_[n]);
    std::vector<int> cursor(offsets_.begin(), offsets_.end() - 1);
    weight_sum_.assign(n, 0.0);
    for (std::size_t e = 0; e < problem_.edges.size(); ++e) {
      const double w = problem_.edge_weights[e];
      if (!(w > 0.0)) continue;
      const auto [u, v] = problem_.edges[e];
      neighbour_[cursor[u]] = v;
      weight_[cursor[u]++] = w;
      neighbour_[cursor[v]] = u;
      weight_[cursor[v]++] = w;
      weight_sum_[u] += w;
      weight_sum_[v] += w;
    }
    cut_.resize(n);
    for (int v = 0; v < n; ++v) update_cut(v);
  }

  const std::vector<int>& labels() const { return labels_; }
  double energy() const { return energy_; }

  // Expands `alpha`; returns true (and applies the move) if the energy strictly drops.
  bool expand(int alpha) {
    const int L = problem_.label_count();
    const double* alpha_cost = problem_.data_cost.col(alpha).data();
    decide_undecided(alpha, alpha_cost);

    // The undecided vertices, in increasing order, are the nodes of the cut graph.
    std::erase_if(free_, [&](int v) { return state_[v] != kFree; });
    const int nodes = static_cast<int>(free_.size());
    for (int i = 0; i < nodes; ++i) node_of_[free_[i]] = i;
    if (nodes > 0) {
      flow_.clear(nodes);
      aux_of_.assign(L, -1);
      for (int v : free_) {
        const int nv = node_of_[v];
        const int b = labels_[v];
        double c0 = switch_cost_[v], c1 = keep_cost_[v];
        // Edges between undecided vertices (decided ones are in c0, c1 already): the Potts term
        // w [l_u != l_v] of the binary variables (0 = alpha, 1 = keep) is w [x_u != x_v] for
        // equal labels, and w unless both switch = w x_u + w (1 - x_u) x_v otherwise.
        for (int a = offsets_[v]; a < offsets_[v + 1]; ++a) {
          const int u = neighbour_[a];
          if (v > u || state_[u] != kFree) continue;
          const double w = weight_[a];
          if (labels_[u] == b) {
            flow_.add_edge(nv, node_of_[u], w, w);
          } else {
            c1 += w;
            flow_.add_edge(nv, node_of_[u], w, 0.0);
          }
        }
        const double m = std::min(c0, c1);
        flow_.add_terminal_weights(nv, c1 - m, c0 - m);
        // Label cost of b when not anchored (Delong et al. 2012): an auxiliary node y_b paying h_b
        // on the sink side (b survives), and an edge y_b -> v of capacity h_b for every undecided
        // vertex that would keep b, so that the cut pays h_b once unless all of b switches.
        const double h = problem_.label_cost[b];
        if (anchored_[b] || !(h > 0.0)) continue;
        if (aux_of_[b] < 0) {
          aux_of_[b] = flow_.add_node();
          flow_.add_terminal_weights(aux_of_[b], h, 0.0);
        }
        flow_.add_edge(aux_of_[b], nv, h, 0.0);
      }
      flow_.solve();
    }

    // The proposed labeling's energy change, over the vertices that switch. alpha's own label
    // cost (when alpha was unused) is not in the cut: the exact change decides.
    // changed_ holds the decided switching vertices; add the cut's, in increasing order.
    for (int v : free_)
      if (flow_.on_source_side(node_of_[v])) changed_.push_back(v);
    if (changed_.empty()) return false;
    std::sort(changed_.begin(), changed_.end());
    double delta = counts_[alpha] == 0 ? problem_.label_cost[alpha] : 0.0;
    for (int v : changed_) {
      delta += alpha_cost[v] - current_cost_[v];
      if (--counts_[labels_[v]] == 0) delta -= problem_.label_cost[labels_[v]];
    }
    // Edges at a switching vertex: [alpha != l'_u] - [l_v != l_u], each edge once (from the
    // switching end of lower index when both switch).
    for (int v : changed_) state_[v] = kChanged;
    for (int v : changed_)
      for (int a = offsets_[v]; a < offsets_[v + 1]; ++a) {
        const int u = neighbour_[a];
        if (state_[u] == kChanged && u < v) continue;
        const int after = state_[u] == kChanged ? alpha : labels_[u];
        delta += weight_[a] * ((after != alpha) - (labels_[u] != labels_[v]));
      }
    if (!(delta < 0.0)) {
      for (int v : changed_) ++counts_[labels_[v]];
      return false;
    }
    for (int v : changed_) {
      labels_[v] = alpha;
      current_cost_[v] = alpha_cost[v];
    }
    counts_[alpha] += static_cast<int>(changed_.size());
    for (int v : changed_) {
      update_cut(v);
      for (int a = offsets_[v]; a < offsets_[v + 1]; ++a) update_cut(neighbour_[a]);
    }
    energy_ += delta;
    return true;
  }

 private:
  static constexpr unsigned char kFree = 0, kSwitch = 1, kKeep = 2, kChanged = 3;

  // Decides what persistency decides (see the class comment), leaving state_ kSwitch / kKeep /
  // kFree per vertex, switch_cost_ / keep_cost_ the terms of the undecided vertices from their data
  // and their edges to decided ones (up to a common constant), and anchored_ per label.
  void decide_undecided(int alpha, const double* alpha_cost) {
    const int n = problem_.vertex_count(), L = problem_.label_count();
    state_.resize(n);
    switch_cost_.resize(n);
    node_of_.resize(n);
    anchored_.assign(L, 0);
    label_margin_.assign(L, 0.0);
    free_.clear();
    changed_.clear();
    if (!reduce_) {
      // Reference: every vertex not already alpha goes to the cut, with only alpha's vertices
      // (which stay alpha) as decided neighbours.
      for (int v = 0; v < n; ++v) {
        state_[v] = labels_[v] == alpha ? kSwitch : kFree;
        switch_cost_[v] = alpha_cost[v] - current_cost_[v];
        if (state_[v] == kFree) free_.push_back(v);
      }
      add_decided_neighbours();
      return;
    }
    // The data terms first (contiguous, no edge visited): they decide most vertices. A label b
    // whose vertices would all switch only at a loss greater than h_b is anchored as a whole:
    // switching all of B (b's vertices) changes E by at least sum_B (D(v, alpha) - D(v, b))
    // - cut(B) - h_b (its boundary edges are the only ones that can stop being cut), so when
    // sum_B (D(v, alpha) - D(v, b) - cut_v) > h_b no minimiser empties b.
    // One pass: switch when alpha wins by more than all edges, keep when b wins by more than all
    // edges and h_b; a vertex between (b wins by less than that, more than its edges) keeps if b
    // turns out anchored, and is held in pending_ until the pass is over.
    pending_.clear();
    for (int v = 0; v < n; ++v) {
      const int b = labels_[v];
      if (b == alpha) {
        state_[v] = kSwitch;
        continue;
      }
      const double diff = alpha_cost[v] - current_cost_[v], slack = weight_sum_[v];
      switch_cost_[v] = diff;
      label_margin_[b] += diff - cut_[v];
      if (diff < -slack) {
        state_[v] = kSwitch;
        changed_.push_back(v);
      } else if (diff > slack + problem_.label_cost[b]) {
        state_[v] = kKeep;
        anchored_[b] = 1;
      } else if (diff > slack) {
        state_[v] = kKeep;
        pending_.push_back(v);
      } else {
        state_[v] = kFree;
        free_.push_back(v);
      }
    }
    for (int b = 0; b < L; ++b)
      if (label_margin_[b] > problem_.label_cost[b]) anchored_[b] = 1;
    const std::size_t decided = free_.size();
    for (int v : pending_)
      if (!anchored_[labels_[v]]) {
        state_[v] = kFree;
        free_.push_back(v);
      }
    std::inplace_merge(free_.begin(), free_.begin() + static_cast<std::ptrdiff_t>(decided),
                       free_.end());
    add_decided_neighbours();
    stack_.clear();
    for (int v : free_)
      if (state_[v] == kFree && try_decide(v)) settle();
  }

  // For every undecided vertex: its costs from its edges to decided vertices, and the weight of
  // its edges to undecided ones.
  void add_decided_neighbours() {
    const int n = problem_.vertex_count();
    keep_cost_.resize(n);
    undecided_.resize(n);
    for (int v : free_) {
      const int b = labels_[v];
      double c0 = switch_cost_[v], c1 = 0.0, open = 0.0;
      for (int a = offsets_[v]; a < offsets_[v + 1]; ++a) {
        const int u = neighbour_[a];
        const double w = weight_[a];
        if (state_[u] == kSwitch) {
          c1 += w;  // u ends alpha: v pays w if it keeps
        } else if (state_[u] == kKeep) {
          c0 += w;  // u keeps its label: v pays w if it switches ...
          if (labels_[u] != b) c1 += w;  // ... and if it keeps a different label
        } else {
          open += w;
        }
      }
      switch_cost_[v] = c0;
      keep_cost_[v] = c1;
      undecided_[v] = open;
    }
  }

  // Whether the undecided v is now decided; if so marks it and stacks it for settle().
  bool try_decide(int v) {
    const double margin = keep_cost_[v] - switch_cost_[v];
    unsigned char side = kFree;
    if (margin > undecided_[v]) {
      side = kSwitch;
    } else if (-margin > undecided_[v] + (anchored_[labels_[v]] ? 0.0 : problem_.label_cost[labels_[v]])) {
      side = kKeep;
      anchored_[labels_[v]] = 1;
    }
    if (side == kFree) return false;
    state_[v] = side;
    if (side == kSwitch) changed_.push_back(v);
    stack_.push_back(v);
    return true;
  }

  // Passes each stacked decided vertex's edges on to its undecided neighbours, deciding them in
  // turn when they can be.
  void settle() {
    while (!stack_.empty()) {
      const int v = stack_.back();
      stack_.pop_back();
      const bool switches = state_[v] == kSwitch;
      const int lv = switches ? -1 : labels_[v];
      for (int a = offsets_[v]; a < offsets_[v + 1]; ++a) {
        const int u = neighbour_[a];
        if (state_[u] != kFree) continue;
        const double w = weight_[a];
        undecided_[u] -= w;
        if (switches) {
          keep_cost_[u] += w;  // v ends alpha: u pays w if it keeps
        } else {
          switch_cost_[u] += w;  // v keeps its label: u pays w if it switches ...
          if (lv != labels_[u]) keep_cost_[u] += w;  // ... and if it keeps a different label
        }
        try_decide(u);
      }
    }
  }

  // cut_[v]: weight of v's edges to vertices of another label.
  void update_cut(int v) {
    double c = 0.0;
    for (int a = offsets_[v]; a < offsets_[v + 1]; ++a)
      if (labels_[neighbour_[a]] != labels_[v]) c += weight_[a];
    cut_[v] = c;
  }

  const LabelingProblem& problem_;
  const bool reduce_;
  std::vector<int> labels_, counts_;
  double energy_ = 0.0;
  std::vector<double> current_cost_;      // D(v, l_v)
  std::vector<int> offsets_, neighbour_;  // adjacency of the positive-weight edges
  std::vector<double> weight_, weight_sum_, cut_;
  MaxFlow flow_{0};
  std::vector<unsigned char> state_, anchored_;
  std::vector<double> switch_cost_, keep_cost_, undecided_, label_margin_;
  std::vector<int> node_of_, aux_of_, changed_, stack_, free_, pending_;
};

}  // namespace

bool LabelingProblem::valid(std::string* why) const {
  auto fail = [&](const std::string& what) {
    if (why) *why = what;
    return false;
  };
  const int n = vertex_count(), labels = label_count();
  if (labels < 1 && n > 0) return fail("data_cost has no label columns");
  if (!data_cost.allFinite()) return fail("data_cost has a non-finite entry");
  if (label_cost.size() != labels)
    return fail("label_cost has " + std::to_string(label_cost.size()) + " entries for " +
                std::to_string(labels) + " labels");
  for (int a = 0; a < labels; ++a)
    if (!(std::isfinite(label_cost[a]) && label_cost[a] >= 0.0))
      return fail("label_cost[" + std::to_string(a) + "] must be finite and >= 0");
  if (edge_weights.size() != edges.size())
    return fail(std::to_string(edge_weights.size()) + " edge weights for " +
                std::to_string(edges.size()) + " edges");
  for (std::size_t e = 0; e < edges.size(); ++e) {
    const auto [u, v] = edges[e];
    if (u < 0 || u >= n || v < 0 || v >= n)
      return fail("edge " + std::to_string(e) + " (" + std::to_string(u) + ", " +
                  std::to_string(v) + ") has a vertex outside 0.." + std::to_string(n - 1));
    if (u == v) return fail("edge " + std::to_string(e) + " is a self-loop");
    if (!(std::isfinite(edge_weights[e]) && edge_weights[e] >= 0.0))
      return fail("edge weight " + std::to_string(e) + " must be finite and >= 0");
  }
  return true;
}

LabelingEnergy labeling_energy_terms(const LabelingProblem& problem,
                                     const std::vector<int>& labels) {
  check_labels(problem, labels);
  LabelingEnergy energy;
  std::vector<char> used(problem.label_count(), 0);
  for (std::size_t v = 0; v < labels.size(); ++v) {
    energy.data += problem.data_cost(static_cast<Eigen::Index>(v), labels[v]);
    used[labels[v]] = 1;
  }
  for (std::size_t e = 0; e < problem.edges.size(); ++e) {
    const auto [u, v] = problem.edges[e];
    if (labels[u] != labels[v]) energy.smoothness += problem.edge_weights[e];
  }
  for (int a = 0; a < problem.label_count(); ++a)
    if (used[a]) energy.label += problem.label_cost[a];
  return energy;
}

double labeling_energy(const LabelingProblem& problem, const std::vector<int>& labels) {
  return labeling_energy_terms(problem, labels).total();
}

bool ExpansionOptions::valid(std::string* why) const {
  if (max_sweeps >= 1) return true;
  if (why) *why = "max_sweeps must be >= 1, got " + std::to_string(max_sweeps);
  return false;
}

ExpansionSummary alpha_expansion(const LabelingProblem& problem, std::vector<int> initial,
                                 const ExpansionOptions& options) {
  std::string why;
  if (!options.valid(&why)) throw Error::usage("alpha_expansion: invalid options: " + why);
  if (!problem.valid(&why)) throw Error::usage("alpha_expansion: invalid problem: " + why);
  check_labels(problem, initial);
  if (!options.known_to_fail.empty() &&
      static_cast<int>(options.known_to_fail.size()) != problem.label_count())
    throw Error::usage("alpha_expansion: known_to_fail has " +
                       std::to_string(options.known_to_fail.size()) + " entries for " +
                       std::to_string(problem.label_count()) + " labels");

  Expander expander(problem, std::move(initial), options.reduce);
  ExpansionSummary summary;
  summary.energy_trace.push_back(expander.energy());
  const int labels = problem.label_count();
  std::vector<int> order(labels);
  // A move is skipped when the labeling has not changed since alpha was last expanded: a failed
  // move would fail again, and after an accepted alpha move every alpha-expansion of the new
  // labeling is also one of the old labeling, which the accepted move already beat. This saves
  // the last, all-rejecting sweep and changes no result.
  std::vector<long> expanded_at(labels, -1);  // accepted_moves when alpha was last expanded
  for (std::size_t a = 0; a < options.known_to_fail.size(); ++a)
    if (options.known_to_fail[a]) expanded_at[a] = 0;
  std::mt19937_64 rng(options.seed);
  while (summary.sweeps < options.max_sweeps) {
    // Fisher-Yates with the raw generator output: the same order on every platform.
    for (int i = 0; i < labels; ++i) order[i] = i;
    for (int i = labels - 1; i > 0; --i)
      std::swap(order[i], order[rng() % static_cast<std::uint64_t>(i + 1)]);
    ++summary.sweeps;
    int accepted = 0;
    for (int alpha : order) {
      if (expanded_at[alpha] == summary.accepted_moves) continue;
      if (expander.expand(alpha)) {
        ++accepted;
        ++summary.accepted_moves;
        summary.energy_trace.push_back(expander.energy());
      }
      expanded_at[alpha] = summary.accepted_moves;
    }
    const bool all_tried = std::all_of(expanded_at.begin(), expanded_at.end(),
                                       [&](long at) { return at == summary.accepted_moves; });
    if (accepted == 0 || all_tried) {
      summary.converged = true;
      break;
    }
  }
  summary.labels = expander.labels();
  summary.energy = labeling_energy(problem, summary.labels);
  return summary;
}

}  // namespace sketchsurf
