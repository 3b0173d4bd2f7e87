#include "surfacing/extract/fold_refit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "tests/support/shapes.h"
#include "tests/unit/extract/fixtures.h"

namespace sketchsurf {
namespace {

using namespace testing;

// A rounded cube labelled by its faces, with the six face planes as models except the top's
// (+y, label 2), which is a sphere through the top's middle: a model that bends away where the
// face is flat. Stroke points cover the top face's flat middle.
struct FoldScene {
  LabeledMesh mesh;
  std::vector<ImplicitModel> models;
  Eigen::MatrixX3d strokes;
};

FoldScene fold_scene() {
  const Eigen::Vector3d half(1.0, 1.0, 1.0);
  FoldScene s;
  s.mesh.mesh = rounded_box_mesh(4, half, 0.1);
  for (int label : box_labels(s.mesh.mesh, half)) s.mesh.labels.push_back({label});
  s.mesh.source_vertex.assign(s.mesh.labels.size(), -1);
  s.models = box_models(half);
  s.models[2] = testing::sphere_model(Eigen::Vector3d(0.0, 0.0, 0.0));  // radius 1: touches the top at its middle
  constexpr int kSide = 13;
  s.strokes.resize(kSide * kSide, 3);
  for (int i = 0; i < kSide; ++i)
    for (int j = 0; j < kSide; ++j)
      s.strokes.row(i * kSide + j) << -0.6 + 1.2 * i / (kSide - 1), 1.0, -0.6 + 1.2 * j / (kSide - 1);
  return s;
}

// The faces whose three corners all carry `label`.
std::vector<int> region_faces(const LabeledMesh& mesh, int label) {
  std::vector<int> out;
  for (auto f : mesh.mesh.faces()) {
    bool all = true;
    for (auto v : mesh.mesh.fv_range(f)) all = all && mesh.labels[v.idx()].front() == label;
    if (all) out.push_back(f.idx());
  }
  return out;
}

TEST(FoldRegions, TheRegionOnMostFoldedTrianglesIsFound) {
  const FoldScene s = fold_scene();
  const std::vector<int> top = region_faces(s.mesh, 2), front = region_faces(s.mesh, 4);
  ASSERT_GE(top.size(), 6u);
  ASSERT_GE(front.size(), 2u);
  // Three pairs within the top, one pair within the front: the top is on 6 of 8 triangles.
  const std::vector<std::array<int, 2>> folds = {
      {top[0], top[1]}, {top[2], top[3]}, {top[4], top[5]}, {front[0], front[1]}};
  EXPECT_EQ(fold_regions(s.mesh, folds, 0.5), std::vector<int>({2}));
  EXPECT_EQ(fold_regions(s.mesh, folds, 0.25), std::vector<int>({2, 4}));
  EXPECT_TRUE(fold_regions(s.mesh, folds, 0.9).empty());
  EXPECT_TRUE(fold_regions(s.mesh, {}, 0.5).empty());
  // A share just above 0: every region on any folded triangle.
  EXPECT_EQ(fold_regions(s.mesh, folds, std::numeric_limits<double>::min()), std::vector<int>({2, 4}));
}

TEST(RefitRegions, AFlatRegionsCurvedModelBecomesItsPlane) {
  const FoldScene s = fold_scene();
  const Eigen::MatrixX3d positions = vertex_matrix(s.mesh.mesh);
  const double diagonal = 2.0 * std::sqrt(3.0);
  std::size_t refitted = 0;
  const RegionSamples samples = region_samples(s.mesh, positions, {2}, s.strokes, 0.02 * diagonal);
  ASSERT_EQ(samples.points.size(), 1u);
  EXPECT_EQ(samples.points[0].rows(), s.strokes.rows());
  const std::vector<ImplicitModel> out = refit_regions(s.models, samples, 1, diagonal, 20, &refitted);
  EXPECT_EQ(refitted, 1u);
  ASSERT_EQ(out.size(), s.models.size());
  EXPECT_EQ(out[2].degree, 1);
  // The strokes lie on the new model; at the top's corners, where the sphere is far below the
  // face, the plane passes through them too.
  for (Eigen::Index i = 0; i < s.strokes.rows(); ++i)
    EXPECT_LT(out[2].distance(s.strokes.row(i).transpose()), 1e-6);
  EXPECT_LT(out[2].distance(Eigen::Vector3d(0.85, 1.0, 0.85)), 1e-6);
  EXPECT_GT(s.models[2].distance(Eigen::Vector3d(0.85, 1.0, 0.85)), 0.1);
  // Every other model is the same.
  for (std::size_t r = 0; r < out.size(); ++r) {
    if (r != 2) {
      EXPECT_EQ(out[r].coefficients, s.models[r].coefficients) << r;
    }
  }
}

TEST(RefitRegions, AModelAlreadyOfThatDegreeOrWithTooFewPointsIsKept) {
  const FoldScene s = fold_scene();
  const Eigen::MatrixX3d positions = vertex_matrix(s.mesh.mesh);
  const double diagonal = 2.0 * std::sqrt(3.0);
  std::size_t refitted = 1;
  // Degree 2: the sphere is a quadric already.
  const RegionSamples samples = region_samples(s.mesh, positions, {2}, s.strokes, 0.02 * diagonal);
  std::vector<ImplicitModel> out = refit_regions(s.models, samples, 2, diagonal, 20, &refitted);
  EXPECT_EQ(refitted, 0u);
  EXPECT_EQ(out[2].coefficients, s.models[2].coefficients);
  // More points asked for than the region has.
  out = refit_regions(s.models, samples, 1, diagonal, static_cast<std::size_t>(s.strokes.rows()) + 1, &refitted);
  EXPECT_EQ(refitted, 0u);
  EXPECT_EQ(out[2].degree, 2);
}

}  // namespace
}  // namespace sketchsurf
