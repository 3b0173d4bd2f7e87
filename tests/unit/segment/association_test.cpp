#include "surfacing/segment/association.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "surfacing/error.h"
#include "tests/support/shapes.h"

namespace sketchsurf {
namespace {

using V3 = Eigen::Vector3d;

// A closed circle on the sphere of radius `radius`, at height kHeight (off the icosphere's
// vertex rows, so that no vertex lies exactly on the stroke).
constexpr double kHeight = 0.0837;
Sketch circle_sketch(double radius) {
  const double r = std::sqrt(radius * radius - kHeight * kHeight);
  Sketch sketch;
  sketch.strokes.push_back(testing::sample_curve(
      [&](double t) { return V3(r * std::cos(t), r * std::sin(t), kHeight); }, 0.0, 2 * M_PI,
      0.01));
  return sketch;
}

double mean_edge_length(const TriMesh& mesh) {
  double sum = 0;
  for (auto e : mesh.edges()) sum += mesh.calc_edge_length(e);
  return sum / mesh.n_edges();
}

// Vertices reachable from `start` without crossing an edge marked crossed.
std::vector<char> reachable(const StrokeGraph& g, int start) {
  std::vector<std::vector<int>> adj(g.vertex_count());
  for (std::size_t e = 0; e < g.edges.size(); ++e)
    if (!g.crossed[e]) {
      adj[g.edges[e][0]].push_back(g.edges[e][1]);
      adj[g.edges[e][1]].push_back(g.edges[e][0]);
    }
  std::vector<char> seen(g.vertex_count(), 0);
  std::vector<int> stack{start};
  seen[start] = 1;
  while (!stack.empty()) {
    const int v = stack.back();
    stack.pop_back();
    for (int w : adj[v])
      if (!seen[w]) seen[w] = 1, stack.push_back(w);
  }
  return seen;
}

TEST(ClosestFaceTree, MatchesBruteForce) {
  const TriMesh mesh = testing::rounded_box_mesh(3, V3(0.5, 0.3, 0.2), 0.05);
  const Eigen::MatrixX3d V = vertex_matrix(mesh);
  const Eigen::MatrixX3i F = face_matrix(mesh);
  const ClosestFaceTree tree(V, F);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.8, 0.8);
  for (int i = 0; i < 200; ++i) {
    const V3 p(u(rng), u(rng), u(rng));
    V3 q;
    const int f = tree.closest_face(p, &q);
    ASSERT_GE(f, 0);
    // Brute force: the distance to the nearest vertex bounds the true distance from above, and
    // no triangle may contain a point closer than the tree's answer (sampled barycentrically).
    double best = std::numeric_limits<double>::infinity();
    for (int g = 0; g < F.rows(); ++g)
      for (double a = 0; a <= 1.0; a += 0.125)
        for (double b = 0; a + b <= 1.0; b += 0.125) {
          const V3 s = V.row(F(g, 0)) * (1 - a - b) + V.row(F(g, 1)) * a + V.row(F(g, 2)) * b;
          best = std::min(best, (s - p).norm());
        }
    EXPECT_LE((q - p).norm(), best + 1e-12);
  }
}

TEST(Associate, ClosedStrokeCutsTheSphere) {
  const TriMesh mesh = testing::icosphere(4, 0.5);
  const StrokeGraph g = associate(circle_sketch(0.5), mesh);
  const double h = mean_edge_length(mesh);
  ASSERT_GT(g.association_count(), 0u);
  EXPECT_EQ(g.skipped_segments, 0u);
  for (std::size_t e = 0; e < g.edges.size(); ++e) {
    if (!g.crossed[e]) continue;
    for (int v : g.edges[e]) EXPECT_LT(std::abs(g.positions(v, 2) - kHeight), 1.5 * h);
  }
  // The crossed edges separate the two hemispheres.
  int north = 0, south = 0;
  g.positions.col(2).maxCoeff(&north);
  g.positions.col(2).minCoeff(&south);
  EXPECT_FALSE(reachable(g, north)[south]);
  // Every attached point lies on the stroke and near its vertex.
  for (int v = 0; v < g.vertex_count(); ++v)
    for (int p : g.points_of(v)) {
      const V3 x = g.points.row(p);
      EXPECT_NEAR(x.z(), kHeight, 1e-12);
      EXPECT_NEAR(x.norm(), 0.5, 1e-3);
      EXPECT_LT((x - V3(g.positions.row(v))).norm(), 2.0 * h);
    }
}

TEST(Associate, WeightsAreLowOnCrossedEdges) {
  const TriMesh mesh = testing::icosphere(3, 0.5);
  AssociationOptions options;
  options.scale_by_edge_size = false;
  const StrokeGraph g = associate(circle_sketch(0.5), mesh, options);
  for (std::size_t e = 0; e < g.edges.size(); ++e)
    EXPECT_EQ(g.weights[e], g.crossed[e] ? 1.0 : 100.0);
  // With the App. C scaling, the weights average the unscaled ones (c_e / mean c_e ~ 1).
  const StrokeGraph scaled = associate(circle_sketch(0.5), mesh);
  double mean_ratio = 0;
  for (std::size_t e = 0; e < g.edges.size(); ++e) mean_ratio += scaled.weights[e] / g.weights[e];
  EXPECT_NEAR(mean_ratio / g.edges.size(), 1.0, 1e-9);
}

TEST(Associate, CreaseGuidesMakeTheUndrawnEdgesBetweenSectionsCheap) {
  // A box drawn with three sections and no edge: between the sections, its edges are crossed by
  // the guides joining the sections' corners, with no stroke point added.
  const V3 half(0.2, 0.1, 0.15);
  const TriMesh mesh = testing::rounded_box_mesh(4, half, 0.01);
  const Sketch sketch = testing::box_sections_sketch(half, {-0.1, 0.0, 0.1});
  AssociationOptions without;
  without.guides.enabled = false;
  const StrokeGraph plain = associate(sketch, mesh, without), guided = associate(sketch, mesh);
  EXPECT_EQ(plain.guides, 0u);
  EXPECT_EQ(guided.guides, 8u);
  EXPECT_EQ(guided.points, plain.points);
  EXPECT_EQ(guided.point_indices, plain.point_indices);
  // Crossed edges near the middle of each box edge between two sections.
  const double h = mean_edge_length(mesh);
  auto crossed_near = [&](const StrokeGraph& g, const V3& p) {
    for (std::size_t e = 0; e < g.edges.size(); ++e)
      if (g.crossed[e] && (g.positions.row(g.edges[e][0]).transpose() - p).norm() < 1.5 * h) return true;
    return false;
  };
  for (double x : {-0.05, 0.05})
    for (double y : {-half.y(), half.y()})
      for (double z : {-half.z(), half.z()}) {
        EXPECT_FALSE(crossed_near(plain, V3(x, y, z)));
        EXPECT_TRUE(crossed_near(guided, V3(x, y, z))) << x << " " << y << " " << z;
      }
  // The faces between sections stay uncrossed.
  EXPECT_FALSE(crossed_near(guided, V3(0.05, 0.0, half.z())));
}

TEST(Associate, IndependentOfThreadsAndScale) {
  const TriMesh mesh = testing::rounded_box_mesh(3, V3(0.5, 0.5, 0.5), 0.1);
  const Sketch sketch = testing::cube_sketch(1.0);
  AssociationOptions one;
  one.threads = 1;
  AssociationOptions two;
  two.threads = 2;
  const StrokeGraph a = associate(sketch, mesh, one), b = associate(sketch, mesh, two);
  EXPECT_EQ(a.point_indices, b.point_indices);
  EXPECT_EQ(a.crossed, b.crossed);
  EXPECT_EQ(a.points, b.points);

  Sketch big = sketch;
  testing::transform(big, 1e3, V3(5, -2, 1));
  TriMesh big_mesh = mesh;
  for (auto v : big_mesh.vertices())
    big_mesh.set_point(v, to_openmesh(1e3 * to_eigen(big_mesh.point(v)) + V3(5, -2, 1)));
  const StrokeGraph c = associate(big, big_mesh);
  EXPECT_EQ(a.crossed, c.crossed);
  EXPECT_EQ(a.point_offsets, c.point_offsets);
}

TEST(Associate, IgnoredStrokesAndEmptyProxy) {
  const TriMesh mesh = testing::icosphere(2, 0.5);
  Sketch sketch = circle_sketch(0.5);
  sketch.strokes[0].ignored = true;
  const StrokeGraph g = associate(sketch, mesh);
  EXPECT_EQ(g.association_count(), 0u);
  EXPECT_EQ(std::count(g.crossed.begin(), g.crossed.end(), 1), 0);

  TriMesh empty;
  empty.add_vertex(TriMesh::Point(0, 0, 0));
  EXPECT_THROW(associate(sketch, empty), Error);
  AssociationOptions bad;
  bad.crossed_weight = -1;
  EXPECT_THROW(associate(sketch, mesh, bad), Error);
}

}  // namespace
}  // namespace sketchsurf
