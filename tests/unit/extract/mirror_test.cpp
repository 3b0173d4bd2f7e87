#include "surfacing/extract/mirror.h"

#include <gtest/gtest.h>

#include "surfacing/error.h"
#include "tests/support/shapes.h"

namespace sketchsurf {
namespace {

Plane make_plane(const Eigen::Vector3d& n, double offset) {
  Plane p;
  p.normal = n.normalized();
  p.offset = offset;
  return p;
}

double area(const TriMesh& mesh) {
  double a = 0.0;
  for (auto f : mesh.faces()) a += mesh.calc_face_area(f);
  return a;
}

/// Largest distance from a reflected vertex to its nearest vertex.
double symmetry_error(const TriMesh& mesh, const Plane& plane) {
  double worst = 0.0;
  for (auto v : mesh.vertices()) {
    const Eigen::Vector3d r = plane.reflect(to_eigen(mesh.point(v)));
    double best = std::numeric_limits<double>::infinity();
    for (auto u : mesh.vertices()) best = std::min(best, (to_eigen(mesh.point(u)) - r).norm());
    worst = std::max(worst, best);
  }
  return worst;
}

TEST(ClipToHalfSpace, KeepsTheHalfAndCutsExactlyOnThePlane) {
  const Plane plane = make_plane({1, 0.3, -0.2}, 0.1);
  const TriMesh sphere = testing::icosphere(3);
  const ClippedMesh half = clip_to_half_space(sphere, plane, 1e-9);
  std::size_t boundary = 0;
  for (auto v : half.mesh.vertices()) {
    const double d = plane.signed_distance(to_eigen(half.mesh.point(v)));
    EXPECT_GE(d, -1e-15);
    if (half.mesh.is_boundary(v)) {
      ++boundary;
      EXPECT_TRUE(half.on_plane[v.idx()]);
      EXPECT_NEAR(d, 0.0, 1e-15);
    }
    if (half.source_vertex[v.idx()] >= 0) {
      EXPECT_EQ(half.mesh.point(v), sphere.point(TriMesh::VertexHandle(half.source_vertex[v.idx()])));
    }
  }
  EXPECT_GT(boundary, 20u);
  // A cap of the unit sphere at height h = 0.1 / |n| ... compare with the exact cap area 2 pi (1 - h).
  const double h = 0.1;  // the plane is at distance |offset| from the centre, on the kept side
  EXPECT_NEAR(area(half.mesh), 2 * M_PI * (1 + h) * area(sphere) / (4 * M_PI), 0.02);
}

TEST(ClipToHalfSpace, ThrowsWhenNothingIsKept) {
  EXPECT_THROW(clip_to_half_space(testing::icosphere(1), make_plane({1, 0, 0}, -5.0), 1e-9), Error);
}

TEST(MirrorAndWeld, GivesAClosedSymmetricMeshWithoutDoubles) {
  for (const Plane& plane : {make_plane({1, 0, 0}, 0.0), make_plane({1, 2, -0.5}, 0.2)}) {
    const ClippedMesh half = clip_to_half_space(testing::icosphere(3), plane, 1e-9);
    std::vector<int> source;
    const TriMesh full = mirror_and_weld(half.mesh, plane, 1e-9, &source);
    std::size_t on_plane = 0;
    for (auto v : half.mesh.vertices()) on_plane += half.mesh.is_boundary(v);
    EXPECT_EQ(full.n_vertices(), 2 * half.mesh.n_vertices() - on_plane);
    EXPECT_EQ(full.n_faces(), 2 * half.mesh.n_faces());
    for (auto v : full.vertices()) EXPECT_FALSE(full.is_boundary(v));
    EXPECT_EQ(long(full.n_vertices()) - long(full.n_edges()) + long(full.n_faces()), 2);
    EXPECT_LT(symmetry_error(full, plane), 1e-9);
    ASSERT_EQ(source.size(), full.n_vertices());
    for (std::size_t v = 0; v < source.size(); ++v) {
      const Eigen::Vector3d p = to_eigen(full.point(TriMesh::VertexHandle(int(v))));
      const Eigen::Vector3d q = to_eigen(half.mesh.point(TriMesh::VertexHandle(source[v])));
      EXPECT_TRUE((p - q).norm() < 1e-12 || (p - plane.reflect(q)).norm() < 1e-12);
    }
    // Outward normals on both halves: the signed volume is twice the kept part's,
    // 2 (4/3 pi - pi k^2 (3 - k) / 3) with k = 1 - offset the height of the dropped cap.
    const double k = 1.0 - plane.offset;
    const double expected = 2.0 * (4.0 / 3.0 * M_PI - M_PI * k * k * (3.0 - k) / 3.0);
    double volume = 0.0;
    for (auto f : full.faces()) {
      std::vector<Eigen::Vector3d> c;
      for (auto v : f.vertices()) c.push_back(to_eigen(full.point(v)));
      volume += c[0].dot(c[1].cross(c[2])) / 6.0;
    }
    EXPECT_NEAR(volume, expected, 0.02 * expected);
  }
}

TEST(HalfSketch, CutsStrokesAtThePlane) {
  const Sketch cube = testing::cube_sketch(1.0, true);
  const Plane plane = make_plane({1, 0, 0}, -0.1);  // keep x >= 0.1
  const Sketch half = half_sketch(cube, plane);
  ASSERT_TRUE(!half.strokes.empty());
  std::size_t on_plane = 0;
  for (const Stroke& s : half.strokes) {
    EXPECT_GE(s.size(), 2u);
    EXPECT_TRUE(s.attributes_consistent());
    for (const auto& p : s.points) {
      EXPECT_GE(plane.signed_distance(p), -1e-12);
      on_plane += std::abs(plane.signed_distance(p)) < 1e-12;
    }
  }
  // At least the 4 edges along x are cut once each.
  EXPECT_GE(on_plane, 4u);
}

TEST(HalfSketch, ZigzagGivesOnePiecePerVisitOfTheKeptSide) {
  Sketch sketch;
  Stroke s;
  for (double x : {-1.0, 1.0, -1.0, 0.5}) s.points.emplace_back(x, 0.0, 0.0);
  s.pressures = {0.1f, 0.2f, 0.3f, 0.4f};
  s.boundary = true;
  s.id = 7;
  sketch.strokes.push_back(s);
  const Sketch half = half_sketch(sketch, make_plane({1, 0, 0}, -0.1));
  ASSERT_EQ(half.strokes.size(), 2u);
  EXPECT_NEAR(half.strokes[0].length(), 1.8, 1e-12);  // 0.1 -> 1 -> 0.1
  EXPECT_NEAR(half.strokes[1].length(), 0.4, 1e-12);  // 0.1 -> 0.5
  for (const Stroke& piece : half.strokes) {
    EXPECT_TRUE(piece.boundary);
    EXPECT_EQ(piece.id, 7);
    EXPECT_TRUE(piece.attributes_consistent());
    EXPECT_DOUBLE_EQ(piece.points.front().x(), 0.1);
  }
  EXPECT_EQ(half.strokes[0].pressures[1], 0.2f);
}

}  // namespace
}  // namespace sketchsurf
