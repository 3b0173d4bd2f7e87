#include "surfacing/proxy/misfit.h"

#include <algorithm>
#include <cmath>

#include "surfacing/parallel.h"
#include "surfacing/proxy/point_grid.h"

namespace sketchsurf {

double shared_misfit(const HermiteRbf& f, const Eigen::MatrixX3d& points,
                     const std::vector<int>& stroke_of, double reach, unsigned threads) {
  const auto n = static_cast<std::size_t>(points.rows());
  if (n == 0) return 0.0;
  std::vector<double> misfit(n);
  parallel_for(0, n, threads, [&](std::size_t i) {
    Eigen::Vector3d g;
    const double v = f.value_gradient(points.row(static_cast<Eigen::Index>(i)).transpose(), &g);
    misfit[i] = v / std::max(g.norm(), 1e-12);
  });
  // Per point, the weighted mean misfit of the other strokes' points within reach (NaN: none).
  const PointGrid grid(points);
  const double r2 = reach * reach;
  std::vector<double> shared(n);
  parallel_for(0, n, threads, [&](std::size_t i) {
    double sum = 0.0, weight = 0.0;
    grid.for_each_within(points.row(static_cast<Eigen::Index>(i)).transpose(), reach,
                         [&](int j, double d2) {
                           if (stroke_of[static_cast<std::size_t>(j)] == stroke_of[i]) return;
                           const double u = 1.0 - d2 / r2, w = u * u;
                           sum += w * misfit[static_cast<std::size_t>(j)];
                           weight += w;
                         });
    shared[i] = weight > 0.0 ? sum / weight : std::nan("");
  });
  double own_shared = 0.0, own = 0.0, others = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (std::isnan(shared[i])) continue;
    own_shared += misfit[i] * shared[i];
    own += misfit[i] * misfit[i];
    others += shared[i] * shared[i];
  }
  return own > 0.0 && others > 0.0 ? own_shared / std::sqrt(own * others) : 0.0;
}

}  // namespace sketchsurf
