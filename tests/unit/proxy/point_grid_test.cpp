// Nearest-point and within-radius queries of PointGrid against a brute-force scan.

#include "surfacing/proxy/point_grid.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace sketchsurf {
namespace {

std::pair<int, double> brute_nearest(const Eigen::MatrixX3d& V, const Eigen::Vector3d& p) {
  std::pair<int, double> best{-1, std::numeric_limits<double>::infinity()};
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    const double d2 = (V.row(i).transpose() - p).squaredNorm();
    if (d2 < best.second) best = {static_cast<int>(i), d2};
  }
  return best;
}

// Points along a few curves (as the strokes the proxy measures distances to), some repeated so
// that ties occur; queries inside, near and far outside their box.
TEST(PointGrid, NearestIsTheBruteForceNearestWithTiesToTheLowerIndex) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  Eigen::MatrixX3d V(900, 3);
  for (Eigen::Index i = 0; i < 600; ++i) {
    const double t = 0.01 * static_cast<double>(i % 200);
    const double k = static_cast<double>(i / 200);
    V.row(i) << std::cos(t + k), std::sin(2.0 * t) * 0.5, 0.3 * k - 0.3 + 0.01 * unit(rng);
  }
  for (Eigen::Index i = 600; i < 900; ++i) V.row(i) = V.row(i - 300);  // duplicates: ties
  const PointGrid grid(V);
  for (int q = 0; q < 2000; ++q) {
    const double reach = q < 1000 ? 1.2 : 4.0;
    const Eigen::Vector3d p(reach * unit(rng), reach * unit(rng), reach * unit(rng));
    const auto expected = brute_nearest(V, p);
    const auto got = grid.nearest(p);
    EXPECT_EQ(got.first, expected.first) << "query " << q;
    EXPECT_EQ(got.second, expected.second) << "query " << q;
    // With a limit: the nearest point whenever it is within the limit, else none or a farther one.
    const double limit = 0.2;
    const auto limited = grid.nearest(p, limit);
    if (std::sqrt(expected.second) <= limit) {
      EXPECT_EQ(limited, expected) << "query " << q;
    } else if (limited.first >= 0) {
      EXPECT_GT(std::sqrt(limited.second), limit) << "query " << q;
    }
    // Some point within a radius, whatever the radius against the cells (smaller, about one, many).
    for (const double radius : {0.01, 0.05, 0.2, 1.5}) {
      EXPECT_EQ(grid.any_within(p, radius), expected.second <= radius * radius)
          << "query " << q << " radius " << radius;
      // finds_within: what the limited search says, and true for every point within the radius.
      const bool finds = grid.finds_within(p, radius);
      EXPECT_EQ(finds, grid.nearest(p, radius).first >= 0) << "query " << q << " radius " << radius;
      if (expected.second <= radius * radius) {
        EXPECT_TRUE(finds) << "query " << q << " radius " << radius;
      }
    }
  }

  // A query exactly on a duplicated point: the lower index, at distance 0.
  const auto on = grid.nearest(V.row(700).transpose());
  EXPECT_EQ(on.first, 400);
  EXPECT_EQ(on.second, 0.0);
}

// Two points at exactly the same distance in different cells: the lower index wins whichever
// cell is searched first.
TEST(PointGrid, EqualDistancesGoToTheLowerIndex) {
  Eigen::MatrixX3d V(402, 3);
  V.row(0) << 0.5, 0.0, 0.0;
  V.row(1) << -0.5, 0.0, 0.0;
  for (Eigen::Index i = 2; i < V.rows(); ++i)  // a dense line far away: small cells
    V.row(i) << -1.0 + 0.005 * static_cast<double>(i), 2.0, 2.0;
  const PointGrid grid(V);
  const auto got = grid.nearest(Eigen::Vector3d::Zero());
  EXPECT_EQ(got.first, 0);
  EXPECT_EQ(got.second, 0.25);
  // A point exactly at the radius counts as within it.
  EXPECT_TRUE(grid.any_within(Eigen::Vector3d::Zero(), 0.5));
  EXPECT_FALSE(grid.any_within(Eigen::Vector3d::Zero(), 0.4999));
}

}  // namespace
}  // namespace sketchsurf
