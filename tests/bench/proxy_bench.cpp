// Proxy surface speed: VIPSS at 500 / 1000 / 2000 points, and polygonisation + remeshing to a
// ~30,000-vertex proxy, on generated sketches. Compare with the public VIPSS on a 2-core machine:
// 500 points 8.6 s, 1000 points 76.5 s / 0.8 GB, 2000 points 601 s / 2.9 GB (METHOD.md section 1).
// Peak RSS: run one size at a time under /usr/bin/time -v, e.g.
//   /usr/bin/time -v proxy_bench --benchmark_filter='Vipss/2000'

#include <benchmark/benchmark.h>

#include "surfacing/proxy/sampling.h"
#include "surfacing/proxy/vipss.h"
#include "tests/support/shapes.h"

namespace {

using namespace sketchsurf;

Eigen::MatrixX3d torus_samples(std::size_t count) {
  Sketch sketch = testing::torus_sketch(0.5, 0.2, 24);
  const double diagonal = sketch.bounding_box().diagonal();
  testing::transform(sketch, 1.0 / diagonal, Eigen::Vector3d::Zero());
  SamplingOptions options;
  options.count = count;
  return sample_strokes(sketch, options);
}

void BM_Vipss(benchmark::State& state) {
  const Eigen::MatrixX3d x = torus_samples(static_cast<std::size_t>(state.range(0)));
  VipssSummary last;
  for (auto _ : state) {
    VipssResult r = solve_vipss(x, {});
    last = r.summary;
    benchmark::DoNotOptimize(r.normals.data());
  }
  state.counters["points"] = static_cast<double>(x.rows());
  state.counters["assemble_s"] = last.assemble_seconds;
  state.counters["factor_s"] = last.factor_seconds;
  state.counters["eigen_s"] = last.eigen_seconds;
  state.counters["optimise_s"] = last.optimise_seconds;
  state.counters["matvecs"] = last.eigen_matvecs;
  state.counters["lbfgs_it"] = last.lbfgs_iterations;
}
BENCHMARK(BM_Vipss)->Arg(500)->Arg(1000)->Arg(2000)->Unit(benchmark::kSecond)->Iterations(1)
    ->Repetitions(3)->ReportAggregatesOnly(true);

}  // namespace

BENCHMARK_MAIN();
