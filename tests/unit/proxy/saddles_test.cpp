// Saddles of the VIPSS function: a gap between two spheres is bridged only where a stroke runs
// across it; a ring's opening is a window to close only where no stroke depicts it.

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

// VIPSS through `points`, scaled to a distance (positive outside) near them.
Field field_through(const std::vector<Eigen::Vector3d>& points) {
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

Field two_spheres() {
  std::vector<Eigen::Vector3d> points = sphere_points({-kCentre, 0.0, 0.0}, 120);
  const std::vector<Eigen::Vector3d> other = sphere_points({kCentre, 0.0, 0.0}, 120);
  points.insert(points.end(), other.begin(), other.end());
  return field_through(points);
}

Saddles saddles_of(const Field& field, const Sketch& s, const SaddleSearch& search = {},
                   double extent = 0.55) {
  std::vector<Eigen::Vector3d> along;
  for (const Stroke& stroke : s.strokes)
    along.insert(along.end(), stroke.points.begin(), stroke.points.end());
  Eigen::MatrixX3d points(static_cast<Eigen::Index>(along.size()), 3);
  for (std::size_t i = 0; i < along.size(); ++i)
    points.row(static_cast<Eigen::Index>(i)) = along[i].transpose();
  const PointGrid grid(points);
  BoundingBox box;
  box.extend(Eigen::Vector3d(-extent, -0.3, -0.3));
  box.extend(Eigen::Vector3d(extent, 0.3, 0.3));
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

// A ring about the z axis (radius kRing, tube kTube): its opening, 0.12 across, is a
// window-shaped saddle of the field (a maximum in the ring's plane, a minimum along the axis) with
// a value between the narrow windows' 0.025 and the wider ones' 0.06.
constexpr double kRing = 0.12, kTube = 0.06;

Eigen::Vector3d ring_point(double around, double across) {
  const double r = kRing + kTube * std::cos(across);
  return {r * std::cos(around), r * std::sin(around), kTube * std::sin(across)};
}

Field ring() {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 24; ++i)
    for (int j = 0; j < 12; ++j)
      points.push_back(ring_point(2.0 * std::numbers::pi * (i + 0.5 * (j % 2)) / 24,
                                  2.0 * std::numbers::pi * j / 12));
  return field_through(points);
}

// The search for wider windows only (narrow ones and bridges off), from grid points within 0.2
// of a stroke.
SaddleSearch wider_windows() {
  SaddleSearch search;
  search.near = 0.2;
  search.window_most = 0.025;
  search.window_undrawn_most = 0.06;
  search.bridge_most = 0.0;
  return search;
}

// Strokes by the ring's opening: a grid of straight lines on its two faces, passing by the
// opening as the strokes that frame a window through a wall do; or only the grid's lines on one
// side of it (open space on the others, as by a hole in a web between two parts); or the same
// grid round the ring, far from the opening (a small hole in a web far from the strokes); or its
// inside circle, winding round the opening; or short lines along the axis on the opening's wall,
// all round it (a bore drawn by its wall's lines).
enum class RingStrokes { kGrid, kOneSide, kFarGrid, kInsideCircle, kWallLines };

Sketch ring_sketch(RingStrokes kind) {
  Sketch s;
  const double pi = std::numbers::pi;
  const auto add = [&](auto&& point_at, int n) {
    Stroke stroke;
    for (int i = 0; i <= n; ++i) stroke.points.push_back(point_at(static_cast<double>(i) / n));
    s.strokes.push_back(stroke);
  };
  if (kind == RingStrokes::kGrid || kind == RingStrokes::kOneSide || kind == RingStrokes::kFarGrid) {
    const double inner = kind == RingStrokes::kFarGrid ? kRing + 0.04 : kRing - 0.04;
    const double z = std::sqrt(kTube * kTube - 0.04 * 0.04);
    for (const double side : {-z, z})  // the lines meet the ring where they pass nearest its axis
      for (const double offset : {-inner, inner}) {
        add([&](double t) { return Eigen::Vector3d(offset, -0.2 + 0.4 * t, side); }, 32);
        if (kind != RingStrokes::kOneSide)
          add([&](double t) { return Eigen::Vector3d(-0.2 + 0.4 * t, offset, side); }, 32);
        else
          break;  // the lines at x = -inner only
      }
  } else if (kind == RingStrokes::kInsideCircle) {
    add([&](double t) { return ring_point(2.0 * pi * t, pi); }, 64);
  } else {
    for (int k = 0; k < 8; ++k)
      add([&](double t) { return ring_point(2.0 * pi * k / 8, pi - 0.6 + 1.2 * t); }, 16);
  }
  return s;
}

TEST(Saddles, WiderOpeningNoStrokeDepictsIsAWindow) {
  const Field field = ring();
  const double middle = field.scale * field.vipss.function.value(Eigen::Vector3d::Zero());
  ASSERT_GT(middle, 0.025);
  ASSERT_LT(middle, 0.06);
  const Saddles found = saddles_of(field, ring_sketch(RingStrokes::kGrid), wider_windows(), 0.3);
  EXPECT_TRUE(found.windows.empty());
  ASSERT_FALSE(found.undrawn.empty());
  // The membrane closes the opening: the lowered field is inside at its middle.
  EXPECT_LT(middle - bumps_value(found.undrawn, Eigen::Vector3d::Zero(), nullptr), 0.0);
  // Off, nothing is found.
  SaddleSearch off = wider_windows();
  off.window_undrawn_most = 0.0;
  EXPECT_TRUE(saddles_of(field, ring_sketch(RingStrokes::kGrid), off, 0.3).undrawn.empty());
}

TEST(Saddles, OpeningWhoseRimOrWallIsDrawnOrOpenOnASideOrFarFromTheStrokesStaysOpen) {
  const Field field = ring();
  for (const RingStrokes kind : {RingStrokes::kInsideCircle, RingStrokes::kWallLines,
                                 RingStrokes::kOneSide, RingStrokes::kFarGrid}) {
    const Saddles found = saddles_of(field, ring_sketch(kind), wider_windows(), 0.3);
    EXPECT_TRUE(found.undrawn.empty()) << static_cast<int>(kind);
    EXPECT_TRUE(found.windows.empty()) << static_cast<int>(kind);
  }
}

}  // namespace
}  // namespace sketchsurf
