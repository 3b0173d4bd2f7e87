// Synthetic sketches: deterministic, on the mesh, the features and sections a shape has.

#include "surfacing/quality/synth.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "surfacing/error.h"
#include "tests/support/shapes.h"
#include "tests/support/truth_suite.h"

namespace sketchsurf {
namespace {

using V3 = Eigen::Vector3d;

/// Distance from p to triangle abc (Ericson, Real-Time Collision Detection 5.1.5).
double point_triangle_distance(const V3& p, const V3& a, const V3& b, const V3& c) {
  const V3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return (p - a).norm();
  const V3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return (p - b).norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
  const V3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return (p - c).norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  const double denom = 1.0 / (va + vb + vc);
  return (p - (a + ab * vb * denom + ac * vc * denom)).norm();
}

double distance_to_mesh(const TriMesh& mesh, const V3& p) {
  double best = INFINITY;
  for (const auto f : mesh.faces()) {
    std::array<V3, 3> c;
    int i = 0;
    for (const auto v : mesh.fv_range(f)) c[i++] = to_eigen(mesh.point(v));
    best = std::min(best, point_triangle_distance(p, c[0], c[1], c[2]));
  }
  return best;
}

double diagonal(const TriMesh& mesh) {
  BoundingBox box;
  for (const auto v : mesh.vertices()) box.extend(to_eigen(mesh.point(v)));
  return box.diagonal();
}

/// Largest distance from a stroke point to the mesh, checking every `step`-th point of each stroke.
double max_distance(const Sketch& sketch, const TriMesh& mesh, std::size_t step) {
  double worst = 0;
  for (const auto& s : sketch.strokes)
    for (std::size_t i = 0; i < s.points.size(); i += step)
      worst = std::max(worst, distance_to_mesh(mesh, s.points[i]));
  return worst;
}

bool same_points(const Sketch& a, const Sketch& b) {
  if (a.strokes.size() != b.strokes.size()) return false;
  for (std::size_t i = 0; i < a.strokes.size(); ++i)
    if (a.strokes[i].points != b.strokes[i].points || a.strokes[i].id != b.strokes[i].id) return false;
  return true;
}

SynthOptions vr(unsigned seed) {
  SynthOptions o;
  o.style = SynthOptions::Style::Vr;
  o.seed = seed;
  return o;
}

TEST(Synth, SameSeedSameSketchOtherSeedAnother) {
  const TriMesh mesh = testing::truth_shape("filleted_box").mesh;
  EXPECT_TRUE(same_points(synthesize_sketch(mesh), synthesize_sketch(mesh)));
  EXPECT_TRUE(same_points(synthesize_sketch(mesh, vr(7)), synthesize_sketch(mesh, vr(7))));
  EXPECT_FALSE(same_points(synthesize_sketch(mesh, vr(7)), synthesize_sketch(mesh, vr(8))));
}

TEST(Synth, NetStrokesLieOnTheMesh) {
  for (const char* name : {"l_bracket", "cup", "mug", "bean"}) {
    const TriMesh mesh = testing::truth_shape(name).mesh;
    const Sketch sketch = synthesize_sketch(mesh);
    ASSERT_GT(sketch.strokes.size(), 5u) << name;
    EXPECT_LT(max_distance(sketch, mesh, 7), 1e-6 * diagonal(mesh)) << name;
    for (std::size_t i = 0; i < sketch.strokes.size(); ++i)
      EXPECT_EQ(sketch.strokes[i].id, static_cast<std::int64_t>(i));
  }
}

TEST(Synth, CubeNetHasItsTwelveEdgesAsFeatureStrokes) {
  const TriMesh mesh = testing::truth_shape("box").mesh;  // unit cube at the origin
  SynthOptions o;
  o.sections = 0;
  o.silhouettes = 0;
  const Sketch sketch = synthesize_sketch(mesh, o);
  ASSERT_EQ(sketch.strokes.size(), 12u);
  for (const auto& s : sketch.strokes) {
    EXPECT_NEAR(s.length(), 1.0, 1e-9);
    // An edge of the cube: two coordinates at +-0.5 all along it.
    for (const V3& p : s.points) {
      int on_face = 0;
      for (int a = 0; a < 3; ++a) on_face += std::abs(std::abs(p[a]) - 0.5) < 1e-9;
      EXPECT_GE(on_face, 2);
    }
  }
  // The cube has no cross-section or silhouette in the way: the default adds 3 sections per axis.
  EXPECT_EQ(synthesize_sketch(mesh).strokes.size(), 12u + 9u);
}

TEST(Synth, SphereSectionsAreCirclesOfTheRightRadius) {
  const double radius = 0.5;
  const TriMesh mesh = testing::icosphere(4, radius);
  SynthOptions o;
  o.silhouettes = 0;
  const Sketch sketch = synthesize_sketch(mesh, o);
  ASSERT_EQ(sketch.strokes.size(), 9u);  // no feature edge; one closed circle per plane
  for (const auto& s : sketch.strokes) {
    EXPECT_NEAR((s.points.front() - s.points.back()).norm(), 0.0, 1e-12);  // closed
    // The plane of the circle: its points' mean and the normal of their spread.
    V3 c = V3::Zero();
    for (const V3& p : s.points) c += p;
    c /= static_cast<double>(s.points.size());
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    for (const V3& p : s.points) cov += (p - c) * (p - c).transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
    const V3 n = eig.eigenvectors().col(0);
    const double offset = std::abs(c.dot(n));
    // Planes at 1/4, 1/2, 3/4 of the extent along an axis: offsets 0 or 0.25 for radius 0.5.
    EXPECT_TRUE(std::abs(offset) < 0.01 || std::abs(offset - 0.25) < 0.01) << offset;
    const double expected = std::sqrt(radius * radius - offset * offset);
    for (const V3& p : s.points) {
      EXPECT_NEAR(std::abs((p - c).dot(n)), 0.0, 1e-9);
      EXPECT_NEAR((p - c).norm(), expected, 0.01 * radius);  // the icosphere's chord error
    }
  }
}

TEST(Synth, SilhouettesOfASphereAreGreatCircles) {
  const TriMesh mesh = testing::icosphere(4, 0.5);
  SynthOptions o;
  o.sections = 0;
  o.silhouettes = 2;
  const Sketch sketch = synthesize_sketch(mesh, o);
  ASSERT_EQ(sketch.strokes.size(), 2u);
  for (const auto& s : sketch.strokes) EXPECT_NEAR(s.length(), 2 * M_PI * 0.5, 0.02);
}

TEST(Synth, OpenMeshBordersAreDrawn) {
  SynthOptions o;
  o.sections = 0;
  o.silhouettes = 0;
  const Sketch sketch = synthesize_sketch(testing::truth_shape("cup").mesh, o);
  ASSERT_EQ(sketch.strokes.size(), 2u);  // the mouth and the crease around the bottom
  for (const auto& s : sketch.strokes) EXPECT_NEAR((s.points.front() - s.points.back()).norm(), 0, 1e-12);
}

TEST(Synth, VrStaysNearTheMeshAndHasItsFlaws) {
  const TriMesh mesh = testing::truth_shape("chamfered_box").mesh;
  const double diag = diagonal(mesh);
  SynthOptions o = vr(3);
  o.overshoot = 0;
  const Sketch clean = synthesize_sketch(mesh), drawn = synthesize_sketch(mesh, o);
  EXPECT_LT(max_distance(drawn, mesh, 5), 4 * o.tremor * diag);
  EXPECT_GT(max_distance(drawn, mesh, 5), 0.5 * o.tremor * diag);  // not on the mesh
  EXPECT_NE(drawn.strokes.size(), clean.strokes.size());
  // Overshoots leave the mesh by at most their length plus the tremor.
  const Sketch over = synthesize_sketch(mesh, vr(3));
  EXPECT_LT(max_distance(over, mesh, 3), (vr(3).overshoot + 4 * o.tremor) * diag);
  // Every flaw off: the clean sketch.
  SynthOptions none = vr(3);
  none.tremor = none.gap = none.overshoot = none.duplicate = none.drop = 0;
  EXPECT_TRUE(same_points(synthesize_sketch(mesh, none), clean));
}

TEST(Synth, TremorIsSmooth) {
  // Smooth hand tremor, not white noise: the offset from the clean stroke changes little between
  // neighbouring points compared with its amplitude.
  const TriMesh mesh = testing::icosphere(4, 0.5);
  SynthOptions o = vr(5);
  o.gap = o.overshoot = o.duplicate = o.drop = 0;
  o.tremor = 0.01;
  const Sketch clean = synthesize_sketch(mesh), drawn = synthesize_sketch(mesh, o);
  ASSERT_EQ(clean.strokes.size(), drawn.strokes.size());
  double largest_step = 0, largest = 0;
  for (std::size_t i = 0; i < clean.strokes.size(); ++i) {
    const auto &a = clean.strokes[i].points, &b = drawn.strokes[i].points;
    ASSERT_EQ(a.size(), b.size());
    for (std::size_t k = 0; k < a.size(); ++k) {
      largest = std::max(largest, (b[k] - a[k]).norm());
      if (k > 0) largest_step = std::max(largest_step, ((b[k] - a[k]) - (b[k - 1] - a[k - 1])).norm());
    }
  }
  EXPECT_GT(largest, 0.5 * o.tremor * diagonal(mesh));
  EXPECT_LT(largest_step, 0.5 * largest);  // white noise: steps as large as the offsets
}

TEST(Synth, InvalidOptionsAndMeshesAreErrors) {
  SynthOptions o;
  std::string why;
  o.gap = 1.5;
  EXPECT_FALSE(o.valid(&why));
  EXPECT_NE(why.find("gap"), std::string::npos);
  EXPECT_THROW(synthesize_sketch(testing::icosphere(1), o), Error);
  EXPECT_THROW(synthesize_sketch(TriMesh{}), Error);
}

}  // namespace
}  // namespace sketchsurf
