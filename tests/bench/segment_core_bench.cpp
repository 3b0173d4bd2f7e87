// Segmentation core at pipeline scale: alpha-expansion sweeps and spectral clustering on a
// ~30k-vertex triangulated grid graph, implicit fits of degree 1-4.
// Run: segment_core_bench [--benchmark_filter=...]; peak RSS with /usr/bin/time -v.

#include <benchmark/benchmark.h>

#include <Eigen/Core>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "surfacing/segment/expansion.h"
#include "surfacing/segment/implicit.h"
#include "surfacing/segment/spectral.h"
#include "tests/support/shapes.h"

namespace sketchsurf {
namespace {

// side x side grid, each quad split by a diagonal (valence 6 inside, ~3 edges per vertex), cut into
// `regions` Voronoi cells of random seeds; edges between cells get weight 1 ("crossed by a stroke"),
// the others 100 (paper §4.1).
struct GridGraph {
  int side = 0;
  std::vector<std::array<int, 2>> edges;
  std::vector<double> weights;
  std::vector<int> region;
};

std::vector<int> voronoi(int side, int regions, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(0.0, side);
  std::vector<Eigen::Vector2d> seeds(regions);
  for (auto& s : seeds) s = {uniform(rng), uniform(rng)};
  std::vector<int> cell(side * side);
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x) {
      int best = 0;
      for (int r = 1; r < regions; ++r)
        if ((seeds[r] - Eigen::Vector2d(x, y)).squaredNorm() <
            (seeds[best] - Eigen::Vector2d(x, y)).squaredNorm())
          best = r;
      cell[y * side + x] = best;
    }
  return cell;
}

GridGraph grid_graph(int side, int regions) {
  GridGraph g;
  g.side = side;
  g.region = voronoi(side, regions, 1);
  auto add = [&](int a, int b) {
    g.edges.push_back({a, b});
    g.weights.push_back(g.region[a] == g.region[b] ? 100.0 : 1.0);
  };
  for (const auto& [u, v] : testing::triangulated_grid_edges(side)) add(u, v);
  return g;
}

// The pipeline's energy at its scale (METHOD.md section 4): about half the vertices carry stroke
// points whose fidelity cost is low for their region's label and high for the others; smoothness
// w_smooth w_e / W; label cost w_simp dim / 35.
LabelingProblem pipeline_problem(const GridGraph& g, int labels) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  const int n = g.side * g.side;
  LabelingProblem p;
  p.data_cost = Eigen::MatrixXd::Zero(n, labels);
  const double points = n / 2.0;
  for (int v = 0; v < n; ++v) {
    if (uniform(rng) < 0.5) continue;
    for (int a = 0; a < labels; ++a) {
      const double d = a == g.region[v] ? 0.3 * uniform(rng) : 1.0 + 3.0 * uniform(rng);  // in eps
      p.data_cost(v, a) = d * d / points;
    }
  }
  double total = 0.0;
  for (double w : g.weights) total += w;
  p.edges = g.edges;
  for (double w : g.weights) p.edge_weights.push_back(10.0 * w / total);
  p.label_cost.resize(labels);
  for (int a = 0; a < labels; ++a) p.label_cost[a] = 0.01 * (a % 2 ? 10 : 35) / 35.0;
  return p;
}

void BM_ExpansionSweep(benchmark::State& state) {
  const int side = static_cast<int>(state.range(0)), labels = static_cast<int>(state.range(1));
  const GridGraph g = grid_graph(side, labels);
  const LabelingProblem p = pipeline_problem(g, labels);
  const std::vector<int> initial = voronoi(side, labels, 3);  // a different over-segmentation
  ExpansionOptions options;
  options.max_sweeps = 1;
  for (auto _ : state) benchmark::DoNotOptimize(alpha_expansion(p, initial, options));
  state.counters["vertices"] = side * side;
  state.counters["labels"] = labels;
}
BENCHMARK(BM_ExpansionSweep)->Args({100, 30})->Args({174, 30})->Unit(benchmark::kMillisecond);

void BM_ExpansionToConvergence(benchmark::State& state) {
  const int side = static_cast<int>(state.range(0)), labels = static_cast<int>(state.range(1));
  const GridGraph g = grid_graph(side, labels);
  const LabelingProblem p = pipeline_problem(g, labels);
  const std::vector<int> initial = voronoi(side, labels, 3);
  ExpansionSummary s;
  for (auto _ : state) s = alpha_expansion(p, initial);
  state.counters["sweeps"] = s.sweeps;
  state.counters["moves"] = s.accepted_moves;
}
BENCHMARK(BM_ExpansionToConvergence)->Args({174, 30})->Unit(benchmark::kMillisecond);

void BM_SpectralClustering(benchmark::State& state) {
  const int side = static_cast<int>(state.range(0)), k = static_cast<int>(state.range(1));
  const GridGraph g = grid_graph(side, 40);
  for (auto _ : state)
    benchmark::DoNotOptimize(spectral_clustering(side * side, g.edges, g.weights, k, 1));
  state.counters["vertices"] = side * side;
}
BENCHMARK(BM_SpectralClustering)->Args({100, 20})->Args({174, 20})->Args({174, 50})
    ->Unit(benchmark::kMillisecond);

// What PEARL's initialisation does: one eigen solve for k = 50, then k = 20, 30, 40, 50.
void BM_SpectralPreparedAllK(benchmark::State& state) {
  const int side = static_cast<int>(state.range(0));
  const GridGraph g = grid_graph(side, 40);
  for (auto _ : state) {
    const SpectralClustering prepared(side * side, g.edges, g.weights, 50);
    for (int k : {20, 30, 40, 50}) benchmark::DoNotOptimize(prepared.cluster(k, 1));
  }
  state.counters["vertices"] = side * side;
}
BENCHMARK(BM_SpectralPreparedAllK)->Arg(100)->Arg(174)->Unit(benchmark::kMillisecond);

void BM_FitImplicit(benchmark::State& state) {
  const int degree = static_cast<int>(state.range(0)), count = static_cast<int>(state.range(1));
  std::mt19937 rng(4);
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::MatrixX3d points(count, 3), normal_points(count, 3), normals(count, 3);
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector3d a(normal(rng), normal(rng), normal(rng)),
        b(normal(rng), normal(rng), normal(rng));
    points.row(i) = a.normalized().transpose();
    normal_points.row(i) = b.normalized().transpose();
    normals.row(i) = b.normalized().transpose();
  }
  for (auto _ : state)
    benchmark::DoNotOptimize(fit_implicit(degree, points, normal_points, normals));
}
BENCHMARK(BM_FitImplicit)->Args({1, 1000})->Args({2, 1000})->Args({4, 1000})->Args({4, 10000})
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace sketchsurf

BENCHMARK_MAIN();
