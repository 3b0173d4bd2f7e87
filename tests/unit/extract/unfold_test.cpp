// Folds ironed out of the final mesh (unfold.h): triangles that cross where the proxy's did not
// are spanned by a membrane, the rest of the surface is untouched, the proxy's own crossings and
// zones too large to span are left as they are.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "surfacing/extract/unfold.h"
#include "surfacing/self_intersections.h"
#include "tests/support/shapes.h"

namespace sketchsurf {
namespace {

// The unit sphere (the proxy) with a small cap round +x (x > 0.97) pushed through the sphere to
// x = -1.3: a spike whose long triangles pierce the far side.
struct Spike {
  TriMesh proxy = testing::icosphere(4, 1.0);
  TriMesh mesh = proxy;
  Eigen::MatrixX3d start = vertex_matrix(proxy);
  Spike() {
    for (auto v : mesh.vertices())
      if (mesh.point(v)[0] > 0.97) mesh.point(v)[0] = -1.3;
  }
};

TEST(Unfold, ASpikeThroughTheSurfaceBecomesAMembraneAndNothingElseMoves) {
  Spike spike;
  ASSERT_GT(count_self_intersections(spike.mesh), 0u);
  const TriMesh before = spike.mesh;
  const UnfoldSummary s = unfold(spike.mesh, spike.start, {});
  EXPECT_GT(s.crossing_pairs, 0u);
  EXPECT_EQ(s.left_pairs, 0u);
  EXPECT_EQ(count_self_intersections(spike.mesh), 0u);
  EXPECT_GT(s.moved_vertices, 0u);
  EXPECT_LT(s.moved_vertices, spike.mesh.n_vertices() / 8);
  for (auto v : spike.mesh.vertices()) {
    const auto& p = spike.mesh.point(v);
    const auto& was = before.point(v);
    if (std::abs(was[0]) < 0.5) {  // far from the spike and from where it pierced: untouched
      EXPECT_EQ(p, was);
    } else if (was[0] == -1.3) {  // the spike's tip: back near the cap's rim plane
      EXPECT_GT(p[0], 0.85);
      EXPECT_LT(p[0], 1.0);
    } else if (was[0] < -0.5) {  // the far side it pierced: spanned too, but it stays near
      EXPECT_LT((p - was).norm(), 0.15);
    }
  }
}

TEST(Unfold, TheFillKeepsTheBendOfTheSurfaceAroundIt) {
  // The spike's cap filled again follows the sphere it was cut from: a membrane would span it
  // flat, inside the sphere, by the cap's height (0.03 of the radius and more, rings included).
  Spike spike;
  unfold(spike.mesh, spike.start, {});
  double worst = 0.0;
  for (auto v : spike.mesh.vertices())
    if (spike.start(v.idx(), 0) > 0.97) worst = std::max(worst, std::abs(spike.mesh.point(v).norm() - 1.0));
  EXPECT_LT(worst, 0.01);
}

TEST(Unfold, TheProxysOwnCrossingsAreLeftAsTheyAre) {
  // Two overlapping spheres as one mesh, unmoved: they cross, but the proxy crossed there too.
  TriMesh mesh = testing::icosphere(3, 0.5);
  append_mesh(mesh, testing::icosphere(3, 0.5, Eigen::Vector3d(0.5, 0.0, 0.0)));
  const TriMesh before = mesh;
  const UnfoldSummary s = unfold(mesh, vertex_matrix(mesh), {});
  EXPECT_EQ(s.crossing_pairs, 0u);
  EXPECT_EQ(s.moved_vertices, 0u);
  EXPECT_GT(count_self_intersections(mesh), 0u);
  for (auto v : mesh.vertices()) {
    EXPECT_EQ(mesh.point(v), before.point(v));
  }
}

TEST(Unfold, AZoneLargerThanItsShareIsLeftAsTheSolveMadeIt) {
  Spike spike;
  const TriMesh before = spike.mesh;
  UnfoldOptions options;
  options.max_share = 0.005;  // the spike's zone has more vertices than 0.5% of the sphere's
  const UnfoldSummary s = unfold(spike.mesh, spike.start, {}, options);
  EXPECT_GT(s.skipped_vertices, 0u);
  EXPECT_GT(s.left_pairs, 0u);
  for (auto v : spike.mesh.vertices()) {  // the spike stays where it was
    if (before.point(v)[0] == -1.3) {
      EXPECT_EQ(spike.mesh.point(v), before.point(v));
    }
  }
}

TEST(Unfold, FixedVerticesKeepTheirPositionsAndOffMeansNothingMoves) {
  Spike spike;
  const TriMesh before = spike.mesh;
  std::vector<std::uint8_t> fixed(spike.mesh.n_vertices(), 0);
  for (auto v : spike.mesh.vertices()) fixed[v.idx()] = before.point(v)[0] == -1.3;
  unfold(spike.mesh, spike.start, fixed);
  for (auto v : spike.mesh.vertices()) {
    if (fixed[v.idx()]) {
      EXPECT_EQ(spike.mesh.point(v), before.point(v));
    }
  }
  Spike off;
  UnfoldOptions none;
  none.rings = 0;
  const UnfoldSummary s = unfold(off.mesh, off.start, {}, none);
  EXPECT_EQ(s.moved_vertices, 0u);
  for (auto v : off.mesh.vertices()) {
    EXPECT_EQ(off.mesh.point(v), before.point(v));
  }
}

TEST(Unfold, TheZoneRoundCrossingTrianglesIsTheirVerticesAndTheRingsRoundThem) {
  // Two triangles of the spike that share no vertex: their six vertices, then each ring adds
  // exactly the neighbours of the vertices before it.
  Spike spike;
  const std::vector<std::array<int, 2>> pair = {{0, static_cast<int>(spike.mesh.n_faces()) - 1}};
  const std::vector<char> own = around(spike.mesh, pair, 0);
  EXPECT_EQ(std::count(own.begin(), own.end(), 1), 6);
  std::vector<char> expected = own;
  for (auto v : spike.mesh.vertices())
    if (own[v.idx()])
      for (auto u : spike.mesh.vv_range(v)) expected[u.idx()] = 1;
  EXPECT_EQ(around(spike.mesh, pair, 1), expected);
  const std::vector<char> two = around(spike.mesh, pair, 2);
  EXPECT_GT(std::count(two.begin(), two.end(), 1), std::count(expected.begin(), expected.end(), 1));
}

}  // namespace
}  // namespace sketchsurf
