// Shape checks: a clean sphere passes them all; a sheet far from the strokes, a surface outside
// the strokes' box, crossing triangles, holes, handles and ragged region borders are flagged.

#include <gtest/gtest.h>

#include <algorithm>

#include "surfacing/quality/checks.h"
#include "surfacing/self_intersections.h"
#include "tests/support/shapes.h"

namespace sketchsurf {
namespace {

// `b` added to `a` as another component.
TriMesh joined(TriMesh a, const TriMesh& b) {
  append_mesh(a, b);
  return a;
}

// A flat square sheet of n x n quads in the plane z = height, centred at (cx, 0).
TriMesh sheet(double cx, double half, double height, int n) {
  TriMesh mesh;
  std::vector<TriMesh::VertexHandle> v;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      v.push_back(mesh.add_vertex({cx - half + 2 * half * i / n, -half + 2 * half * j / n, height}));
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const auto a = v[j * (n + 1) + i], b = v[j * (n + 1) + i + 1], c = v[(j + 1) * (n + 1) + i + 1],
                 d = v[(j + 1) * (n + 1) + i];
      mesh.add_face(a, b, c);
      mesh.add_face(a, c, d);
    }
  return mesh;
}

std::vector<int> split_by_z(const TriMesh& mesh) {
  std::vector<int> labels;
  for (auto v : mesh.vertices()) labels.push_back(mesh.point(v)[2] > 0 ? 1 : 0);
  return labels;
}

TEST(ShapeChecks, ASphereOnItsStrokesPassesEveryCheck) {
  const TriMesh mesh = testing::icosphere(4, 0.5);
  const ShapeChecks c = check_shape(mesh, split_by_z(mesh), testing::sphere_sketch(0.5, 6), false);
  EXPECT_EQ(c.far_10, 0.0);
  EXPECT_EQ(c.outside_box, 0.0);
  EXPECT_EQ(c.genus, 0);
  EXPECT_EQ(c.components, 1u);
  EXPECT_EQ(c.boundary_loops, 0u);
  EXPECT_EQ(c.self_intersections, 0u);
  EXPECT_EQ(c.regions, 2u);
  EXPECT_LT(c.border_ratio, 1.2);
  EXPECT_TRUE(c.warnings.empty()) << c.warnings.front();
}

TEST(ShapeChecks, ASheetWhereNoStrokeIsIsFlagged) {
  // The sphere's strokes span [-0.5, 0.5]^3; a 3 x 3 sheet through the equator runs far beyond.
  const TriMesh mesh = joined(testing::icosphere(3, 0.5), sheet(0.0, 1.5, 0.0, 30));
  const ShapeChecks c = check_shape(mesh, {}, testing::sphere_sketch(0.5, 6), false);
  EXPECT_GT(c.far_10, 0.3);
  EXPECT_GT(c.beyond, 0.3);
  EXPECT_GT(c.outside_box, 0.5);
  EXPECT_GT(c.self_intersections, 0u);  // the sheet cuts through the sphere
  EXPECT_EQ(c.boundary_loops, 1u);
  EXPECT_EQ(c.regions, 0u);
  ASSERT_GE(c.warnings.size(), 4u);
  EXPECT_NE(c.warnings[0].find("beyond the strokes"), std::string::npos) << c.warnings[0];
  EXPECT_NE(c.warnings[1].find("outside the strokes' bounding box"), std::string::npos) << c.warnings[1];
}

TEST(ShapeChecks, HolesAreExpectedWhenBoundaryStrokesAreMarked) {
  // A unit square sheet drawn as a grid of 5 x 5 lines, its border included.
  const TriMesh mesh = sheet(0.0, 0.5, 0.0, 10);
  Sketch sketch;
  for (double t = -0.5; t <= 0.5 + 1e-9; t += 0.25) {
    sketch.strokes.push_back(testing::sample_curve([t](double u) { return Eigen::Vector3d(t, u, 0); }, -0.5, 0.5, 0.02));
    sketch.strokes.push_back(testing::sample_curve([t](double u) { return Eigen::Vector3d(u, t, 0); }, -0.5, 0.5, 0.02));
  }
  const ShapeChecks closed = check_shape(mesh, {}, sketch, false);
  EXPECT_EQ(closed.far_10, 0.0);
  EXPECT_EQ(closed.beyond, 0.0);
  ASSERT_EQ(closed.warnings.size(), 1u);
  EXPECT_NE(closed.warnings[0].find("1 hole(s)"), std::string::npos) << closed.warnings[0];
  EXPECT_TRUE(check_shape(mesh, {}, sketch, true).warnings.empty());
}

TEST(ShapeChecks, FacesFramedBySparseStrokesAreNotBeyondThem) {
  // The cube of the bundled example (one stroke across each face): parts of the faces are over
  // 10% of the diagonal from every stroke, but strokes frame them.
  const TriMesh mesh = testing::rounded_box_mesh(4, Eigen::Vector3d(0.5, 0.5, 0.5), 0.0);
  const ShapeChecks c = check_shape(mesh, {}, testing::cube_sketch(1.0, true), false);
  EXPECT_GT(c.far_10, 0.05);
  EXPECT_EQ(c.beyond, 0.0);
  EXPECT_TRUE(c.warnings.empty()) << c.warnings.front();
}

TEST(ShapeChecks, HandlesAboveTheLimitAreFlagged) {
  const TriMesh torus = testing::torus_mesh(48, 16, 0.5, 0.2);
  const ShapeChecks c = check_shape(torus, {}, testing::torus_sketch(0.5, 0.2, 8), false);
  EXPECT_EQ(c.genus, 1);
  EXPECT_TRUE(c.warnings.empty());
  CheckOptions strict;
  strict.warn_genus = 0;
  const ShapeChecks s = check_shape(torus, {}, testing::torus_sketch(0.5, 0.2, 8), false, strict);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("genus 1"), std::string::npos);
}

