// Checks of the generated test shapes themselves: every other test trusts their known answers.
#include "tests/support/shapes.h"

#include <gtest/gtest.h>

namespace sketchsurf::testing {
namespace {

int euler_characteristic(const TriMesh& m) {
  return static_cast<int>(m.n_vertices()) - static_cast<int>(m.n_edges()) + static_cast<int>(m.n_faces());
}

bool closed(const TriMesh& m) {
  for (auto e : m.edges())
    if (e.is_boundary()) return false;
  return true;
}

TEST(Shapes, IcosphereIsAClosedSphere) {
  const TriMesh m = icosphere(3, 2.0);
  EXPECT_EQ(m.n_vertices(), 10u * 64 + 2);
  EXPECT_TRUE(closed(m));
  EXPECT_EQ(euler_characteristic(m), 2);
  for (auto v : m.vertices()) EXPECT_NEAR(m.point(v).norm(), 2.0, 1e-12);
  // Outward orientation: the normal points away from the centre.
  for (auto v : m.vertices()) EXPECT_GT(OpenMesh::dot(m.normal(v), m.point(v)), 0.0);
}

TEST(Shapes, RoundedBoxLiesOnTheBox) {
  const Eigen::Vector3d half(0.5, 0.5, 0.5);
  const TriMesh m = rounded_box_mesh(3, half, 0.05);
  EXPECT_TRUE(closed(m));
  EXPECT_EQ(euler_characteristic(m), 2);
  for (auto v : m.vertices()) {
    // Within the rounding of the sharp box.
    EXPECT_LE(box_distance(to_eigen(m.point(v)), half), 0.05 * (1 - 1 / std::sqrt(3.0)) + 1e-9);
  }
}

TEST(Shapes, TorusMeshHasGenusOne) {
  const TriMesh m = torus_mesh(24, 12, 1.0, 0.3);
  EXPECT_TRUE(closed(m));
  EXPECT_EQ(euler_characteristic(m), 0);
}

TEST(Shapes, CubeSketchFollowsTheCubeEdges) {
  const Sketch s = cube_sketch(2.0);
  EXPECT_EQ(s.strokes.size(), 18u);
  for (const auto& stroke : s.strokes)
    for (const auto& p : stroke.points) EXPECT_NEAR(box_distance(p, Eigen::Vector3d::Ones()), 0.0, 1e-12);
  EXPECT_NEAR(s.bounding_box().diagonal(), 2.0 * std::sqrt(3.0), 1e-12);
}

TEST(Shapes, CurvesLieOnTheirSurfaces) {
  for (const auto& stroke : sphere_sketch(0.7).strokes)
    for (const auto& p : stroke.points) EXPECT_NEAR(p.norm(), 0.7, 1e-12);
  for (const auto& stroke : cylinder_sketch(0.5, 1.0).strokes)
    for (const auto& p : stroke.points) {
      const double rho = std::hypot(p.x(), p.y());
      EXPECT_TRUE(std::abs(rho - 0.5) < 1e-12 || std::abs(std::abs(p.z()) - 0.5) < 1e-12);
    }
  for (const auto& stroke : torus_sketch(0.5, 0.2).strokes)
    for (const auto& p : stroke.points)
      EXPECT_NEAR(std::hypot(std::hypot(p.x(), p.y()) - 0.5, p.z()), 0.2, 1e-12);
  int boundary = 0;
  for (const auto& stroke : sheet_sketch().strokes) boundary += stroke.boundary;
  EXPECT_EQ(boundary, 4);
}

TEST(Shapes, TransformMovesTheMirrorPlaneWithThePoints) {
  Sketch s = cube_sketch();
  s.mirror = Plane{Eigen::Vector3d::UnitX(), 0.0};
  const Eigen::Vector3d p = s.strokes[0].points[3];
  const Eigen::Vector3d mirrored = s.mirror->reflect(p);
  transform(s, 1e3, Eigen::Vector3d(1, 2, 3));
  EXPECT_NEAR((s.mirror->reflect(s.strokes[0].points[3]) - (1e3 * mirrored + Eigen::Vector3d(1, 2, 3))).norm(), 0.0, 1e-9);
}

}  // namespace
}  // namespace sketchsurf::testing
