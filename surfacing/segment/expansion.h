#pragma once
// Multi-label energy minimisation by alpha-expansion with label costs (Delong, Osokin, Isack,
// Boykov 2012), the labeling step of PEARL (paper §4.2, Algorithm 1 step 1; METHOD.md section 4).
//
// API notes:
// - E(l) = sum_v D(v, l_v) + sum_e w_e [l_u != l_v] + sum_{labels a in use} h_a (Potts pairwise).
//   Units are the caller's (the pipeline passes E_fidelity per vertex, w_smooth w_e / W and
//   w_simp dim(theta_a) / 35). Data costs may be any finite numbers; the 2-approximation bound
//   below needs them >= 0.
// - alpha_expansion expands every label (unused ones too: PEARL's candidate models) once per sweep,
//   in a seeded random order, and accepts a move only if the total energy strictly drops, so the
//   energy never increases. It stops once no label can improve the current labeling (moves whose
//   outcome is known, because the labeling did not change since that label's last expansion, are
//   skipped) or after max_sweeps.
//   At convergence E(l) <= 2 (D + S)(l*) + H(l*) + H(l) for the global minimum l* (Boykov et al.
//   2001 with Delong et al.'s label-cost term; H = label costs).
// - Deterministic for a seed (single-threaded). Cost per move: a linear pass over the vertices,
//   then one max-flow on the vertices whose side the move's binary problem does not already decide
//   (persistency: a vertex whose data and decided-edge terms outweigh all its other edges, and the
//   label cost at stake, takes that side in every minimiser), plus one node per other used label
//   with h > 0 that the move might empty (a label whose vertices all switching would cost more
//   than its label cost saves is anchored first, as a whole). The result is the cut of the full
//   graph (ExpansionOptions::reduce = false cuts the full graph, the tests' reference); on PEARL's
//   problems the graph left is a fraction of the vertices (chair, 6860 vertices: 1089 on average,
//   1694 without the whole-label anchor; 11-2-2: 590, 625 without).
// - Throws sketchsurf::Error (Usage) for inconsistent shapes (data_cost rows != labels' size, edge
//   out of range or a self-loop, weights/label costs negative or not finite, non-finite data costs,
//   an initial label out of range, known_to_fail neither empty nor one entry per label) and
//   invalid options.

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace sketchsurf {

/// A multi-label problem: E(l) = sum_v D(v, l_v) + sum_e w_e [l_u != l_v] + sum_{used a} h_a.
struct LabelingProblem {
  Eigen::MatrixXd data_cost;              // #V x #L, finite
  std::vector<std::array<int, 2>> edges;  // undirected vertex pairs, u != v
  std::vector<double> edge_weights;       // one per edge, >= 0 (already multiplied by w_smooth/W)
  Eigen::VectorXd label_cost;             // #L, >= 0 (h_a)

  int vertex_count() const { return static_cast<int>(data_cost.rows()); }
  int label_count() const { return static_cast<int>(data_cost.cols()); }
  /// Checks shapes and values; on failure says what is wrong in *why (if not null).
  bool valid(std::string* why) const;
};

/// The three parts of E(l).
struct LabelingEnergy {
  double data = 0.0;
  double smoothness = 0.0;
  double label = 0.0;
  double total() const { return data + smoothness + label; }
};

/// E(l) for labels (#V entries in [0, #L)). Throws sketchsurf::Error (Usage) on bad shapes.
double labeling_energy(const LabelingProblem& problem, const std::vector<int>& labels);
/// E(l) split into its data, smoothness and label-cost parts.
LabelingEnergy labeling_energy_terms(const LabelingProblem& problem, const std::vector<int>& labels);

struct ExpansionOptions {
  int max_sweeps = 10;       // full passes over the labels (>= 1)
  std::uint64_t seed = 123;  // order in which labels are expanded (public code: seed 123)
  std::vector<char> known_to_fail;  // per label (or empty): 1 if its expansion of `initial` is
                                   // known not to lower E (the caller ran that very move), so it
                                   // is skipped until a move is accepted (same result)
  bool reduce = true;        // decide what persistency decides before each cut (same labels,
                             // much smaller graphs); false cuts the whole graph (tests' reference)
  bool valid(std::string* why) const;
};

struct ExpansionSummary {
  std::vector<int> labels;            // #V final labels
  double energy = 0.0;                // E(labels)
  int sweeps = 0;                     // sweeps run
  int accepted_moves = 0;             // expansions that lowered the energy
  bool converged = false;             // no expansion move improves the final labeling
  std::vector<double> energy_trace;   // E before any move, then after each accepted move
};

/// Alpha-expansion with label costs (Delong et al. 2012), accepting a move only if E drops.
/// initial: #V labels in [0, #L). Throws sketchsurf::Error (Usage) as listed above.
ExpansionSummary alpha_expansion(const LabelingProblem& problem, std::vector<int> initial,
                                 const ExpansionOptions& options = {});

}  // namespace sketchsurf
