// eval: distances against a brute-force computation on small meshes, known offsets between
// spheres, and creases of a box against a sharp and a rounded result.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "surfacing/closest_face.h"
#include "surfacing/error.h"
#include "surfacing/quality/eval.h"
#include "tests/support/shapes.h"

namespace sketchsurf {
namespace {

double brute_force_distance(const Eigen::Vector3d& p, const TriMesh& mesh) {
  double best = std::numeric_limits<double>::infinity();
  for (auto f : mesh.faces()) {
    Eigen::Vector3d corner[3];
    int k = 0;
    for (auto v : mesh.fv_range(f)) corner[k++] = to_eigen(mesh.point(v));
    best = std::min(best, (closest_on_triangle(p, corner[0], corner[1], corner[2]) - p).norm());
  }
  return best;
}

double diagonal_of(const TriMesh& mesh) {
  const Eigen::MatrixX3d V = vertex_matrix(mesh);
  return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
}

TEST(Eval, DistancesEqualBruteForceOnTheSameSamples) {
  const TriMesh truth = testing::icosphere(2, 1.0);
  const TriMesh result = testing::rounded_box_mesh(2, Eigen::Vector3d(0.9, 0.7, 1.1), 0.2);
  EvalOptions options;
  options.samples = 500;
  const Evaluation e = evaluate(result, truth, options);
  const double diagonal = diagonal_of(truth);
  EXPECT_NEAR(e.diagonal, diagonal, 1e-12);

  const auto expected = [&](const TriMesh& from, const TriMesh& to, unsigned seed) {
    const SurfaceSamples s = sample_surface(from, options.samples, seed);
    std::vector<double> d;
    for (Eigen::Index i = 0; i < s.points.rows(); ++i)
      d.push_back(brute_force_distance(s.points.row(i), to) / diagonal);
    return distance_stats(d);
  };
  const DistanceStats accuracy = expected(result, truth, options.seed);
  const DistanceStats completeness = expected(truth, result, options.seed + 1);
  EXPECT_NEAR(e.accuracy.median, accuracy.median, 1e-12);
  EXPECT_NEAR(e.accuracy.p95, accuracy.p95, 1e-12);
  EXPECT_NEAR(e.accuracy.max, accuracy.max, 1e-12);
  EXPECT_NEAR(e.completeness.median, completeness.median, 1e-12);
  EXPECT_NEAR(e.completeness.p99, completeness.p99, 1e-12);
  EXPECT_GT(e.accuracy.max, 0.01);  // the shapes differ: the test is not vacuous
  ASSERT_EQ(e.vertex_deviation.size(), result.n_vertices());
  for (auto v : result.vertices())
    EXPECT_NEAR(e.vertex_deviation[v.idx()], brute_force_distance(to_eigen(result.point(v)), truth) / diagonal, 1e-12);
}

TEST(Eval, ConcentricSpheresAreTheRadiusDifferenceApart) {
  const TriMesh truth = testing::icosphere(4, 1.0);
  const TriMesh result = testing::icosphere(4, 1.05);
  const Evaluation e = evaluate(result, truth);
  // Chords of a fine icosphere lie within 0.3% of the radius below the sphere.
  EXPECT_NEAR(e.accuracy.median * e.diagonal, 0.05, 0.004);
  EXPECT_NEAR(e.completeness.median * e.diagonal, 0.05, 0.004);
  EXPECT_NEAR(e.accuracy.max * e.diagonal, 0.05, 0.006);
  EXPECT_LE(e.accuracy.median, e.accuracy.p95);
  EXPECT_LE(e.accuracy.p95, e.accuracy.p99);
  EXPECT_LE(e.accuracy.p99, e.accuracy.max);
}

TEST(Eval, ASurfaceAgainstItselfIsExact) {
  const TriMesh mesh = testing::torus_mesh(48, 16, 0.5, 0.2);
  const Evaluation e = evaluate(mesh, mesh);
  EXPECT_LT(e.accuracy.max, 1e-12);
  EXPECT_LT(e.completeness.max, 1e-12);
  EXPECT_EQ(e.creases.sharp_edges, 0u);  // a fine torus has no sharp edge
}

TEST(Eval, TheSameSurfaceListedInAnotherOrderScoresTheSame) {
  // A result that is its proxy with each face's corners rotated and the faces reversed (as the
  // pipeline may hand it back) must score exactly as the proxy did.
  const TriMesh truth = testing::icosphere(4, 1.0);
  const TriMesh a = testing::rounded_box_mesh(3, Eigen::Vector3d(0.9, 0.8, 0.85), 0.3);
  TriMesh b;
  for (auto v : a.vertices()) b.add_vertex(a.point(v));
  std::vector<std::vector<TriMesh::VertexHandle>> faces;
  for (auto f : a.faces()) {
    std::vector<TriMesh::VertexHandle> c;
    for (auto v : a.fv_range(f)) c.push_back(TriMesh::VertexHandle(v.idx()));
    std::rotate(c.begin(), c.begin() + 1 + f.idx() % 2, c.end());
    faces.push_back(c);
  }
  for (auto it = faces.rbegin(); it != faces.rend(); ++it) b.add_face(*it);
  ASSERT_EQ(b.n_faces(), a.n_faces());
  const Evaluation ea = evaluate(a, truth), eb = evaluate(b, truth);
  EXPECT_GT(ea.accuracy.p95, 1e-3);  // the shapes differ: the test is not vacuous
  EXPECT_EQ(ea.accuracy.median, eb.accuracy.median);
  EXPECT_EQ(ea.accuracy.p95, eb.accuracy.p95);
  EXPECT_EQ(ea.accuracy.max, eb.accuracy.max);
  // The truth's samples are the same; their distances to a face differ in the last bits with
  // the order of its corners.
  EXPECT_NEAR(ea.completeness.p95, eb.completeness.p95, 1e-12);
}

TEST(Eval, MissingPartIsSeenByCompletenessOnly) {
  // Truth: two spheres; result: one of them. Accuracy is perfect, completeness is not.
  TriMesh truth = testing::icosphere(3, 0.5);
  append_mesh(truth, testing::icosphere(3, 0.5, Eigen::Vector3d(2, 0, 0)));
  const TriMesh result = testing::icosphere(3, 0.5);
  const Evaluation e = evaluate(result, truth);
  EXPECT_LT(e.accuracy.max, 1e-9);
  EXPECT_GT(e.completeness.p95, 0.3);  // half the truth is ~1.5 units from the result
}

TEST(Eval, BoxCreasesAreFoundOnASharpResultAndMissedOnARoundOne) {
  const TriMesh box = testing::rounded_box_mesh(4, Eigen::Vector3d(0.5, 0.5, 0.5), 0.0);
  const Evaluation same = evaluate(box, box);
  ASSERT_GT(same.creases.sharp_edges, 0u);
  EXPECT_GT(same.creases.found, 0.95);
  EXPECT_LT(same.creases.error.median, 1.0);

  const TriMesh round = testing::rounded_box_mesh(4, Eigen::Vector3d(0.5, 0.5, 0.5), 0.25);
  const Evaluation rounded = evaluate(round, box);
  EXPECT_LT(rounded.creases.found, 0.5);
}

TEST(Eval, InvalidOptionsAndEmptyMeshesAreRefused) {
  const TriMesh sphere = testing::icosphere(1);
  EvalOptions options;
  options.samples = 0;
  EXPECT_THROW(evaluate(sphere, sphere, options), Error);
  EXPECT_THROW(evaluate(TriMesh{}, sphere), Error);
  EXPECT_THROW(evaluate(sphere, TriMesh{}), Error);
}

TEST(Eval, SamplesAreDeterministicAndCoverTheAreaEvenly) {
  const TriMesh mesh = testing::rounded_box_mesh(5, Eigen::Vector3d(1.0, 0.5, 0.25), 0.0);
  const SurfaceSamples a = sample_surface(mesh, 20000, 7), b = sample_surface(mesh, 20000, 7);
  EXPECT_TRUE(a.points == b.points);
  EXPECT_FALSE(a.points == sample_surface(mesh, 20000, 8).points);
  // Total area, and the share of the faces on the two sides normal to x.
  double total = 0.0, sides = 0.0;
  std::vector<bool> on_side(mesh.n_faces());
  for (auto f : mesh.faces()) {
    const double area = mesh.calc_face_area(f);
    total += area;
    bool side = true;
    for (auto v : mesh.fv_range(f)) side &= std::abs(mesh.point(v)[0]) > 1.0 - 1e-9;
    on_side[f.idx()] = side;
    if (side) sides += area;
  }
  EXPECT_NEAR(a.area, total, 1e-9);
  ASSERT_GT(sides, 0.5);
  double hits = 0.0;
  for (int f : a.faces) hits += on_side[f];
  EXPECT_NEAR(hits / static_cast<double>(a.faces.size()), sides / total, 0.01);
}

}  // namespace
}  // namespace sketchsurf
