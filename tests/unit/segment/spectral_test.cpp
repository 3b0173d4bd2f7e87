#include "surfacing/segment/spectral.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <vector>

#include "surfacing/error.h"
#include "surfacing/mesh.h"
#include "tests/support/shapes.h"

namespace sketchsurf {
namespace {

struct Graph {
  int n = 0;
  std::vector<std::array<int, 2>> edges;
  std::vector<double> affinities;
};

void add_clique(Graph& g, int first, int size, double affinity) {
  for (int u = first; u < first + size; ++u)
    for (int v = u + 1; v < first + size; ++v) {
      g.edges.push_back({u, v});
      g.affinities.push_back(affinity);
    }
  g.n = std::max(g.n, first + size);
}

int cluster_count(const std::vector<int>& labels) {
  return static_cast<int>(std::set<int>(labels.begin(), labels.end()).size());
}

// Vertices of `truth` class c all share one cluster and no other class uses it, for every class,
// except at most `allowed` vertices.
int mismatches(const std::vector<int>& labels, const std::vector<int>& truth) {
  std::map<int, std::map<int, int>> votes;  // truth class -> cluster -> count
  for (std::size_t v = 0; v < labels.size(); ++v) ++votes[truth[v]][labels[v]];
  std::map<int, int> majority;
  for (const auto& [cls, counts] : votes)
    majority[cls] = std::max_element(counts.begin(), counts.end(), [](auto& a, auto& b) {
                      return a.second < b.second;
                    })->first;
  std::set<int> used;
  for (const auto& [cls, cluster] : majority) used.insert(cluster);
  EXPECT_EQ(used.size(), majority.size()) << "two classes share their majority cluster";
  int wrong = 0;
  for (std::size_t v = 0; v < labels.size(); ++v) wrong += labels[v] != majority[truth[v]];
  return wrong;
}

TEST(Spectral, TwoCliquesJoinedByAWeakEdgeSplit) {
  Graph g;
  add_clique(g, 0, 7, 100.0);
  add_clique(g, 7, 5, 100.0);
  g.edges.push_back({3, 9});
  g.affinities.push_back(1.0);
  const std::vector<int> labels = spectral_clustering(g.n, g.edges, g.affinities, 2, 1);
  ASSERT_EQ(labels.size(), 12u);
  for (int v = 0; v < 12; ++v) EXPECT_EQ(labels[v], v < 7 ? 0 : 1) << v;
}

// The rounded-box proxy of the tests with the paper's weights: 1 on edges between vertices of
// different cube faces (edges "crossed by a stroke" along the cube's edges), 100 elsewhere.
struct CubeGraph {
  Graph graph;
  std::vector<int> face;  // 0..5 per vertex
};

CubeGraph cube_graph(int subdivisions) {
  const Eigen::Vector3d half(0.5, 0.5, 0.5);
  const TriMesh mesh = testing::rounded_box_mesh(subdivisions, half, 0.05);
  CubeGraph c;
  c.graph.n = static_cast<int>(mesh.n_vertices());
  for (auto v : mesh.vertices()) {
    const Eigen::Vector3d p = to_eigen(mesh.point(v));
    Eigen::Index axis = 0;
    p.cwiseAbs().maxCoeff(&axis);
    c.face.push_back(static_cast<int>(2 * axis + (p[axis] > 0 ? 1 : 0)));
  }
  for (auto e : mesh.edges()) {
    const auto h = mesh.halfedge_handle(e, 0);
    const int a = mesh.from_vertex_handle(h).idx(), b = mesh.to_vertex_handle(h).idx();
    c.graph.edges.push_back({a, b});
    c.graph.affinities.push_back(c.face[a] == c.face[b] ? 100.0 : 1.0);
  }
  return c;
}

TEST(Spectral, CubeMeshClustersFacesApart) {
  // 3 subdivisions: 642 vertices (dense eigen-solver); 4: 2562 vertices (Spectra shift-invert).
  for (int subdivisions : {3, 4}) {
    const CubeGraph c = cube_graph(subdivisions);
    const std::vector<int> labels =
        spectral_clustering(c.graph.n, c.graph.edges, c.graph.affinities, 6, 123);
    EXPECT_EQ(cluster_count(labels), 6);
    EXPECT_EQ(mismatches(labels, c.face), 0) << "subdivisions " << subdivisions;
  }
}

TEST(Spectral, PreparedClusteringServesSmallerK) {
  const CubeGraph c = cube_graph(4);
  const SpectralClustering prepared(c.graph.n, c.graph.edges, c.graph.affinities, 12);
  const std::vector<int> six = prepared.cluster(6, 5);
  EXPECT_EQ(mismatches(six, c.face), 0);
  // k = 12 over-segments, but no cluster straddles two cube faces.
  const std::vector<int> twelve = prepared.cluster(12, 5);
  EXPECT_EQ(cluster_count(twelve), 12);
  std::map<int, std::set<int>> faces_of_cluster;
  for (int v = 0; v < c.graph.n; ++v) faces_of_cluster[twelve[v]].insert(c.face[v]);
  for (const auto& [cluster, faces] : faces_of_cluster) EXPECT_EQ(faces.size(), 1u) << cluster;
  EXPECT_THROW(prepared.cluster(13, 5), Error);
}

TEST(Spectral, ChainOfCliquesWithNearlyDegenerateSpectrum) {
  // 200 cliques of 10 chained by bridges of affinity 1e-9: 200 eigenvalues within ~1e-10 of 0, a
  // hard case for the shift-invert Lanczos solver (2000 vertices, not the dense path). k = 50
  // clusters must never split a clique.
  Graph g;
  for (int c = 0; c < 200; ++c) {
    add_clique(g, 10 * c, 10, 1.0);
    if (c > 0) {
      g.edges.push_back({10 * c - 1, 10 * c});
      g.affinities.push_back(1e-9);
    }
  }
  const std::vector<int> labels = spectral_clustering(g.n, g.edges, g.affinities, 50, 3);
  EXPECT_EQ(cluster_count(labels), 50);
  for (int c = 0; c < 200; ++c)
    for (int i = 1; i < 10; ++i) EXPECT_EQ(labels[10 * c + i], labels[10 * c]) << "clique " << c;
}

TEST(Spectral, DisconnectedGraphs) {
  Graph g;
  add_clique(g, 0, 8, 1.0);
  add_clique(g, 8, 5, 1.0);
  add_clique(g, 13, 3, 1.0);
  g.n = 17;  // vertex 16 is isolated
  g.edges.push_back({0, 13});
  g.affinities.push_back(0.0);  // a zero-affinity edge connects nothing
  std::vector<int> component(17);
  for (int v = 0; v < 17; ++v) component[v] = v < 8 ? 0 : v < 13 ? 1 : v < 16 ? 2 : 3;

  const std::vector<int> four = spectral_clustering(g.n, g.edges, g.affinities, 4, 1);
  EXPECT_EQ(cluster_count(four), 4);
  EXPECT_EQ(mismatches(four, component), 0);
  // Fewer clusters than components: the largest ones keep their own cluster.
  const std::vector<int> two = spectral_clustering(g.n, g.edges, g.affinities, 2, 1);
  EXPECT_EQ(cluster_count(two), 2);
  for (int v = 0; v < 17; ++v) EXPECT_EQ(two[v] == two[0], v < 8) << v;
  // More clusters than components: components never share a cluster.
  const std::vector<int> six = spectral_clustering(g.n, g.edges, g.affinities, 6, 1);
  EXPECT_LE(cluster_count(six), 6);
  for (int u = 0; u < 17; ++u)
    for (int v = 0; v < 17; ++v)
      if (component[u] != component[v]) {
        EXPECT_NE(six[u], six[v]);
      }
}

TEST(Spectral, MoreClustersThanVertices) {
  Graph g;
  add_clique(g, 0, 4, 1.0);
  const std::vector<int> labels = spectral_clustering(g.n, g.edges, g.affinities, 10, 1);
  EXPECT_EQ(labels, (std::vector<int>{0, 1, 2, 3}));
  EXPECT_TRUE(spectral_clustering(0, {}, {}, 3, 1).empty());
}

TEST(Spectral, DeterministicForASeedWhateverTheThreadCount) {
  const CubeGraph c = cube_graph(4);
  SpectralOptions one, two;
  one.threads = 1;
  two.threads = 2;
  const auto a = spectral_clustering(c.graph.n, c.graph.edges, c.graph.affinities, 20, 9, one);
  const auto b = spectral_clustering(c.graph.n, c.graph.edges, c.graph.affinities, 20, 9, two);
  const auto again = spectral_clustering(c.graph.n, c.graph.edges, c.graph.affinities, 20, 9, two);
  EXPECT_EQ(a, b);
  EXPECT_EQ(b, again);
  EXPECT_LE(cluster_count(a), 20);
}

TEST(Spectral, RejectsBadInput) {
  const std::vector<std::array<int, 2>> edges = {{0, 1}};
  EXPECT_THROW(spectral_clustering(2, edges, {1.0}, 0, 1), Error);
  EXPECT_THROW(spectral_clustering(2, edges, {-1.0}, 2, 1), Error);
  EXPECT_THROW(spectral_clustering(2, edges, {1.0, 2.0}, 2, 1), Error);
  try {
    spectral_clustering(2, {{0, 2}}, {1.0}, 2, 1);
    FAIL() << "no exception";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Usage);
    EXPECT_NE(std::string(e.what()).find("edge 0"), std::string::npos) << e.what();
  }
  SpectralOptions options;
  options.kmeans_restarts = 0;
  EXPECT_THROW(spectral_clustering(2, edges, {1.0}, 2, 1, options), Error);
}

}  // namespace
}  // namespace sketchsurf