TEST(ShapeChecks, MirroredSketchesCountTheReflectedStrokes) {
  // Strokes on one half of the sphere only, with a mirror plane x = 0: the other half is not far.
  Sketch half = testing::sphere_sketch(0.5, 6);
  for (Stroke& s : half.strokes)
    std::erase_if(s.points, [](const Eigen::Vector3d& p) { return p.x() < -1e-9; });
  std::erase_if(half.strokes, [](const Stroke& s) { return s.points.size() < 2; });
  const TriMesh mesh = testing::icosphere(3, 0.5);
  EXPECT_GT(check_shape(mesh, {}, half, false).outside_box, 0.2);
  half.mirror = Plane{Eigen::Vector3d::UnitX(), 0.0};
  EXPECT_EQ(check_shape(mesh, {}, half, false).outside_box, 0.0);
}

TEST(ShapeChecks, RaggedRegionBordersHaveALargeRatio) {
  const TriMesh mesh = testing::icosphere(4, 0.5);
  std::vector<int> ragged = split_by_z(mesh);
  // Flip every other vertex in a band around the equator: a zig-zag border.
  for (auto v : mesh.vertices())
    if (std::abs(mesh.point(v)[2]) < 0.08 && v.idx() % 2 == 0) ragged[v.idx()] = 1 - ragged[v.idx()];
  const ShapeChecks c = check_shape(mesh, ragged, testing::sphere_sketch(0.5, 6), false);
  EXPECT_GT(c.border_ratio, 1.35);
  EXPECT_FALSE(c.warnings.empty());
}

TEST(ShapeChecks, SelfIntersectionsOfTwoOverlappingSpheres) {
  const TriMesh one = testing::icosphere(2, 0.5);
  EXPECT_EQ(count_self_intersections(one), 0u);
  EXPECT_GT(count_self_intersections(joined(one, testing::icosphere(2, 0.5, Eigen::Vector3d(0.5, 0, 0)))), 0u);
  EXPECT_EQ(count_self_intersections(joined(one, testing::icosphere(2, 0.5, Eigen::Vector3d(1.2, 0, 0)))), 0u);
}

TEST(ShapeChecks, CrossingPairsAmongFlaggedTrianglesAreTheWholeSearchsPairsWithOneOfThem) {
  const TriMesh mesh = joined(testing::icosphere(3, 0.5), testing::icosphere(3, 0.5, Eigen::Vector3d(0.5, 0.1, 0)));
  const Eigen::MatrixX3d V = vertex_matrix(mesh);
  const Eigen::MatrixX3i F = face_matrix(mesh);
  const std::vector<std::array<int, 2>> all = crossing_face_pairs(V, F);
  ASSERT_GT(all.size(), 50u);
  std::vector<char> among(static_cast<std::size_t>(F.rows()), 0);
  for (std::size_t f = 0; f < among.size(); f += 3) among[f] = 1;
  std::vector<std::array<int, 2>> expected;
  for (const auto& pair : all)
    if (among[pair[0]] || among[pair[1]]) expected.push_back(pair);
  ASSERT_FALSE(expected.empty());
  ASSERT_LT(expected.size(), all.size());
  EXPECT_EQ(crossing_face_pairs(V, F, among), expected);
  EXPECT_TRUE(crossing_face_pairs(V, F, std::vector<char>(among.size(), 0)).empty());
  EXPECT_EQ(crossing_face_pairs(V, F, std::vector<char>(among.size(), 1)), all);
}

TEST(ShapeChecks, CrossingPairsAreTheSameWhateverTheThreads) {
  // Two overlapping spheres of 1,280 triangles each: the search runs in blocks of triangles.
  const TriMesh mesh = joined(testing::icosphere(3, 0.5), testing::icosphere(3, 0.5, Eigen::Vector3d(0.5, 0.1, 0)));
  const Eigen::MatrixX3d V = vertex_matrix(mesh);
  const Eigen::MatrixX3i F = face_matrix(mesh);
  const std::vector<std::array<int, 2>> one = crossing_face_pairs(V, F, {}, 1);
  ASSERT_GT(one.size(), 50u);
  ASSERT_TRUE(std::is_sorted(one.begin(), one.end()));
  std::vector<char> among(static_cast<std::size_t>(F.rows()), 0);
  for (std::size_t f = 0; f < among.size(); f += 5) among[f] = 1;
  const std::vector<std::array<int, 2>> some = crossing_face_pairs(V, F, among, 1);
  for (const unsigned threads : {2u, 3u, 8u}) {
    EXPECT_EQ(crossing_face_pairs(V, F, {}, threads), one) << threads << " threads";
    EXPECT_EQ(crossing_face_pairs(V, F, among, threads), some) << threads << " threads";
  }
}

}  // namespace
}  // namespace sketchsurf
