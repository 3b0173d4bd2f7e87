// Thin parts' normals from their strokes: outward from a tube's axis, webs told where the surface
// holds the space in front of a sample, between parts where another lies ahead, nothing on a flat
// face or where the axis lies outside.

#include "surfacing/proxy/part_normals.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace sketchsurf {
namespace {

// Stroke points (spacing about 0.005) of a tube along y, axis (x0, ., 0), radius r, from y = -h to
// h: rings every 0.02 and eight lengthwise lines.
void add_tube(std::vector<Eigen::Vector3d>& points, double x0, double r, double h) {
  for (double y = -h; y <= h + 1e-9; y += 0.02)
    for (int k = 0; k < 24; ++k) {
      const double a = 2.0 * M_PI * k / 24.0;
      points.emplace_back(x0 + r * std::cos(a), y, r * std::sin(a));
    }
  for (int k = 0; k < 8; ++k) {
    const double a = 2.0 * M_PI * k / 8.0;
    for (double y = -h; y <= h + 1e-9; y += 0.005)
      points.emplace_back(x0 + r * std::cos(a), y, r * std::sin(a));
  }
}

Eigen::MatrixX3d to_matrix(const std::vector<Eigen::Vector3d>& points) {
  Eigen::MatrixX3d m(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) m.row(static_cast<Eigen::Index>(i)) = points[i];
  return m;
}

// An ellipsoid with semi-axes (a, b, c) about the origin as a Hermite RBF: VIPSS through points on
// it; the scale's sign makes s f negative inside.
struct Ellipsoid {
  HermiteRbf f;
  double scale = 1.0;
};
Ellipsoid ellipsoid(double a, double b, double c) {
  std::vector<Eigen::Vector3d> points;
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 24; ++j) {
      const double theta = M_PI * (i + 0.5) / 12.0, phi = 2.0 * M_PI * j / 24.0;
      points.emplace_back(a * std::sin(theta) * std::cos(phi), b * std::cos(theta),
                          c * std::sin(theta) * std::sin(phi));
    }
  Ellipsoid e;
  e.f = solve_vipss(to_matrix(points), {}).function;
  e.scale = e.f.value(Eigen::Vector3d::Zero()) < 0.0 ? 1.0 : -1.0;
  return e;
}

// Two tubes (radius 0.02) 0.2 apart, both inside one ellipsoid that webs them (its side 0.01
// past their outer sides): samples on the tubes' sides get the normal away from their own axis;
// the web lies in front of their inner sides, not their outer ones.
TEST(PartNormals, TwoTubesInOneBlobPointAwayFromTheirAxesAndTheWebIsBetweenThem) {
  std::vector<Eigen::Vector3d> strokes;
  add_tube(strokes, -0.1, 0.02, 0.2);
  add_tube(strokes, 0.1, 0.02, 0.2);
  const Eigen::MatrixX3d stroke_points = to_matrix(strokes);
  const PointGrid grid(stroke_points);
  const Ellipsoid blob = ellipsoid(0.13, 0.3, 0.05);
  // Samples on each tube at mid-height: inner side, outer side, front.
  const Eigen::MatrixX3d samples = to_matrix({{-0.08, 0.0, 0.0},
                                              {-0.12, 0.0, 0.0},
                                              {-0.1, 0.0, 0.02},
                                              {0.08, 0.0, 0.0},
                                              {0.12, 0.0, 0.0}});
  const PartNormals parts = part_normals(blob.f, blob.scale, samples, stroke_points, grid, {});
  const std::vector<Eigen::Vector3d> expected{
      {1, 0, 0}, {-1, 0, 0}, {0, 0, 1}, {-1, 0, 0}, {1, 0, 0}};
  for (Eigen::Index i = 0; i < samples.rows(); ++i) {
    ASSERT_TRUE(parts.known[static_cast<std::size_t>(i)]) << "sample " << i;
    EXPECT_GT(parts.normals.row(i).dot(expected[static_cast<std::size_t>(i)].transpose()), 0.95)
        << "sample " << i << ": " << parts.normals.row(i);
  }
  EXPECT_TRUE(parts.web[0]);
  EXPECT_FALSE(parts.web[1]);
  EXPECT_TRUE(parts.web[3]);
  EXPECT_FALSE(parts.web[4]);
  EXPECT_TRUE(parts.between[0] && parts.between[3]) << "the other tube lies ahead of each";
}

// One tube in a blob wider than it on one side: the web in front of its side has no other part
// ahead (a bulge of the surface, not a web between parts).
TEST(PartNormals, AWebWithNoPartAheadIsNotBetweenParts) {
  std::vector<Eigen::Vector3d> strokes;
  add_tube(strokes, -0.1, 0.02, 0.2);
  const Eigen::MatrixX3d stroke_points = to_matrix(strokes);
  const PointGrid grid(stroke_points);
  const Ellipsoid blob = ellipsoid(0.13, 0.3, 0.05);
  const PartNormals parts =
      part_normals(blob.f, blob.scale, to_matrix({{-0.08, 0.0, 0.0}, {-0.08, 0.05, 0.0}}),
                   stroke_points, grid, {});
  EXPECT_TRUE(parts.web[0] && parts.web[1]);
  EXPECT_FALSE(parts.between[0] || parts.between[1]);
}

// A flat face drawn as a grid of lines is no thin part: its section is not round.
TEST(PartNormals, AFlatFaceGivesNoNormal) {
  std::vector<Eigen::Vector3d> strokes;
  for (double u = -0.2; u <= 0.2 + 1e-9; u += 0.02)
    for (double v = -0.2; v <= 0.2 + 1e-9; v += 0.005) {
      strokes.emplace_back(u, v, 0.0);
      strokes.emplace_back(v, u, 0.0);
    }
  const Eigen::MatrixX3d stroke_points = to_matrix(strokes);
  const PointGrid grid(stroke_points);
  const Ellipsoid slab = ellipsoid(0.3, 0.3, 0.05);
  const Eigen::MatrixX3d samples = to_matrix({{0.0, 0.0, 0.0}, {0.1, 0.05, 0.0}, {0.19, 0.0, 0.0}});
  const PartNormals parts = part_normals(slab.f, slab.scale, samples, stroke_points, grid, {});
  for (const char known : parts.known) EXPECT_FALSE(known);
}

// Outside the surface the strokes' axis is a concave place (the inside of a bend): no normal.
TEST(PartNormals, AnAxisOutsideTheSurfaceGivesNoNormal) {
  std::vector<Eigen::Vector3d> strokes;
  add_tube(strokes, 0.0, 0.02, 0.2);
  const Eigen::MatrixX3d stroke_points = to_matrix(strokes);
  const PointGrid grid(stroke_points);
  Ellipsoid inverted = ellipsoid(0.13, 0.3, 0.05);
  inverted.scale = -inverted.scale;  // positive inside: the tube's axis is outside
  const PartNormals parts =
      part_normals(inverted.f, inverted.scale, to_matrix({{0.02, 0.0, 0.0}}), stroke_points, grid, {});
  EXPECT_FALSE(parts.known[0]);
}

}  // namespace
}  // namespace sketchsurf
