#include "surfacing/segment/expansion.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "surfacing/error.h"
#include "tests/support/shapes.h"

namespace sketchsurf {
namespace {

LabelingProblem random_problem(std::mt19937& rng, int vertices, int labels, bool label_costs) {
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  LabelingProblem p;
  p.data_cost.resize(vertices, labels);
  for (int v = 0; v < vertices; ++v)
    for (int a = 0; a < labels; ++a) p.data_cost(v, a) = 2.0 * uniform(rng);
  for (int u = 0; u < vertices; ++u)
    for (int v = u + 1; v < vertices; ++v)
      if (uniform(rng) < 0.5) {
        p.edges.push_back({u, v});
        p.edge_weights.push_back(uniform(rng) < 0.2 ? 0.0 : uniform(rng));
      }
  p.label_cost = Eigen::VectorXd::Zero(labels);
  if (label_costs)
    for (int a = 0; a < labels; ++a) p.label_cost[a] = uniform(rng) < 0.2 ? 0.0 : 2.0 * uniform(rng);
  return p;
}

// Calls fn(labels) for every labeling of `vertices` vertices with `labels` labels.
template <class Fn>
void for_each_labeling(int vertices, int labels, Fn&& fn) {
  std::vector<int> l(vertices, 0);
  while (true) {
    fn(l);
    int i = 0;
    while (i < vertices && ++l[i] == labels) l[i++] = 0;
    if (i == vertices) return;
  }
}

TEST(Expansion, EnergyTermsMatchTheDefinition) {
  LabelingProblem p;
  p.data_cost.resize(3, 2);
  p.data_cost << 1, 2, 3, 4, 5, 6;
  p.edges = {{0, 1}, {1, 2}, {0, 2}};
  p.edge_weights = {0.5, 0.25, 2.0};
  p.label_cost = Eigen::Vector2d(10.0, 20.0);
  const LabelingEnergy e = labeling_energy_terms(p, {0, 1, 0});
  EXPECT_DOUBLE_EQ(e.data, 1 + 4 + 5);
  EXPECT_DOUBLE_EQ(e.smoothness, 0.5 + 0.25);
  EXPECT_DOUBLE_EQ(e.label, 30.0);
  EXPECT_DOUBLE_EQ(labeling_energy(p, {1, 1, 1}), 2 + 4 + 6 + 20);
}

// Against exhaustive search on tiny problems: the result is a local minimum for every expansion
// move (checked by enumerating all moves), never above the initial energy, within the
// approximation bound E <= 2 (D + S)(l*) + H(l*) + H(l), and the energy drops move by move.
TEST(Expansion, MatchesExhaustiveSearchOnTinyProblems) {
  std::mt19937 rng(7);
  int optimal = 0, trials = 0;
  for (bool label_costs : {false, true})
    for (int trial = 0; trial < 60; ++trial, ++trials) {
      const int vertices = 5 + trial % 3, labels = 3;
      const LabelingProblem p = random_problem(rng, vertices, labels, label_costs);
      std::vector<int> initial(vertices);
      for (int& l : initial) l = std::uniform_int_distribution<int>(0, labels - 1)(rng);

      ExpansionOptions options;
      options.max_sweeps = 100;
      options.seed = trial;
      const ExpansionSummary s = alpha_expansion(p, initial, options);
      ASSERT_TRUE(s.converged);
      EXPECT_NEAR(s.energy, labeling_energy(p, s.labels), 1e-12);
      EXPECT_LE(s.energy, labeling_energy(p, initial));
      ASSERT_EQ(s.energy_trace.size(), static_cast<std::size_t>(s.accepted_moves) + 1);
      EXPECT_DOUBLE_EQ(s.energy_trace.front(), labeling_energy(p, initial));
      for (std::size_t i = 1; i < s.energy_trace.size(); ++i)
        EXPECT_LT(s.energy_trace[i], s.energy_trace[i - 1]);

      LabelingEnergy best{0, 0, std::numeric_limits<double>::infinity()};
      for_each_labeling(vertices, labels, [&](const std::vector<int>& l) {
        const LabelingEnergy e = labeling_energy_terms(p, l);
        if (e.total() < best.total()) best = e;
      });
      const double bound = 2.0 * (best.data + best.smoothness) + best.label +
                           labeling_energy_terms(p, s.labels).label;
      EXPECT_LE(s.energy, bound + 1e-12) << "trial " << trial;
      if (s.energy <= best.total() + 1e-12) ++optimal;

      // No expansion move from the result lowers the energy.
      for (int alpha = 0; alpha < labels; ++alpha)
        for (unsigned mask = 0; mask < (1u << vertices); ++mask) {
          std::vector<int> moved = s.labels;
          for (int v = 0; v < vertices; ++v)
            if (mask >> v & 1u) moved[v] = alpha;
          ASSERT_GE(labeling_energy(p, moved), s.energy - 1e-12)
              << "trial " << trial << ": expansion of " << alpha << " still improves";
        }
    }
  // Expansion is near-optimal in practice: most tiny problems reach the global minimum.
  EXPECT_GE(optimal, trials * 3 / 4);
}

TEST(Expansion, CostlyLabelVanishes) {
  // Vertex 3 prefers label 1 by 1.0, everybody else prefers label 0 by 4.0; no edges.
  LabelingProblem p;
  p.data_cost.resize(4, 2);
  p.data_cost << 1, 5, 1, 5, 1, 5, 1, 0;
  p.label_cost = Eigen::Vector2d(0.0, 2.0);
  const ExpansionSummary costly = alpha_expansion(p, {0, 0, 0, 1});
  EXPECT_EQ(costly.labels, (std::vector<int>{0, 0, 0, 0}));  // 4 < 3 + 2
  EXPECT_DOUBLE_EQ(costly.energy, 4.0);
  p.label_cost[1] = 0.5;
  const ExpansionSummary cheap = alpha_expansion(p, {0, 0, 0, 0});
  EXPECT_EQ(cheap.labels, (std::vector<int>{0, 0, 0, 1}));  // 3 + 0.5 < 4
  EXPECT_DOUBLE_EQ(cheap.energy, 3.5);
}

TEST(Expansion, LabelCostRemovesALabelOnlyAsAWhole) {
  // Both vertices prefer label 1 by 0.2 each, but label 1 costs 1.0: switching one vertex alone
  // raises the energy (2.6 -> 2.8), switching both lowers it (2.6 -> 2.0). Only the auxiliary-node
  // construction sees that.
  LabelingProblem p;
  p.data_cost.resize(2, 2);
  p.data_cost << 1.0, 0.8, 1.0, 0.8;
  p.label_cost = Eigen::Vector2d(0.0, 1.0);
  const ExpansionSummary s = alpha_expansion(p, {1, 1});
  EXPECT_EQ(s.labels, (std::vector<int>{0, 0}));
  EXPECT_DOUBLE_EQ(s.energy, 2.0);
  EXPECT_EQ(s.accepted_moves, 1);
}

TEST(Expansion, SmoothnessFollowsWeakEdges) {
  // A chain of 10 vertices with noisy data favouring label 0 on the left half and 1 on the right;
  // strong edges everywhere except a weak one in the middle: the cut lands on the weak edge.
  LabelingProblem p;
  const int n = 10;
  p.data_cost.resize(n, 2);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> noise(0.0, 0.6);
  for (int v = 0; v < n; ++v) {
    const bool left = v < 6;  // the weak edge is (5, 6)
    p.data_cost(v, 0) = (left ? 0.0 : 1.0) + noise(rng);
    p.data_cost(v, 1) = (left ? 1.0 : 0.0) + noise(rng);
  }
  for (int v = 0; v + 1 < n; ++v) {
    p.edges.push_back({v, v + 1});
    p.edge_weights.push_back(v == 5 ? 0.01 : 5.0);
  }
  p.label_cost = Eigen::Vector2d(0.1, 0.1);
  const ExpansionSummary s = alpha_expansion(p, std::vector<int>(n, 0));
  for (int v = 0; v < n; ++v) EXPECT_EQ(s.labels[v], v < 6 ? 0 : 1) << v;
}

// A PEARL-like problem on a side x side triangulated grid: `cells` Voronoi cells, one label fitting
// each cell, plus near-copies of those labels, labels fitting two neighbouring cells (merges) and
// labels fitting nothing well; a third of the vertices have no data (cost 0 for every label, like
// proxy vertices without stroke points); small, uneven edge weights; label costs that matter.
LabelingProblem pearl_like_problem(std::mt19937& rng, int side, int cells) {
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const int n = side * side;
  std::vector<double> cx(cells), cy(cells);
  for (int c = 0; c < cells; ++c) cx[c] = side * uniform(rng), cy[c] = side * uniform(rng);
  std::vector<int> cell(n);
  for (int v = 0; v < n; ++v) {
    const double x = v % side, y = v / side;
    int best = 0;
    for (int c = 1; c < cells; ++c)
      if (std::hypot(x - cx[c], y - cy[c]) < std::hypot(x - cx[best], y - cy[best])) best = c;
    cell[v] = best;
  }
  const int labels = 4 * cells;
  LabelingProblem p;
  p.data_cost.resize(n, labels);
  for (int v = 0; v < n; ++v) {
    const bool no_data = uniform(rng) < 0.33;
    for (int a = 0; a < labels; ++a) {
      const int c = a % cells, kind = a / cells;
      bool fits = cell[v] == c;
      if (kind == 2) fits = fits || cell[v] == (c + 1) % cells;  // a merge
      if (kind == 3) fits = false;                               // fits nothing
      const double cost = (fits ? 0.02 : 1.0) * (0.5 + uniform(rng));
      p.data_cost(v, a) = no_data ? 0.0 : kind == 1 ? 1.05 * cost : cost;
    }
  }
  auto add = [&](int u, int v) {
    p.edges.push_back({u, v});
    p.edge_weights.push_back((cell[u] == cell[v] ? 0.05 : 0.005) * (0.5 + uniform(rng)));
  };
  for (const auto& [u, v] : testing::triangulated_grid_edges(side)) add(u, v);
  p.label_cost.resize(labels);
  for (int a = 0; a < labels; ++a) p.label_cost[a] = 0.05 + 0.3 * uniform(rng);
  return p;
}

// Deciding vertices and whole labels by persistency before each cut is exact: the same labels,
// moves and energies as cutting the full graph (Delong et al.'s construction on every vertex).
TEST(Expansion, PersistencyReductionGivesTheSameLabelsAsTheFullCut) {
  std::mt19937 rng(5);
  for (int trial = 0; trial < 12; ++trial) {
    const bool pearl_like = trial % 2 == 0;
    const LabelingProblem p = pearl_like ? pearl_like_problem(rng, 24, 4 + trial % 5)
                                         : random_problem(rng, 30, 5, trial % 4 != 1);
    std::vector<int> initial(p.vertex_count(), 0);
    if (trial % 3 == 0)
      for (int& l : initial) l = std::uniform_int_distribution<int>(0, p.label_count() - 1)(rng);
    ExpansionOptions reduced, full;
    reduced.seed = full.seed = 100 + trial;
    full.reduce = false;
    const ExpansionSummary a = alpha_expansion(p, initial, reduced);
    const ExpansionSummary b = alpha_expansion(p, initial, full);
    ASSERT_EQ(a.labels, b.labels) << "trial " << trial;
    EXPECT_EQ(a.accepted_moves, b.accepted_moves) << "trial " << trial;
    ASSERT_EQ(a.energy_trace.size(), b.energy_trace.size()) << "trial " << trial;
    for (std::size_t i = 0; i < a.energy_trace.size(); ++i)
      EXPECT_NEAR(a.energy_trace[i], b.energy_trace[i], 1e-12) << "trial " << trial;
    EXPECT_GT(a.accepted_moves, 0) << "trial " << trial;  // the problems are not trivial
  }
}

// Label 1 holds vertices 3 and 4 of a chain, each better there than label 0 by g: keeping it costs
// its cut (2 edges of 0.1) and its label cost 0.1, so it survives only if 2 g > 0.2. Neither vertex
// alone outweighs its edges and that label cost (g <= 0.2), so only the whole-label anchor
// (2 g - 0.2 > 0.1 for g = 0.15) decides it before the cut; either way the result is the full cut's.
TEST(Expansion, WholeLabelAnchorMatchesTheFullCut) {
  for (double g : {0.09, 0.15}) {
    LabelingProblem p;
    const int n = 8;
    p.data_cost.resize(n, 2);
    for (int v = 0; v < n; ++v) p.data_cost.row(v) << 1.0, (v == 3 || v == 4) ? 1.0 - g : 2.0;
    for (int v = 0; v + 1 < n; ++v) {
      p.edges.push_back({v, v + 1});
      p.edge_weights.push_back(0.1);
    }
    p.label_cost = Eigen::Vector2d(0.1, 0.1);
    std::vector<int> initial(n, 0);
    initial[3] = initial[4] = 1;
    ExpansionOptions full;
    full.reduce = false;
    const ExpansionSummary a = alpha_expansion(p, initial);
    const ExpansionSummary b = alpha_expansion(p, initial, full);
    EXPECT_EQ(a.labels, b.labels) << g;
    EXPECT_DOUBLE_EQ(a.energy, b.energy) << g;
    std::vector<int> expected(n, 0);
    if (g > 0.1) expected = initial;
    EXPECT_EQ(a.labels, expected) << g;
  }
}

// Labels marked known_to_fail (PEARL's labels of the previous step, when their moves failed on the
// same binary problems) are skipped until a move is accepted: marking labels that do fail changes
// nothing; a wrong-sized mark list is rejected.
TEST(Expansion, SkipsLabelsKnownToFailWithTheSameResult) {
  std::mt19937 rng(9);
  for (int trial = 0; trial < 6; ++trial) {
    const LabelingProblem p = pearl_like_problem(rng, 20, 5);
    ExpansionOptions options;
    options.seed = trial;
    // A converged labeling: every label's expansion from it fails.
    const ExpansionSummary first = alpha_expansion(p, std::vector<int>(p.vertex_count(), 0), options);
    ASSERT_TRUE(first.converged);
    for (int mark = 0; mark < 2; ++mark) {
      ExpansionOptions marked = options;
      marked.seed = 50 + trial;
      marked.known_to_fail.assign(p.label_count(), 0);
      for (int a = 0; a < p.label_count(); ++a) marked.known_to_fail[a] = mark == 1 || a % 2 == 0;
      const ExpansionSummary again = alpha_expansion(p, first.labels, marked);
      EXPECT_EQ(again.labels, first.labels) << trial;
      EXPECT_EQ(again.accepted_moves, 0) << trial;
      EXPECT_TRUE(again.converged) << trial;
    }
    // From a labeling that is not converged: labels worse than every other label on every vertex
    // by more than all edge weights (appended copies) fail from any labeling; marking them
    // changes nothing.
    LabelingProblem q = p;
    const int L = p.label_count();
    q.data_cost.conservativeResize(Eigen::NoChange, 2 * L);
    q.label_cost.conservativeResize(2 * L);
    for (int a = 0; a < L; ++a) {
      q.data_cost.col(L + a) = p.data_cost.col(a).array() + p.data_cost.maxCoeff() + 10.0;
      q.label_cost[L + a] = p.label_cost[a];
    }
    const std::vector<int> start(q.vertex_count(), 0);
    ExpansionOptions reference = options;
    reference.seed = 70 + trial;
    ExpansionOptions marked = reference;
    marked.known_to_fail.assign(2 * L, 0);
    for (int a = L; a < 2 * L; ++a) marked.known_to_fail[a] = 1;
    const ExpansionSummary a = alpha_expansion(q, start, reference);
    const ExpansionSummary b = alpha_expansion(q, start, marked);
    EXPECT_GT(a.accepted_moves, 0) << trial;
    EXPECT_EQ(a.labels, b.labels) << trial;
    EXPECT_NEAR(a.energy, b.energy, 1e-12) << trial;
  }
  const LabelingProblem p = pearl_like_problem(rng, 6, 2);
  ExpansionOptions bad;
  bad.known_to_fail.assign(p.label_count() + 1, 0);
  EXPECT_THROW(alpha_expansion(p, std::vector<int>(p.vertex_count(), 0), bad), Error);
}

TEST(Expansion, DeterministicForASeed) {
  std::mt19937 rng(11);
  const LabelingProblem p = random_problem(rng, 40, 6, true);
  const std::vector<int> initial(40, 0);
  ExpansionOptions options;
  const ExpansionSummary a = alpha_expansion(p, initial, options);
  const ExpansionSummary b = alpha_expansion(p, initial, options);
  EXPECT_EQ(a.labels, b.labels);
  EXPECT_EQ(a.energy_trace, b.energy_trace);
}

TEST(Expansion, RejectsBadInput) {
  LabelingProblem p;
  p.data_cost = Eigen::MatrixXd::Zero(3, 2);
  p.label_cost = Eigen::Vector2d(0.0, 0.0);
  p.edges = {{0, 1}};
  p.edge_weights = {1.0};
  EXPECT_NO_THROW(alpha_expansion(p, {0, 0, 0}));
  EXPECT_THROW(alpha_expansion(p, {0, 0}), Error);     // wrong count
  EXPECT_THROW(alpha_expansion(p, {0, 2, 0}), Error);  // label out of range
  ExpansionOptions bad_options;
  bad_options.max_sweeps = 0;
  EXPECT_THROW(alpha_expansion(p, {0, 0, 0}, bad_options), Error);
  std::string why;
  LabelingProblem q = p;
  q.edges = {{0, 3}};
  EXPECT_FALSE(q.valid(&why));
  EXPECT_NE(why.find("edge 0"), std::string::npos) << why;
  q = p;
  q.edge_weights = {-1.0};
  EXPECT_THROW(alpha_expansion(q, {0, 0, 0}), Error);
  q = p;
  q.label_cost = Eigen::Vector3d(0, 0, 0);
  EXPECT_THROW(alpha_expansion(q, {0, 0, 0}), Error);
  q = p;
  q.data_cost(1, 1) = std::numeric_limits<double>::infinity();
  try {
    alpha_expansion(q, {0, 0, 0});
    FAIL() << "no exception";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Usage);
    EXPECT_NE(std::string(e.what()).find("non-finite"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sketchsurf
