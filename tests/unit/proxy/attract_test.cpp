// Least-Squares Mesh attraction of a rough user proxy.

#include "surfacing/proxy/attract.h"

#include <gtest/gtest.h>

#include <Eigen/SparseCholesky>

#include <cmath>
#include <functional>
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

TEST(Attract, SolveMatchesADirectSolveAndIgnoresTheThreadCount) {
  // One round on a 10k-vertex sphere pulled towards a larger sphere's strokes: the system of
  // attract.h solved here with Eigen's default (AMD) ordering gives the same positions to
  // rounding as the METIS-ordered solve, whose result has the same bits on 1, 2 or 5 threads.
  const TriMesh sphere = testing::icosphere(5, 0.5);
  const Sketch sketch = testing::sphere_sketch(0.6, 4);
  std::vector<Eigen::Vector3d> points;
  for (const auto& s : sketch.strokes)
    for (std::size_t i = 0; i < s.points.size(); i += 4) points.push_back(s.points[i]);
  Eigen::MatrixX3d targets(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i) targets.row(static_cast<Eigen::Index>(i)) = points[i];

  AttractOptions options;
  options.rounds = 1;
  const auto n = static_cast<Eigen::Index>(sphere.n_vertices());
  const Eigen::MatrixX3d V = vertex_matrix(sphere);
  std::vector<Eigen::Triplet<double>> lap;
  for (const auto v : sphere.vertices()) {
    lap.emplace_back(v.idx(), v.idx(), 1.0);
    for (const auto w : v.vertices()) lap.emplace_back(v.idx(), w.idx(), -1.0 / sphere.valence(v));
  }
  Eigen::SparseMatrix<double> L(n, n);
  L.setFromTriplets(lap.begin(), lap.end());
  const double w2 = options.weight * options.weight, keep = 1e-8 * w2;
  Eigen::SparseMatrix<double> A = (L.transpose() * L).pruned();
  Eigen::VectorXd count = Eigen::VectorXd::Zero(n);
  Eigen::MatrixX3d sum = Eigen::MatrixX3d::Zero(n, 3);
  for (Eigen::Index t = 0; t < targets.rows(); ++t) {  // nearest vertex, ties to the lower index
    Eigen::Index nearest = 0;
    (V.rowwise() - targets.row(t)).rowwise().squaredNorm().minCoeff(&nearest);
    count[nearest] += 1.0;
    sum.row(nearest) += targets.row(t);
  }
  Eigen::MatrixX3d rhs = keep * V;
  for (Eigen::Index v = 0; v < n; ++v) {
    A.coeffRef(v, v) += keep + (count[v] > 0 ? w2 : 0.0);
    if (count[v] > 0) rhs.row(v) += w2 * sum.row(v) / count[v];
  }
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> direct(A);
  ASSERT_EQ(direct.info(), Eigen::Success);
  const Eigen::MatrixX3d expected = direct.solve(rhs);

  std::vector<TriMesh> results;
  for (const unsigned threads : {1u, 2u, 5u}) {
    options.threads = threads;
    TriMesh mesh = sphere;
    attract_to_points(mesh, targets, options);
    results.push_back(mesh);
  }
  EXPECT_GT(vertex_matrix(results[0]).rowwise().norm().mean(), 0.55);  // pulled outwards
  EXPECT_LT((vertex_matrix(results[0]) - expected).cwiseAbs().maxCoeff(), 1e-9);
  for (const auto v : sphere.vertices()) {
    ASSERT_EQ(results[1].point(v), results[0].point(v));
    ASSERT_EQ(results[2].point(v), results[0].point(v));
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

TEST(Attract, MeshesThatCannotBeAProxyAreRefusedBeforeAnyWork) {
  const Sketch sketch = testing::sphere_sketch(0.5, 4);
  const TriMesh sphere = testing::icosphere(2, 0.55);
  EXPECT_EQ(proxy_mesh_problem(sphere, sketch), "");
  // The same at any scale, when the sketch is scaled with it.
  for (const double scale : {1e-3, 1e3}) {
    Sketch scaled_sketch = sketch;
    for (Stroke& stroke : scaled_sketch.strokes)
      for (auto& p : stroke.points) p *= scale;
    TriMesh scaled = sphere;
    for (const auto v : scaled.vertices()) scaled.set_point(v, scaled.point(v) * scale);
    EXPECT_EQ(proxy_mesh_problem(scaled, scaled_sketch), "") << scale;
  }
  auto problem = [&](const std::function<void(TriMesh&)>& edit) {
    TriMesh mesh = sphere;
    edit(mesh);
    return proxy_mesh_problem(mesh, sketch);
  };
  auto scaled_by = [](double factor) {
    return [factor](TriMesh& m) {
      for (const auto v : m.vertices()) m.set_point(v, m.point(v) * factor);
    };
  };
  // The sphere's box is 1.1 times the strokes'.
  EXPECT_NE(problem(scaled_by(1e6)).find("is 1.1e+06 times larger than the strokes"), std::string::npos)
      << problem(scaled_by(1e6));
  EXPECT_NE(problem(scaled_by(11)).find("times larger"), std::string::npos);
  EXPECT_EQ(problem(scaled_by(5)), "");  // rough proxies may well be larger than the strokes
  EXPECT_NE(problem(scaled_by(1e-4)).find("times smaller than the strokes"), std::string::npos);
  const std::string far_vertex =
      problem([](TriMesh& m) { m.set_point(TriMesh::VertexHandle(7), OpenMesh::Vec3d(1e300, 0, 0)); });
  EXPECT_NE(far_vertex.find("has vertex 7 at (1e+300, 0, 0): a coordinate is beyond +-1e+12"),
            std::string::npos)
      << far_vertex;
  const std::string nan_vertex = problem([](TriMesh& m) {
    m.set_point(TriMesh::VertexHandle(3), OpenMesh::Vec3d(0, std::nan(""), 0));
  });
  EXPECT_NE(nan_vertex.find("has vertex 3 at"), std::string::npos) << nan_vertex;
  EXPECT_NE(nan_vertex.find("not finite"), std::string::npos) << nan_vertex;
  const std::string point = problem([](TriMesh& m) {
    for (const auto v : m.vertices()) m.set_point(v, OpenMesh::Vec3d(0.1, 0.2, 0.3));
  });
  EXPECT_NE(point.find("has no area"), std::string::npos) << point;
  const std::string line = problem([](TriMesh& m) {
    for (const auto v : m.vertices()) m.set_point(v, OpenMesh::Vec3d(m.point(v)[0], 0, 0));
  });
  EXPECT_NE(line.find("has no area"), std::string::npos) << line;
  EXPECT_NE(proxy_mesh_problem(TriMesh(), sketch).find("no triangles"), std::string::npos);
  // attract_proxy refuses a mesh a million times too large at once (remeshing it at the sketch's
  // edge length would not end).
  TriMesh huge = sphere;
  scaled_by(1e6)(huge);
  try {
    attract_proxy(huge, sketch, {});
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Processing);
    EXPECT_NE(std::string(e.what()).find("the proxy mesh is 1.1e+06 times larger"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace sketchsurf
