// The lofted proxy through a sketch's parallel sections: shapes with known answers (a truncated
// cone, a barrel), a closed outward mesh, and the sketches it must refuse.

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "surfacing/mesh.h"
#include "surfacing/proxy/loft.h"
#include "surfacing/proxy/proxy.h"

namespace sketchsurf {
namespace {

constexpr double kPi = 3.14159265358979323846;

// A closed section stroke at height z round the z axis, radius r(angle), its last point on its first.
Stroke section(double z, const std::function<double(double)>& r, int n = 200) {
  Stroke s;
  for (int i = 0; i <= n; ++i) {
    const double a = 2.0 * kPi * i / n;
    s.points.emplace_back(r(a) * std::cos(a), r(a) * std::sin(a), z);
  }
  return s;
}

Stroke line(const Eigen::Vector3d& a, const Eigen::Vector3d& b, int n = 100) {
  Stroke s;
  for (int i = 0; i <= n; ++i) s.points.push_back(a + (b - a) * i / n);
  return s;
}

// Radius 1 at z = 0 to radius 0.5 at z = 2, with two profile lines on its side.
Sketch frustum() {
  Sketch sketch;
  sketch.strokes.push_back(section(0.0, [](double) { return 1.0; }));
  sketch.strokes.push_back(section(2.0, [](double) { return 0.5; }));
  sketch.strokes.push_back(line({1, 0, 0}, {0.5, 0, 2}));
  sketch.strokes.push_back(line({-1, 0, 0}, {-0.5, 0, 2}));
  return sketch;
}

LoftOptions coarse() {
  LoftOptions options;
  options.edge = 0.05;
  return options;
}

TEST(Loft, TwoSectionsAndProfilesMakeATruncatedCone) {
  const std::optional<Loft> loft = loft_sections(frustum(), coarse());
  ASSERT_TRUE(loft);
  EXPECT_EQ(loft->sections, 2u);
  const TriangleArrays& m = loft->mesh;
  for (Eigen::Index i = 0; i < m.V.rows(); ++i) {
    const Eigen::Vector3d p = m.V.row(i).transpose();
    const double radial = std::hypot(p.x(), p.y());
    ASSERT_GE(p.z(), -1e-9);
    ASSERT_LE(p.z(), 2.0 + 1e-9);
    if (p.z() > 1e-9 && p.z() < 2.0 - 1e-9)  // on the side: the cone's radius at that height
      ASSERT_NEAR(radial, 1.0 - 0.25 * p.z(), 2e-3) << "vertex " << i;
    else  // on a cap
      ASSERT_LE(radial, (p.z() < 1.0 ? 1.0 : 0.5) + 2e-3) << "vertex " << i;
  }
  const TriMesh mesh = mesh_from_matrices(m.V, m.F);
  const MeshTopology t = mesh_topology(mesh);
  EXPECT_TRUE(t.closed());
  EXPECT_EQ(t.components, 1u);
  EXPECT_EQ(t.genus, 0);
  double volume = 0.0;  // outward: positive, the frustum's pi h (R^2 + R r + r^2) / 3
  for (Eigen::Index f = 0; f < m.F.rows(); ++f)
    volume += m.V.row(m.F(f, 0)).dot(m.V.row(m.F(f, 1)).cross(m.V.row(m.F(f, 2)))) / 6.0;
  EXPECT_NEAR(volume, kPi * 2.0 * (1.0 + 0.5 + 0.25) / 3.0, 0.02);
}

TEST(Loft, ThreeSectionsAreJoinedSmoothlyThroughTheMiddleOne) {
  // A barrel: radius 1, 1.5, 1 at z = 0, 1, 2, the sections drawn out of order. The cubic
  // Hermite through them (slopes 0.5, 0, -0.5) reaches 1.5 at the middle and no farther.
  Sketch sketch;
  sketch.strokes.push_back(section(1.0, [](double) { return 1.5; }));
  sketch.strokes.push_back(section(2.0, [](double) { return 1.0; }));
  sketch.strokes.push_back(section(0.0, [](double) { return 1.0; }));
  const std::optional<Loft> loft = loft_sections(sketch, coarse());
  ASSERT_TRUE(loft);
  EXPECT_EQ(loft->sections, 3u);
  double widest = 0.0;
  for (Eigen::Index i = 0; i < loft->mesh.V.rows(); ++i) {
    const Eigen::Vector3d p = loft->mesh.V.row(i).transpose();
    const double radial = std::hypot(p.x(), p.y());
    widest = std::max(widest, radial);
    if (p.z() < 1e-9 || p.z() > 2.0 - 1e-9) continue;  // a cap
    const double t = 1.0 - std::abs(p.z() - 1.0);        // 0 at an end section, 1 at the middle
    const double expected = (2 * t * t * t - 3 * t * t + 1) * 1.0 + (t * t * t - 2 * t * t + t) * 0.5 +
                            (-2 * t * t * t + 3 * t * t) * 1.5;
    ASSERT_NEAR(radial, expected, 2e-3) << "vertex " << i;
  }
  EXPECT_NEAR(widest, 1.5, 1e-3);
}

TEST(Loft, AWavySectionIsFollowedAllRound) {
  // A dress: a waist circle over a four-lobed hem; the loft's hem ring is the hem stroke's own
  // points, in its valleys as on its lobes.
  Sketch sketch;
  const auto hem = [](double a) { return 1.0 + 0.3 * std::cos(4.0 * a); };
  sketch.strokes.push_back(section(0.0, hem, 400));
  sketch.strokes.push_back(section(2.0, [](double) { return 0.5; }));
  const std::optional<Loft> loft = loft_sections(sketch, coarse());
  ASSERT_TRUE(loft);
  int on_hem = 0;
  for (Eigen::Index i = 0; i < loft->mesh.V.rows(); ++i) {
    const Eigen::Vector3d p = loft->mesh.V.row(i).transpose();
    const double radial = std::hypot(p.x(), p.y());
    if (std::abs(p.z()) > 1e-9) continue;
    // The hem's cap lies within the hem; its outer ring is on it.
    const double wanted = hem(std::atan2(p.y(), p.x()));
    EXPECT_LE(radial, wanted + 5e-3) << "vertex " << i;
    on_hem += std::abs(radial - wanted) < 5e-3;
  }
  EXPECT_GT(on_hem, 140);  // the ring has one direction per 0.05 of the hem's length (8.1)
}

TEST(Loft, AHandsJitterIsSmoothedAway) {
  // The frustum's sections drawn with a zigzag of +-0.02 in radius, one point in two out: each ring
  // smoothed over 0.06 lies within 0.01 of the cone's radius; as drawn, its crossings stray farther.
  Sketch sketch = frustum();
  for (int s = 0; s < 2; ++s) {
    const double r = s == 0 ? 1.0 : 0.5;
    sketch.strokes[s] = section(2.0 * s, [](double) { return 1.0; }, 600);
    for (std::size_t i = 0; i < sketch.strokes[s].points.size(); ++i) {
      Eigen::Vector3d& p = sketch.strokes[s].points[i];
      const double jitter = (i % 2 == 0 ? 0.02 : -0.02) * (i + 1 < sketch.strokes[s].points.size());
      p.head<2>() *= r + jitter;
    }
  }
  const auto worst = [&](double smoothing) {
    LoftOptions options;
    options.edge = 0.02;
    options.smoothing = smoothing;
    options.fit = 0.05;  // the zigzag's points lie 0.02 off the smoothed loft
    const std::optional<Loft> loft = loft_sections(sketch, options);
    EXPECT_TRUE(loft);
    double most = 0.0;
    if (loft)
      for (Eigen::Index i = 0; i < loft->mesh.V.rows(); ++i) {
        const Eigen::Vector3d p = loft->mesh.V.row(i).transpose();
        if (p.z() > 1e-9 && p.z() < 2.0 - 1e-9)
          most = std::max(most, std::abs(std::hypot(p.x(), p.y()) - (1.0 - 0.25 * p.z())));
      }
    return most;
  };
  EXPECT_LT(worst(0.06), 0.01);
  EXPECT_GT(worst(0.0), 0.015);
}

TEST(Loft, NoLoftWhenAStrokeLiesOffIt) {
  // A spike out of the side: 10% of the points are a tube's length away from any loft.
  Sketch sketch = frustum();
  sketch.strokes.push_back(line({0, 1, 1}, {0, 3, 1}, 60));
  EXPECT_FALSE(loft_sections(sketch, coarse()));
  LoftOptions lenient = coarse();
  lenient.fit = 10.0;
  EXPECT_TRUE(loft_sections(sketch, lenient));
}

TEST(Loft, NoLoftWithoutTwoParallelSections) {
  Sketch one;
  one.strokes.push_back(section(0.0, [](double) { return 1.0; }));
  one.strokes.push_back(line({1, 0, 0}, {1, 0, 2}));
  EXPECT_FALSE(loft_sections(one, coarse()));
  // Two loops at right angles: a cross, not sections of one tube.
  Sketch crossed = one;
  Stroke upright = section(0.0, [](double) { return 1.0; });
  for (Eigen::Vector3d& p : upright.points) p = Eigen::Vector3d(p.x(), p.z(), p.y());
  crossed.strokes.push_back(upright);
  EXPECT_FALSE(loft_sections(crossed, coarse()));
  // Ignored strokes are not sections.
  Sketch ignored = frustum();
  ignored.strokes[1].ignored = true;
  EXPECT_FALSE(loft_sections(ignored, coarse()));
}

}  // namespace
}  // namespace sketchsurf
