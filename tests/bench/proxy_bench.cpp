// Proxy surface speed: VIPSS at 500 / 1000 / 2000 points, and polygonisation + remeshing to a
// ~30,000-vertex proxy, on generated sketches. Compare with the public VIPSS on a 2-core machine:
// 500 points 8.6 s, 1000 points 76.5 s / 0.8 GB, 2000 points 601 s / 2.9 GB (METHOD.md section 1).
// Peak RSS: run one size at a time under /usr/bin/time -v, e.g.
//   /usr/bin/time -v proxy_bench --benchmark_filter='Vipss/2000'

#include <benchmark/benchmark.h>
#include <sys/resource.h>

#include <chrono>

#include "surfacing/parallel.h"
#include "surfacing/proxy/polygonize.h"
#include "surfacing/proxy/proxy.h"
#include "surfacing/proxy/remesh.h"
#include "surfacing/proxy/sampling.h"
#include "surfacing/proxy/vipss.h"
#include "tests/support/shapes.h"

namespace {

using namespace sketchsurf;

// User + system CPU seconds of the whole process (all threads): on a shared machine this is the
// fairer measure next to wall time.
double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

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
  const double cpu0 = cpu_seconds();
  for (auto _ : state) {
    VipssResult r = solve_vipss(x, {});
    last = r.summary;
    benchmark::DoNotOptimize(r.normals.data());
  }
  state.counters["cpu_s"] = (cpu_seconds() - cpu0) / static_cast<double>(state.iterations());
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

// Polygonisation + remeshing of the VIPSS surface of a sphere sketch (1000 samples) at the default
// cell and edge (0.01 and 0.007 of the diagonal): about 28,000 vertices.
void BM_PolygonizeRemesh(benchmark::State& state) {
  Sketch sketch = testing::sphere_sketch(0.5, 4);
  testing::transform(sketch, 1.0 / sketch.bounding_box().diagonal(), Eigen::Vector3d::Zero());
  SamplingOptions sampling;
  sampling.count = 1000;
  const Eigen::MatrixX3d x = sample_strokes(sketch, sampling);
  const VipssResult vipss = solve_vipss(x, {});
  const ProxyOptions defaults;
  BoundingBox box;
  box.extend(Eigen::Vector3d::Constant(-0.4));
  box.extend(Eigen::Vector3d::Constant(0.4));
  const FieldBatch field = [&](const Eigen::MatrixX3d& p, Eigen::VectorXd& v) {
    vipss.function.values(p, v, 0);
  };
  const SurfaceProjector project = [&](Eigen::MatrixX3d& p) {
    parallel_for(0, static_cast<std::size_t>(p.rows()), 0, [&](std::size_t i) {
      Eigen::Vector3d g;
      const Eigen::Vector3d q = p.row(static_cast<Eigen::Index>(i)).transpose();
      const double f = vipss.function.value_gradient(q, &g);
      p.row(static_cast<Eigen::Index>(i)) = (q - f / g.squaredNorm() * g).transpose();
    });
  };
  PolygonizeOptions poly;
  poly.cell_size = defaults.cell;
  RemeshOptions remesh_options;
  remesh_options.target_edge = defaults.edge;
  remesh_options.iterations = defaults.remesh_iterations;
  std::size_t vertices = 0;
  double poly_s = 0;
  const double cpu0 = cpu_seconds();
  for (auto _ : state) {
    const auto t0 = std::chrono::steady_clock::now();
    TriMesh mesh = polygonize(field, x, box, poly);
    poly_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    remesh(mesh, remesh_options, project);
    vertices = mesh.n_vertices();
  }
  state.counters["cpu_s"] = (cpu_seconds() - cpu0) / static_cast<double>(state.iterations());
  state.counters["polygonize_s"] = poly_s;
  state.counters["vertices"] = static_cast<double>(vertices);
}
BENCHMARK(BM_PolygonizeRemesh)->Unit(benchmark::kSecond)->Iterations(1)->Repetitions(3)
    ->ReportAggregatesOnly(true);

}  // namespace

BENCHMARK_MAIN();
