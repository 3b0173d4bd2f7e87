#include "surfacing/segment/maxflow.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "surfacing/error.h"

namespace sketchsurf {
namespace {

struct CutProblem {
  int n = 0;
  std::vector<double> source, sink;
  struct Edge {
    int u, v;
    double uv, vu;
  };
  std::vector<Edge> edges;

  // Cost of the cut where bit v of `source_side` says node v is on the source side.
  double cost(unsigned source_side) const {
    double c = 0.0;
    for (int v = 0; v < n; ++v) c += (source_side >> v & 1u) ? sink[v] : source[v];
    for (const Edge& e : edges) {
      const bool su = source_side >> e.u & 1u, sv = source_side >> e.v & 1u;
      if (su && !sv) c += e.uv;
      if (sv && !su) c += e.vu;
    }
    return c;
  }
  double brute_force_min_cut() const {
    double best = std::numeric_limits<double>::infinity();
    for (unsigned mask = 0; mask < (1u << n); ++mask) best = std::min(best, cost(mask));
    return best;
  }
};

// Random capacity: zero with probability `zero`, else spread over several orders of magnitude.
double random_capacity(std::mt19937& rng, double zero) {
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  if (uniform(rng) < zero) return 0.0;
  return std::pow(10.0, -3.0 + 5.0 * uniform(rng));
}

CutProblem random_problem(std::mt19937& rng) {
  CutProblem p;
  p.n = std::uniform_int_distribution<int>(1, 12)(rng);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const double density = uniform(rng);
  for (int v = 0; v < p.n; ++v) {
    p.source.push_back(random_capacity(rng, 0.4));
    p.sink.push_back(random_capacity(rng, 0.4));
  }
  for (int u = 0; u < p.n; ++u)
    for (int v = u + 1; v < p.n; ++v)
      if (uniform(rng) < density) {
        // Asymmetric, sometimes one-way, sometimes the same pair twice.
        p.edges.push_back({u, v, random_capacity(rng, 0.3), random_capacity(rng, 0.3)});
        if (uniform(rng) < 0.1) p.edges.push_back({v, u, random_capacity(rng, 0.3), 0.0});
      }
  return p;
}

void load(const CutProblem& p, MaxFlow& flow) {
  flow.clear(p.n);
  for (int v = 0; v < p.n; ++v) flow.add_terminal_weights(v, p.source[v], p.sink[v]);
  for (const auto& e : p.edges) flow.add_edge(e.u, e.v, e.uv, e.vu);
}

TEST(MaxFlow, MatchesBruteForceMinCutOnRandomGraphs) {
  std::mt19937 rng(2024);
  MaxFlow flow(0);  // reused across problems through clear()
  for (int trial = 0; trial < 300; ++trial) {
    const CutProblem p = random_problem(rng);
    const double expected = p.brute_force_min_cut();
    const double tolerance = 1e-9 * (1.0 + expected);
    for (MaxFlowSolver solver : {MaxFlowSolver::Native, MaxFlowSolver::Boost}) {
      load(p, flow);
      const double value = flow.solve(solver);
      ASSERT_NEAR(value, expected, tolerance) << "trial " << trial << " n " << p.n;
      unsigned side = 0;
      for (int v = 0; v < p.n; ++v)
        if (flow.on_source_side(v)) side |= 1u << v;
      ASSERT_NEAR(p.cost(side), expected, tolerance)
          << "the reported cut is not minimal, trial " << trial;
    }
  }
}

// Cost of the cut `flow` reports, recomputed from the problem.
double reported_cut_cost(const CutProblem& p, const MaxFlow& flow) {
  double c = 0.0;
  for (int v = 0; v < p.n; ++v) c += flow.on_source_side(v) ? p.sink[v] : p.source[v];
  for (const auto& e : p.edges) {
    const bool su = flow.on_source_side(e.u), sv = flow.on_source_side(e.v);
    if (su && !sv) c += e.uv;
    if (sv && !su) c += e.vu;
  }
  return c;
}

TEST(MaxFlow, AgreesWithBoostOnLargeGridGraphs) {
  // Expansion-like graphs: a 60 x 60 grid with diagonals, random terminal weights and
  // asymmetric edge capacities over six orders of magnitude.
  std::mt19937 rng(99);
  for (int trial = 0; trial < 6; ++trial) {
    CutProblem p;
    const int side = 60;
    p.n = side * side;
    for (int v = 0; v < p.n; ++v) {
      p.source.push_back(random_capacity(rng, 0.5));
      p.sink.push_back(random_capacity(rng, 0.5));
    }
    for (int y = 0; y < side; ++y)
      for (int x = 0; x < side; ++x) {
        const int v = y * side + x;
        auto add = [&](int w, double zero) {
          p.edges.push_back({v, w, random_capacity(rng, zero), random_capacity(rng, zero)});
        };
        if (x + 1 < side) add(v + 1, 0.1);
        if (y + 1 < side) add(v + side, 0.1);
        if (x + 1 < side && y + 1 < side) add(v + side + 1, 0.3);
      }
    MaxFlow ours(0), reference(0);
    load(p, ours);
    load(p, reference);
    const double a = ours.solve(), b = reference.solve(MaxFlowSolver::Boost);
    EXPECT_NEAR(a, b, 1e-9 * b) << "trial " << trial;
    EXPECT_NEAR(reported_cut_cost(p, ours), a, 1e-9 * a);
    EXPECT_NEAR(reported_cut_cost(p, reference), b, 1e-9 * b);
  }
}

TEST(MaxFlow, HandMadeChain) {
  // s -> 0 -> 1 -> 2 -> t with the bottleneck in the middle: cut between 1 and 2.
  MaxFlow flow(3);
  flow.add_terminal_weights(0, 5.0, 0.0);
  flow.add_edge(0, 1, 4.0, 0.0);
  flow.add_edge(1, 2, 0.5, 10.0);
  flow.add_terminal_weights(2, 0.0, 3.0);
  EXPECT_DOUBLE_EQ(flow.solve(), 0.5);
  EXPECT_TRUE(flow.on_source_side(0));
  EXPECT_TRUE(flow.on_source_side(1));
  EXPECT_FALSE(flow.on_source_side(2));
  // Adding a node and solving again.
  const int extra = flow.add_node();
  flow.add_terminal_weights(extra, 2.0, 1.0);
  EXPECT_DOUBLE_EQ(flow.solve(), 1.5);
  EXPECT_TRUE(flow.on_source_side(extra));
}

TEST(MaxFlow, EmptyAndEdgelessGraphs) {
  MaxFlow empty(0);
  EXPECT_EQ(empty.solve(), 0.0);
  MaxFlow terminals(2);
  terminals.add_terminal_weights(0, 1.0, 3.0);
  terminals.add_terminal_weights(1, 2.5, 0.5);
  EXPECT_DOUBLE_EQ(terminals.solve(), 1.5);
  EXPECT_TRUE(terminals.on_source_side(1));
  EXPECT_FALSE(terminals.on_source_side(0));
}

TEST(MaxFlow, RejectsBadInput) {
  MaxFlow flow(2);
  EXPECT_THROW(flow.on_source_side(0), Error);  // before solve()
  EXPECT_THROW(flow.add_terminal_weights(2, 1.0, 1.0), Error);
  EXPECT_THROW(flow.add_terminal_weights(0, -1.0, 1.0), Error);
  EXPECT_THROW(flow.add_edge(0, 1, std::numeric_limits<double>::infinity(), 1.0), Error);
  EXPECT_THROW(flow.add_edge(0, 1, std::nan(""), 1.0), Error);
  EXPECT_THROW(flow.add_edge(1, 1, 1.0, 1.0), Error);
  EXPECT_THROW(MaxFlow(-1), Error);
  try {
    flow.add_edge(0, 5, 1.0, 1.0);
    FAIL() << "no exception";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Usage);
    EXPECT_NE(std::string(e.what()).find("node 5"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace sketchsurf
