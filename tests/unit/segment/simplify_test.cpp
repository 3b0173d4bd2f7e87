#include "surfacing/segment/simplify.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

#include "surfacing/error.h"
#include "tests/support/shapes.h"

namespace sketchsurf {
namespace {

using V3 = Eigen::Vector3d;

struct Fixture {
  TriMesh mesh = testing::icosphere(4, 0.5);
  Sketch sketch;
  StrokeGraph graph;
  SimplifiedGraph coarse;
  Fixture() {
    // One short stroke on the sphere: most of the proxy is far from strokes.
    sketch.strokes.push_back(testing::sample_curve(
        [](double t) -> V3 { return V3(0.5 * std::cos(t), 0.5 * std::sin(t), 0.0837).normalized() * 0.5; },
        0.0, 1.0, 0.01));
    graph = associate(sketch, mesh);
    coarse = simplify_graph(mesh, graph, AssociationOptions{});
  }
};

TEST(SimplifyGraph, KeepsStrokeVerticesAndCrossedEdges) {
  const Fixture f;
  ASSERT_GT(f.coarse.collapses, 0);
  EXPECT_LT(f.coarse.vertex_count, f.graph.vertex_count() / 2);
  std::set<std::pair<int, int>> edges;
  for (const auto& e : f.coarse.edges) edges.insert({std::min(e[0], e[1]), std::max(e[0], e[1])});
  for (int v = 0; v < f.graph.vertex_count(); ++v)
    if (!f.graph.points_of(v).empty()) {
      EXPECT_EQ(f.coarse.coarse_to_fine[f.coarse.fine_to_coarse[v]], v);
    }
  for (std::size_t e = 0; e < f.graph.edges.size(); ++e) {
    if (!f.graph.crossed[e]) continue;
    const int a = f.coarse.fine_to_coarse[f.graph.edges[e][0]];
    const int b = f.coarse.fine_to_coarse[f.graph.edges[e][1]];
    EXPECT_TRUE(edges.count({std::min(a, b), std::max(a, b)})) << "crossed edge " << e << " lost";
  }
}

TEST(SimplifyGraph, RespectsValenceCapAndStaysConnected) {
  const Fixture f;
  std::vector<std::set<int>> adjacency(f.coarse.vertex_count);
  for (const auto& e : f.coarse.edges) {
    ASSERT_NE(e[0], e[1]);
    adjacency[e[0]].insert(e[1]);
    adjacency[e[1]].insert(e[0]);
  }
  for (const auto& a : adjacency) EXPECT_LE(a.size(), 12u);
  // Connected: a breadth-first search reaches every coarse vertex.
  std::vector<char> seen(f.coarse.vertex_count, 0);
  std::vector<int> queue{0};
  seen[0] = 1;
  for (std::size_t i = 0; i < queue.size(); ++i)
    for (int w : adjacency[queue[i]])
      if (!seen[w]) seen[w] = 1, queue.push_back(w);
  EXPECT_EQ(static_cast<int>(queue.size()), f.coarse.vertex_count);
  // Every coarse edge weight is positive; larger coarse triangles weigh more (App. C c_e).
  double fine_mean = 0, coarse_mean = 0;
  for (double w : f.graph.weights) fine_mean += w / f.graph.weights.size();
  for (double w : f.coarse.weights) {
    EXPECT_GT(w, 0.0);
    coarse_mean += w / f.coarse.weights.size();
  }
  EXPECT_GT(coarse_mean, fine_mean);
}

TEST(SimplifyGraph, PropagatesLabelsToMergedVertices) {
  const Fixture f;
  std::vector<int> coarse_labels(f.coarse.vertex_count);
  for (int c = 0; c < f.coarse.vertex_count; ++c) coarse_labels[c] = c % 3;
  const std::vector<int> fine = f.coarse.propagate(coarse_labels);
  ASSERT_EQ(static_cast<int>(fine.size()), f.graph.vertex_count());
  for (int v = 0; v < f.graph.vertex_count(); ++v) EXPECT_EQ(fine[v], f.coarse.fine_to_coarse[v] % 3);
  // The identity graph changes nothing.
  const SimplifiedGraph id = identity_graph(f.graph);
  EXPECT_EQ(id.vertex_count, f.graph.vertex_count());
  EXPECT_EQ(id.weights, f.graph.weights);
}

TEST(SimplifyGraph, RejectsMismatchedInput) {
  const Fixture f;
  const TriMesh other = testing::icosphere(2, 0.5);
  EXPECT_THROW(simplify_graph(other, f.graph, AssociationOptions{}), Error);
  SimplifyOptions bad;
  bad.max_valence = 2;
  EXPECT_THROW(simplify_graph(f.mesh, f.graph, AssociationOptions{}, bad), Error);
}

}  // namespace
}  // namespace sketchsurf
