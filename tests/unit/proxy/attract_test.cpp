// Least-Squares Mesh attraction of a rough user proxy.

#include "surfacing/proxy/attract.h"

#include <gtest/gtest.h>

#include <random>

#include "surfacing/error.h"
#include "surfacing/proxy/proxy.h"
#include "tests/support/shapes.h"

namespace sketchsurf {
namespace {

// Median over stroke points of the exact distance to the mesh surface (brute force).
double median_surface_distance(const TriMesh& mesh, const Sketch& sketch) {
  std::vector<double> d;
  for (const auto& s : sketch.strokes)
    for (const auto& p : s.points) {
      double best = 1e300;
      for (const auto f : mesh.faces()) {
        auto h = f.halfedge();
        const Eigen::Vector3d a = to_eigen(mesh.point(h.from())), b = to_eigen(mesh.point(h.to())),
                              c = to_eigen(mesh.point(h.next().to()));
        // Closest point on triangle by barycentric clamping over a fine grid of the edges is
        // enough here: use the plane distance when the projection is inside, else the edges.
        const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
        const Eigen::Vector3d q = p - n * n.dot(p - a);
        const bool inside = (b - a).cross(q - a).dot(n) >= 0 && (c - b).cross(q - b).dot(n) >= 0 &&
                            (a - c).cross(q - c).dot(n) >= 0;
        double dist = inside ? std::abs(n.dot(p - a)) : 1e300;
        for (auto [u, v] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}}) {
          const double t = std::clamp((p - u).dot(v - u) / (v - u).squaredNorm(), 0.0, 1.0);
          dist = std::min(dist, (p - (u + t * (v - u))).norm());
        }
        best = std::min(best, dist);
      }
      d.push_back(best);
    }
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  return d[d.size() / 2];
}

TEST(Attract, RoughBoxIsPulledOntoACurvedSketch) {
  // A sphere sketch (diagonal ~1.7 x 0.5) inside a coarse box 1.5 times larger.
  const Sketch sketch = testing::sphere_sketch(0.5, 4);
  const double diagonal = sketch.bounding_box().diagonal();
  const TriMesh box = testing::rounded_box_mesh(1, Eigen::Vector3d::Constant(0.6), 0.0);
  ProxyOptions options;
  options.edge = 0.02;  // keep the brute-force distance check affordable
  ProxyReport report;
  const TriMesh proxy = attract_proxy(box, sketch, options, {}, &report);
  const MeshTopology t = mesh_topology(proxy);
  EXPECT_TRUE(t.closed());
  EXPECT_EQ(t.genus, 0);
  EXPECT_GT(median_surface_distance(box, sketch), 0.05 * diagonal);  // rough indeed
  EXPECT_LT(median_surface_distance(proxy, sketch), 0.01 * diagonal);
  EXPECT_LT(report.median_distance_after, report.median_distance_before);
  EXPECT_GT(report.anchors, 0u);
}

TEST(Attract, CoarseSolveThenSubdivisionMatchesTheFineSolve) {
  // The default solves on a mesh with twice the target edge and subdivides back: as close to the
  // strokes as solving at full resolution, with edges of the target length.
  const Sketch sketch = testing::sphere_sketch(0.5, 4);
  const double diagonal = sketch.bounding_box().diagonal();
  const TriMesh box = testing::rounded_box_mesh(1, Eigen::Vector3d::Constant(0.6), 0.0);
  ProxyOptions options;
  options.edge = 0.02;
  ASSERT_EQ(options.attract_levels, 1);
  const TriMesh coarse_solve = attract_proxy(box, sketch, options);
  options.attract_levels = 0;
  const TriMesh fine_solve = attract_proxy(box, sketch, options);
  EXPECT_LT(median_surface_distance(coarse_solve, sketch), 0.01 * diagonal);
  EXPECT_LT(median_surface_distance(coarse_solve, sketch),
            median_surface_distance(fine_solve, sketch) + 0.002 * diagonal);
  // The box shrinks onto the sphere either way (edges ~0.6 of the target); the two meshes have
  // about the same resolution.
  auto mean_edge = [](const TriMesh& mesh) {
    double total = 0.0;
    for (const auto e : mesh.edges()) total += mesh.calc_edge_length(e);
    return total / static_cast<double>(mesh.n_edges());
  };
  EXPECT_NEAR(mean_edge(coarse_solve) / mean_edge(fine_solve), 1.0, 0.25);
  EXPECT_TRUE(mesh_topology(coarse_solve).closed());
  EXPECT_EQ(mesh_topology(coarse_solve).genus, 0);
}

TEST(Attract, NearestVertexDistanceMatchesBruteForce) {
  const TriMesh mesh = testing::icosphere(3, 0.5, Eigen::Vector3d(0.1, -0.2, 0.3));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  for (const int count : {1, 2, 101}) {  // odd and even counts: the median is an element
    Eigen::MatrixX3d targets(count, 3);
    for (int i = 0; i < count; ++i) targets.row(i) << u(rng), u(rng), u(rng);  // inside and out
    std::vector<double> brute;
    for (int i = 0; i < count; ++i) {
      double best = 1e300;
      for (const auto v : mesh.vertices())
        best = std::min(best, (to_eigen(mesh.point(v)) - targets.row(i).transpose()).norm());
      brute.push_back(best);
    }
    std::nth_element(brute.begin(), brute.begin() + count / 2, brute.end());
    EXPECT_DOUBLE_EQ(median_nearest_vertex_distance(mesh, targets, 2), brute[count / 2]);
  }
}

TEST(Attract, FarAwayProxyIsRefused) {
  const Sketch sketch = testing::sphere_sketch(0.5, 4);
  TriMesh far = testing::icosphere(2, 0.5, Eigen::Vector3d(10, 0, 0));
  try {
    attract_proxy(far, sketch, {});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Processing);
    EXPECT_NE(std::string(e.what()).find("far from the strokes"), std::string::npos);
  }
  EXPECT_THROW(attract_proxy(TriMesh(), sketch, {}), Error);
}

}  // namespace
}  // namespace sketchsurf
