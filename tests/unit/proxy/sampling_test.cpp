// Stroke sampling: count, even coverage, ignored strokes, determinism.

#include "surfacing/proxy/sampling.h"

#include <gtest/gtest.h>

#include "surfacing/error.h"
#include "tests/support/shapes.h"

namespace sketchsurf {
namespace {

double min_pairwise(const Eigen::MatrixX3d& x) {
  double m = 1e300;
  for (Eigen::Index i = 0; i < x.rows(); ++i)
    for (Eigen::Index j = i + 1; j < x.rows(); ++j) m = std::min(m, (x.row(i) - x.row(j)).norm());
  return m;
}

TEST(Sampling, EvenCoverageOfEveryStroke) {
  const Sketch sketch = testing::cube_sketch(1.0);
  SamplingOptions options;
  options.count = 300;
  const Eigen::MatrixX3d x = sample_strokes(sketch, options);
  ASSERT_EQ(x.rows(), 300);
  // Every stroke point has a sample nearby, and no two samples are much closer than that.
  double cover = 0;
  for (const auto& s : sketch.strokes)
    for (const auto& p : s.points)
      cover = std::max(cover, (x.rowwise() - p.transpose()).rowwise().norm().minCoeff());
  EXPECT_LT(cover, 2.5 * min_pairwise(x));
  EXPECT_EQ(x, sample_strokes(sketch, options));  // deterministic
}

TEST(Sampling, IgnoredStrokesAreNotSampledAndShortSketchesGiveFewerPoints) {
  Sketch sketch = testing::sphere_sketch(0.5, 2);
  Stroke far;
  far.points = {Eigen::Vector3d(5, 5, 5), Eigen::Vector3d(6, 6, 6)};
  far.ignored = true;
  sketch.strokes.push_back(far);
  SamplingOptions options;
  options.count = 100000;
  const Eigen::MatrixX3d x = sample_strokes(sketch, options);
  EXPECT_LT(x.rows(), 100000);
  EXPECT_LT(x.rowwise().norm().maxCoeff(), 0.5 + 1e-9);
  Sketch empty;
  EXPECT_THROW(sample_strokes(empty, {}), Error);
}

}  // namespace
}  // namespace sketchsurf
