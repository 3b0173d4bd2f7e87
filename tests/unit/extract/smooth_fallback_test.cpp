#include "surfacing/extract/smooth_fallback.h"

#include <gtest/gtest.h>

#include "surfacing/sketch/stroke_segments.h"
#include "tests/support/shapes.h"

namespace sketchsurf {
namespace {

using namespace testing;

// Two unit spheres, 4 apart along x, each drawn with its meridians and equator: the strokes lie
// exactly on the first mesh's spheres ("the proxy"); the second is the same mesh inflated by 2%
// ("an optimised surface that left the strokes").
struct Scene {
  TriMesh proxy, inflated;
  StrokeSegments strokes;
  std::vector<std::uint8_t> sharp;
};

Scene two_spheres() {
  Scene s;
  const Eigen::Vector3d offset(4.0, 0.0, 0.0);
  s.proxy = icosphere(4, 1.0);
  append_mesh(s.proxy, icosphere(4, 1.0, offset));
  s.inflated = icosphere(4, 1.02);
  append_mesh(s.inflated, icosphere(4, 1.02, offset));
  Sketch sketch = sphere_sketch(1.0, 4), second = sphere_sketch(1.0, 4);
  transform(second, 1.0, offset);
  sketch.strokes.insert(sketch.strokes.end(), second.strokes.begin(), second.strokes.end());
  s.strokes = stroke_segments(sketch, false);
  s.sharp.assign(s.proxy.n_vertices(), 0);
  return s;
}

double max_offset(const TriMesh& mesh, const Eigen::MatrixX3d& reference, int first, int last) {
  double m = 0.0;
  for (int v = first; v < last; ++v)
    m = std::max(m, (to_eigen(mesh.point(mesh.vertex_handle(v))) - reference.row(v).transpose()).norm());
  return m;
}

TEST(SmoothFallback, ASmoothPartThatLeftItsStrokesGoesBackToTheProxy) {
  Scene s = two_spheres();
  const Eigen::MatrixX3d start = vertex_matrix(s.proxy);
  const Eigen::MatrixX3d inflated = vertex_matrix(s.inflated);
  const int half = static_cast<int>(s.proxy.n_vertices() / 2);
  s.sharp[static_cast<std::size_t>(half + 3)] = 1;  // the second sphere has a crease vertex
  TriMesh mesh = s.inflated;
  const SmoothFallbackSummary summary = keep_smooth_proxy(mesh, start, s.sharp, s.strokes, 6.0, {});
  EXPECT_EQ(summary.parts, 1u);
  EXPECT_EQ(summary.reverted, 1u);
  EXPECT_EQ(summary.vertices, static_cast<std::size_t>(half));
  EXPECT_EQ(max_offset(mesh, start, 0, half), 0.0) << "the smooth sphere is the proxy's again";
  EXPECT_EQ(max_offset(mesh, inflated, half, 2 * half), 0.0) << "the creased sphere is untouched";
}

TEST(SmoothFallback, APartCloserToItsStrokesThanTheProxyKeepsItsPositions) {
  Scene s = two_spheres();
  // Now the proxy is the inflated mesh and the optimised surface the exact one.
  const Eigen::MatrixX3d start = vertex_matrix(s.inflated);
  TriMesh mesh = s.proxy;
  const Eigen::MatrixX3d exact = vertex_matrix(mesh);
  const SmoothFallbackSummary summary = keep_smooth_proxy(mesh, start, s.sharp, s.strokes, 6.0, {});
  EXPECT_EQ(summary.parts, 2u);
  EXPECT_EQ(summary.reverted, 0u);
  EXPECT_EQ(max_offset(mesh, exact, 0, static_cast<int>(mesh.n_vertices())), 0.0);
}

TEST(SmoothFallback, OffOrWithoutStrokesNearbyNothingMoves) {
  Scene s = two_spheres();
  const Eigen::MatrixX3d start = vertex_matrix(s.proxy);
  SmoothFallbackOptions off;
  off.enabled = false;
  TriMesh mesh = s.inflated;
  EXPECT_EQ(keep_smooth_proxy(mesh, start, s.sharp, s.strokes, 6.0, off).reverted, 0u);
  // Strokes 10 diagonals away belong to no part.
  StrokeSegments far = s.strokes;
  far.points.col(1).array() += 60.0;
  EXPECT_EQ(keep_smooth_proxy(mesh, start, s.sharp, far, 6.0, {}).reverted, 0u);
  EXPECT_EQ(max_offset(mesh, vertex_matrix(s.inflated), 0, static_cast<int>(mesh.n_vertices())), 0.0);
}

}  // namespace
}  // namespace sketchsurf
