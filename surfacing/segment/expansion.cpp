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
class Expander {
 public:
  Expander(const LabelingProblem& problem, std::vector<int> labels)
      : problem_(problem), labels_(std::move(labels)), counts_(problem.label_count(), 0) {
    for (int l : labels_) ++counts_[l];
    energy_ = labeling_energy(problem_, labels_);
  }

  const std::vector<int>& labels() const { return labels_; }
  double energy() const { return energy_; }

  // Expands `alpha`; returns true (and applies the move) if the energy strictly drops.
  bool expand(int alpha) {
    const int n = problem_.vertex_count();
    node_of_.resize(n);
    int nodes = 0;
    for (int v = 0; v < n; ++v) node_of_[v] = labels_[v] == alpha ? -1 : nodes++;
    if (nodes == 0) return false;

    // Unary terms: cost0 = switch to alpha (source side), cost1 = keep the current label.
    cost0_.resize(nodes);
    cost1_.resize(nodes);
    for (int v = 0; v < n; ++v)
      if (node_of_[v] >= 0) {
        cost0_[node_of_[v]] = problem_.data_cost(v, alpha);
        cost1_[node_of_[v]] = problem_.data_cost(v, labels_[v]);
      }
    flow_.clear(nodes);
    // Potts terms w [l_u != l_v] as functions of the two binary variables (0 = alpha, 1 = keep):
    // same labels: w [x_u != x_v]; different labels: w unless both switch, = w x_u + w (1-x_u) x_v.
    for (std::size_t e = 0; e < problem_.edges.size(); ++e) {
      const double w = problem_.edge_weights[e];
      if (w == 0.0) continue;
      const auto [u, v] = problem_.edges[e];
      const int nu = node_of_[u], nv = node_of_[v];
      if (nu < 0 && nv < 0) continue;
      if (nu < 0) {
        cost1_[nv] += w;
      } else if (nv < 0) {
        cost1_[nu] += w;
      } else if (labels_[u] == labels_[v]) {
        flow_.add_edge(nu, nv, w, w);
      } else {
        cost1_[nu] += w;
        flow_.add_edge(nu, nv, w, 0.0);
      }
    }
    // Label costs of the other used labels b (Delong et al. 2012): an auxiliary node y_b paying
    // h_b on the sink side (b survives), and an edge y_b -> v of capacity h_b for every vertex that
    // would keep b, so that the cut pays h_b exactly once unless every vertex of b switches.
    aux_of_.assign(problem_.label_count(), -1);
    for (int b = 0; b < problem_.label_count(); ++b)
      if (b != alpha && counts_[b] > 0 && problem_.label_cost[b] > 0.0) {
        aux_of_[b] = flow_.add_node();
        flow_.add_terminal_weights(aux_of_[b], problem_.label_cost[b], 0.0);
      }
    for (int v = 0; v < n; ++v)
      if (node_of_[v] >= 0 && aux_of_[labels_[v]] >= 0)
        flow_.add_edge(aux_of_[labels_[v]], node_of_[v], problem_.label_cost[labels_[v]], 0.0);
    for (int i = 0; i < nodes; ++i) {
      const double m = std::min(cost0_[i], cost1_[i]);
      flow_.add_terminal_weights(i, cost1_[i] - m, cost0_[i] - m);
    }
    flow_.solve();

    // alpha's own label cost (when alpha was unused) is not in the cut: the exact energy of the
    // proposed labeling decides.
    candidate_ = labels_;
    bool changed = false;
    for (int v = 0; v < n; ++v)
      if (node_of_[v] >= 0 && flow_.on_source_side(node_of_[v])) {
        candidate_[v] = alpha;
        changed = true;
      }
    if (!changed) return false;
    const double candidate_energy = labeling_energy(problem_, candidate_);
    if (!(candidate_energy < energy_)) return false;
    for (int v = 0; v < n; ++v)
      if (candidate_[v] != labels_[v]) {
        --counts_[labels_[v]];
        ++counts_[alpha];
      }
    labels_.swap(candidate_);
    energy_ = candidate_energy;
    return true;
  }

 private:
  const LabelingProblem& problem_;
  std::vector<int> labels_, counts_;
  double energy_ = 0.0;
  MaxFlow flow_{0};
  std::vector<int> node_of_, aux_of_, candidate_;
  std::vector<double> cost0_, cost1_;
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

  Expander expander(problem, std::move(initial));
  ExpansionSummary summary;
  summary.energy_trace.push_back(expander.energy());
  const int labels = problem.label_count();
  std::vector<int> order(labels);
  // A move is skipped when the labeling has not changed since alpha was last expanded: a failed
  // move would fail again, and after an accepted alpha move every alpha-expansion of the new
  // labeling is also one of the old labeling, which the accepted move already beat. This saves
  // the last, all-rejecting sweep and changes no result.
  std::vector<long> expanded_at(labels, -1);  // accepted_moves when alpha was last expanded
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
  summary.energy = expander.energy();
  return summary;
}

}  // namespace sketchsurf
