// The ground-truth mesh of ../shared/data/gt (label `data`): it reads as the closed genus-0 mesh
// its README describes, synth draws on it, and eval measures known displacements of it.

#include <gtest/gtest.h>

#include <filesystem>

#include "surfacing/closest_face.h"
#include "surfacing/proxy/proxy.h"
#include "surfacing/quality/eval.h"
#include "surfacing/quality/synth.h"
#include "surfacing/sketch/io/mesh_io.h"

namespace sketchsurf {
namespace {

TriMesh spot() { return read_mesh(std::filesystem::path(SKETCHSURF_DATA_DIR) / "gt" / "spot.ply"); }

double diagonal_of(const TriMesh& mesh) {
  const Eigen::MatrixX3d V = vertex_matrix(mesh);
  return (V.colwise().maxCoeff() - V.colwise().minCoeff()).norm();
}

TEST(QualityData, SpotIsAClosedGenusZeroMesh) {
  const TriMesh mesh = spot();
  EXPECT_EQ(mesh.n_vertices(), 2930u);
  EXPECT_EQ(mesh.n_faces(), 5856u);
  const MeshTopology t = mesh_topology(mesh);
  EXPECT_TRUE(t.closed());
  EXPECT_EQ(t.genus, 0);
  EXPECT_EQ(t.components, 1u);
}

TEST(QualityData, SynthStrokesLieOnSpot) {
  const TriMesh mesh = spot();
  const double diagonal = diagonal_of(mesh);
  const ClosestFaceTree tree(vertex_matrix(mesh), face_matrix(mesh));
  const Sketch sketch = synthesize_sketch(mesh);
  ASSERT_GE(sketch.strokes.size(), 6u);
  for (const Stroke& s : sketch.strokes)
    for (const auto& p : s.points) {
      Eigen::Vector3d q;
      tree.closest_face(p, &q);
      ASSERT_LT((q - p).norm(), 1e-6 * diagonal);
    }
}

TEST(QualityData, EvalMeasuresAKnownOffsetOfSpot) {
  const TriMesh truth = spot();
  const double diagonal = diagonal_of(truth);
  EXPECT_LT(evaluate(truth, truth).accuracy.max, 1e-12);
  // Every vertex moved 0.5% of the diagonal along its normal: a surface about that far away.
  TriMesh moved = truth;
  moved.update_normals();
  for (auto v : moved.vertices())
    moved.set_point(v, moved.point(v) + 0.005 * diagonal * moved.normal(v));
  const Evaluation e = evaluate(moved, truth);
  EXPECT_NEAR(e.accuracy.median, 0.005, 0.001);
  EXPECT_NEAR(e.completeness.median, 0.005, 0.001);
  EXPECT_LT(e.accuracy.max, 0.0075);
}

}  // namespace
}  // namespace sketchsurf
