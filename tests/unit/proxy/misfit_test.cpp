// The strokes' shared misfit: tremor (each stroke off the surface on its own) reads near zero,
// a surface rounded off a shape that neighbouring strokes share reads near one.

#include "surfacing/proxy/misfit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

namespace sketchsurf {
namespace {

// The plane z = 0 as a Hermite RBF with no centres: f(x) = z, its misfit exactly z.
HermiteRbf plane_z() {
  return HermiteRbf(Eigen::MatrixX3d(0, 3), Eigen::VectorXd(0), Eigen::MatrixX3d(0, 3),
                    Eigen::Vector4d(0.0, 0.0, 0.0, 1.0));
}

// 21 strokes along x across the unit square, 0.05 apart in y, a point every 0.01; each point
// lifted off the plane by offset(stroke, x, y).
template <typename Offset>
Eigen::MatrixX3d strokes_over_plane(std::vector<int>& stroke_of, Offset offset) {
  std::vector<Eigen::Vector3d> points;
  stroke_of.clear();
  for (int k = 0; k <= 20; ++k)
    for (int i = 0; i <= 100; ++i) {
      const double x = 0.01 * i, y = 0.05 * k;
      points.emplace_back(x, y, offset(k, x, y));
      stroke_of.push_back(k);
    }
  Eigen::MatrixX3d m(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) m.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  return m;
}

TEST(SharedMisfit, AHandsTremorIsNotShared) {
  // Each stroke wobbles on its own: a random phase and amplitude per stroke.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> phase(0.0, 2.0 * std::numbers::pi), amplitude(0.002, 0.006);
  std::vector<double> p(21), a(21);
  for (int k = 0; k < 21; ++k) {
    p[k] = phase(rng);
    a[k] = amplitude(rng);
  }
  std::vector<int> stroke_of;
  const Eigen::MatrixX3d points = strokes_over_plane(stroke_of, [&](int k, double x, double) {
    return a[k] * std::sin(9.0 * x + p[k]);
  });
  const double c = shared_misfit(plane_z(), points, stroke_of, 0.08, 2);
  EXPECT_LT(std::abs(c), 0.3);
}

TEST(SharedMisfit, AShapeRoundedOffIsSharedByNeighbouringStrokes) {
  // The strokes draw a gentle bump that the plane ignores: every stroke near it lies above it,
  // with a little tremor of its own.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> phase(0.0, 2.0 * std::numbers::pi);
  std::vector<double> p(21);
  for (double& v : p) v = phase(rng);
  std::vector<int> stroke_of;
  const Eigen::MatrixX3d points = strokes_over_plane(stroke_of, [&](int k, double x, double y) {
    const double r2 = (x - 0.5) * (x - 0.5) + (y - 0.5) * (y - 0.5);
    return 0.02 * std::exp(-r2 / 0.05) + 0.001 * std::sin(9.0 * x + p[k]);
  });
  const double c = shared_misfit(plane_z(), points, stroke_of, 0.08, 2);
  EXPECT_GT(c, 0.8);
}

TEST(SharedMisfit, TheSameWhateverTheThreadsAndZeroWithoutNeighbours) {
  std::vector<int> stroke_of;
  const Eigen::MatrixX3d points = strokes_over_plane(stroke_of, [](int k, double x, double y) {
    return 0.01 * std::sin(3.0 * x + y) + 0.001 * k;
  });
  EXPECT_EQ(shared_misfit(plane_z(), points, stroke_of, 0.08, 1),
            shared_misfit(plane_z(), points, stroke_of, 0.08, 2));
  // Strokes 0.05 apart have no other stroke's point within 0.04.
  EXPECT_EQ(shared_misfit(plane_z(), points, stroke_of, 0.04, 2), 0.0);
}

}  // namespace
}  // namespace sketchsurf
