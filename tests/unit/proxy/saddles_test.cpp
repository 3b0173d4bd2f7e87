// Saddles of the VIPSS function: a gap between two spheres is bridged only where a stroke runs
// across it.

#include "surfacing/proxy/saddles.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace sketchsurf {
namespace {

constexpr double kRadius = 0.2, kCentre = 0.23;  // two spheres 0.06 apart at the origin

// n points spread over the sphere (Fibonacci lattice).
std::vector<Eigen::Vector3d> sphere_points(const Eigen::Vector3d& centre, int n) {
  std::vector<Eigen::Vector3d> out;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double y = 1.0 - 2.0 * (i + 0.5) / n, r = std::sqrt(1.0 - y * y);
    out.push_back(centre + kRadius * Eigen::Vector3d(r * std::cos(golden * i), y,
                                                     r * std::sin(golden * i)));
  }
  return out;
}

// A great circle of each sphere (in the xy and xz planes) as strokes, and optionally a stroke
// drawn from one sphere to the other across the gap, 0.04 off the axis.
Sketch sketch(bool across) {
  Sketch s;
  for (const double side : {-1.0, 1.0})
    for (int plane = 0; plane < 2; ++plane) {
      Stroke stroke;
      for (int i = 0; i <= 64; ++i) {
        const double t = 2.0 * std::numbers::pi * i / 64;
        Eigen::Vector3d p(side * kCentre + kRadius * std::cos(t), 0.0, 0.0);
        p[1 + plane] = kRadius * std::sin(t);
        stroke.points.push_back(p);
      }
      s.strokes.push_back(stroke);
    }
  if (across) {
    Stroke stroke;
    for (int i = 0; i <= 10; ++i) stroke.points.emplace_back(-0.05 + 0.01 * i, 0.04, 0.0);
    s.strokes.push_back(stroke);
  }
  return s;
}

struct Field {
  VipssResult vipss;
  double scale = 1.0;
};

// VIPSS through points of both spheres, scaled to a distance (positive outside) near them.
Field two_spheres() {
  std::vector<Eigen::Vector3d> points = sphere_points({-kCentre, 0.0, 0.0}, 120);
  const std::vector<Eigen::Vector3d> other = sphere_points({kCentre, 0.0, 0.0}, 120);
  points.insert(points.end(), other.begin(), other.end());
  Eigen::MatrixX3d x(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i)
    x.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  Field out{solve_vipss(x, VipssOptions{}, {}), 1.0};
  std::vector<double> norms;
  for (const Eigen::Vector3d& p : points) {
    Eigen::Vector3d g;
    out.vipss.function.value_gradient(p, &g);
    norms.push_back(g.norm());
  }
  std::nth_element(norms.begin(), norms.begin() + static_cast<std::ptrdiff_t>(norms.size() / 2),
                   norms.end());
  const double sign = out.vipss.function.value(Eigen::Vector3d(1.0, 1.0, 1.0)) > 0.0 ? 1.0 : -1.0;
  out.scale = sign / norms[norms.size() / 2];
  return out;
}

Saddles saddles_of(const Field& field, const Sketch& s, const SaddleSearch& search = {}) {
  std::vector<Eigen::Vector3d> along;
  for (const Stroke& stroke : s.strokes)
    along.insert(along.end(), stroke.points.begin(), stroke.points.end());
  Eigen::MatrixX3d points(static_cast<Eigen::Index>(along.size()), 3);
  for (std::size_t i = 0; i < along.size(); ++i)
    points.row(static_cast<Eigen::Index>(i)) = along[i].transpose();
  const PointGrid grid(points);
  BoundingBox box;
  box.extend(Eigen::Vector3d(-0.55, -0.3, -0.3));
  box.extend(Eigen::Vector3d(0.55, 0.3, 0.3));
  return find_saddles(field.vipss.function, field.scale, {}, s, grid, box, search, 1);
}

TEST(Saddles, GapCrossedByAStrokeIsBridged) {
  const Field field = two_spheres();
  // The gap is open at its middle, and narrow.
  const double middle = field.scale * field.vipss.function.value(Eigen::Vector3d::Zero());
  EXPECT_GT(middle, 0.0);
  EXPECT_LT(middle, 0.025);
  const Saddles found = saddles_of(field, sketch(true));
  EXPECT_TRUE(found.windows.empty());
  ASSERT_EQ(found.bridges.size(), 1u);
  const Bump& bridge = found.bridges.front();
  EXPECT_LT(bridge.centre.norm(), 0.02);
  // Lowered by the bump, the field is inside at the gap's middle and where the stroke crosses.
  for (const Eigen::Vector3d& p : {Eigen::Vector3d::Zero().eval(), Eigen::Vector3d(0.0, 0.04, 0.0)})
    EXPECT_LT(field.scale * field.vipss.function.value(p) - bridge.value(p, nullptr), 0.0)
        << p.transpose();
}

TEST(Saddles, GapNoStrokeCrossesStaysOpen) {
  const Saddles found = saddles_of(two_spheres(), sketch(false));
  EXPECT_TRUE(found.bridges.empty());
  EXPECT_TRUE(found.windows.empty());
}

TEST(Saddles, NothingSearchedWhenBothAreOff) {
  SaddleSearch off;
  off.window_most = 0.0;
  off.bridge_most = 0.0;
  const Saddles found = saddles_of(two_spheres(), sketch(true), off);
  EXPECT_TRUE(found.bridges.empty());
  EXPECT_TRUE(found.windows.empty());
}

}  // namespace
}  // namespace sketchsurf
