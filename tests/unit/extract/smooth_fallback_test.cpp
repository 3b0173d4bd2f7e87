#include "surfacing/extract/smooth_fallback.h"

#include <gtest/gtest.h>

#include <cmath>

#include "surfacing/closest_face.h"
#include "surfacing/sketch/stroke_segments.h"
#include "tests/support/shapes.h"

namespace sketchsurf {
namespace {

using namespace testing;

// Two unit spheres, 4 apart along x, each drawn with its meridians and equator, each one region
// of the proxy (a fine icosphere through the strokes). Sketch diagonal about 6.
struct Scene {
  LabeledMesh proxy;
  StrokeSegments strokes;
};

Scene two_spheres() {
  const Eigen::Vector3d offset(4.0, 0.0, 0.0);
  TriMesh mesh = icosphere(4, 1.0);
  const int half = static_cast<int>(mesh.n_vertices());
  append_mesh(mesh, icosphere(4, 1.0, offset));
  Scene s;
  s.proxy.labels.assign(mesh.n_vertices(), {0});
  for (std::size_t v = static_cast<std::size_t>(half); v < mesh.n_vertices(); ++v) s.proxy.labels[v] = {1};
  s.proxy.source_vertex.assign(mesh.n_vertices(), -1);
  s.proxy.mesh = std::move(mesh);
  Sketch sketch = sphere_sketch(1.0, 4), second = sphere_sketch(1.0, 4);
  transform(second, 1.0, offset);
  sketch.strokes.insert(sketch.strokes.end(), second.strokes.begin(), second.strokes.end());
  s.strokes = stroke_segments(sketch, false);
  return s;
}

/// The sphere |x - center| = radius as a quadric.
ImplicitModel sphere_model(const Eigen::Vector3d& center, double radius) {
  ImplicitModel m;
  m.degree = 2;
  m.center = center;
  m.coefficients = Eigen::VectorXd::Zero(10);
  m.coefficients[0] = -radius * radius;
  m.coefficients[4] = m.coefficients[7] = m.coefficients[9] = 1.0;
  return m;
}

/// The mean squared distance to `proxy` of the stroke points beyond x = from.
double proxy_mean_square(const TriMesh& proxy, const StrokeSegments& strokes, double from) {
  const ClosestFaceTree tree(vertex_matrix(proxy), face_matrix(proxy));
  double squares = 0.0;
  int count = 0;
  for (Eigen::Index i = 0; i < strokes.points.rows(); ++i) {
    const Eigen::Vector3d p = strokes.points.row(i).transpose();
    if (p.x() < from) continue;
    Eigen::Vector3d q;
    tree.closest_face(p, &q);
    squares += (q - p).squaredNorm();
    ++count;
  }
  return squares / count;
}

/// The scene's second proxy sphere grown by 2%, and models: the first sphere exact, the second a
/// sphere whose mean squared distance to its stroke points is the proxy's over `nearer`.
std::vector<ImplicitModel> second_sphere_nearer(Scene& s, double nearer) {
  const auto second = static_cast<int>(s.proxy.mesh.n_vertices() / 2);
  const Eigen::Vector3d c(4.0, 0.0, 0.0);
  for (auto v : s.proxy.mesh.vertices())
    if (v.idx() >= second)
      s.proxy.mesh.set_point(v, to_openmesh(c + 1.02 * (to_eigen(s.proxy.mesh.point(v)) - c)));
  const double squares = proxy_mean_square(s.proxy.mesh, s.strokes, 2.0);
  return {sphere_model(Eigen::Vector3d::Zero(), 1.0), sphere_model(c, 1.0 + std::sqrt(squares / nearer))};
}

/// The scene's models: the first sphere exact, the second of radius 1.2, whose projection would
/// move the second proxy sphere by 0.2, 3.3% of the diagonal (more than `agree`).
std::vector<ImplicitModel> reshaping_models() {
  return {sphere_model(Eigen::Vector3d::Zero(), 1.0), sphere_model(Eigen::Vector3d(4.0, 0.0, 0.0), 1.2)};
}

TEST(SmoothFallback, ARegionWhoseModelMissesItsStrokesStaysAtTheProxy) {
  const Scene s = two_spheres();
  // Region 0's model is the drawn sphere; region 1's is 8% too large: it misses every stroke
  // point by 0.08, the proxy by its chords' sagitta only.
  const std::vector<ImplicitModel> models{sphere_model(Eigen::Vector3d::Zero(), 1.0),
                                          sphere_model(Eigen::Vector3d(4.0, 0.0, 0.0), 1.08)};
  SmoothFallbackSummary summary;
  const std::vector<char> kept = regions_at_proxy(s.proxy, models, s.strokes, 6.0, {}, {}, &summary);
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[0], 0) << "an exact model is projected onto";
  EXPECT_EQ(kept[1], 1) << "a model farther from the strokes than the proxy is not";
  EXPECT_EQ(summary.regions, 2u);
  EXPECT_EQ(summary.kept, 1u);
  EXPECT_EQ(summary.held, s.proxy.mesh.n_vertices() / 2);
}

TEST(SmoothFallback, ModelsCloserThanTheProxyAreAllProjectedOnto) {
  Scene s = two_spheres();
  // The proxy 5% too large: both exact models are closer to the strokes.
  for (auto v : s.proxy.mesh.vertices()) {
    const Eigen::Vector3d c(v.idx() < static_cast<int>(s.proxy.mesh.n_vertices() / 2) ? 0.0 : 4.0, 0.0, 0.0);
    s.proxy.mesh.set_point(v, to_openmesh(c + 1.05 * (to_eigen(s.proxy.mesh.point(v)) - c)));
  }
  const std::vector<ImplicitModel> models{sphere_model(Eigen::Vector3d::Zero(), 1.0),
                                          sphere_model(Eigen::Vector3d(4.0, 0.0, 0.0), 1.0)};
  SmoothFallbackSummary summary;
  const std::vector<char> kept = regions_at_proxy(s.proxy, models, s.strokes, 6.0, {}, {}, &summary);
  EXPECT_EQ(kept, std::vector<char>(2, 0));
  EXPECT_EQ(summary.regions, 2u);
  EXPECT_EQ(summary.held, 0u);
}

TEST(SmoothFallback, AModelOnlyAboutAsCloseAsTheProxyStaysAtTheProxy) {
  // The second model 2.5% nearer its strokes than the proxy in mean squared distance: within the
  // margin, the smooth proxy is kept; without it, the model is projected onto and, a sphere only a
  // little nearer, pulled toward the proxy.
  Scene s = two_spheres();
  const std::vector<ImplicitModel> models = second_sphere_nearer(s, 1.025);
  EXPECT_EQ(regions_at_proxy(s.proxy, models, s.strokes, 6.0, {}, {}), (std::vector<char>{0, 1}));
  SmoothFallbackOptions no_margin;
  no_margin.margin = 0.0;
  EXPECT_EQ(regions_at_proxy(s.proxy, models, s.strokes, 6.0, no_margin, {}),
            (std::vector<char>{kRegionProjected, kRegionPulled}));
}

TEST(SmoothFallback, ADoublyCurvedModelOnlyALittleNearerItsStrokesIsPulledTowardTheProxy) {
  // The second model 10% nearer (past the 5% margin, within pull_ratio's 25%): projected and
  // pulled. A sphere of radius 1 in a sketch of diagonal 6 has curvature 6 in diagonal units:
  // pulled under a pull_curvature of 5, not over 7. 40% nearer: projected only.
  Scene s = two_spheres();
  const std::vector<ImplicitModel> models = second_sphere_nearer(s, 1.1);
  SmoothFallbackSummary summary;
  EXPECT_EQ(regions_at_proxy(s.proxy, models, s.strokes, 6.0, {}, {}, &summary),
            (std::vector<char>{kRegionProjected, kRegionPulled}));
  EXPECT_EQ(summary.pulled, 1u);
  EXPECT_EQ(summary.kept, 0u);
  EXPECT_EQ(summary.held, 0u);
  SmoothFallbackOptions curvature;
  curvature.pull_curvature = 5.0;
  EXPECT_EQ(regions_at_proxy(s.proxy, models, s.strokes, 6.0, curvature, {})[1], kRegionPulled);
  curvature.pull_curvature = 7.0;
  EXPECT_EQ(regions_at_proxy(s.proxy, models, s.strokes, 6.0, curvature, {})[1], kRegionProjected);
  SmoothFallbackOptions off;
  off.pull_ratio = 1.0;
  EXPECT_EQ(regions_at_proxy(s.proxy, models, s.strokes, 6.0, off, {})[1], kRegionProjected);
  Scene clearly = two_spheres();
  EXPECT_EQ(regions_at_proxy(clearly.proxy, second_sphere_nearer(clearly, 1.4), clearly.strokes, 6.0, {}, {})[1],
            kRegionProjected);
}

TEST(SmoothFallback, ACylinderOnlyALittleNearerItsStrokesIsProjectedWithoutAPull) {
  // A tube of radius 1 drawn by eight lines along its axis and three circles; the proxy 2% too
  // wide; the model a cylinder 10% nearer the strokes than the proxy. A cylinder is developable (a
  // leg, a mug's body): there the proxy bulges or inflates between the strokes, and the model is
  // right: projected, not pulled.
  const int around = 64, along = 41;
  Eigen::MatrixX3d V(around * along, 3);
  for (int j = 0; j < along; ++j)
    for (int i = 0; i < around; ++i) {
      const double a = 2.0 * M_PI * i / around, z = -2.0 + 4.0 * j / (along - 1);
      V.row(j * around + i) << 1.02 * std::cos(a), 1.02 * std::sin(a), z;
    }
  Eigen::MatrixX3i F(2 * around * (along - 1), 3);
  int f = 0;
  for (int j = 0; j + 1 < along; ++j)
    for (int i = 0; i < around; ++i) {
      const int a = j * around + i, b = j * around + (i + 1) % around;
      F.row(f++) << a, b, a + around;
      F.row(f++) << b, b + around, a + around;
    }
  LabeledMesh proxy{mesh_from_matrices(V, F), std::vector<std::vector<int>>(V.rows(), {0}),
                    std::vector<int>(V.rows(), -1)};
  Sketch sketch;
  for (int k = 0; k < 8; ++k) {
    const double a = M_PI / 4.0 * k;
    sketch.strokes.push_back(sample_curve(
        [&](double t) { return Eigen::Vector3d(std::cos(a), std::sin(a), t); }, -1.8, 1.8, 0.02));
  }
  for (double z : {-1.5, 0.0, 1.5})
    sketch.strokes.push_back(sample_curve(
        [&](double t) { return Eigen::Vector3d(std::cos(t), std::sin(t), z); }, 0.0, 2.0 * M_PI, 0.02));
  const StrokeSegments strokes = stroke_segments(sketch, false);
  const double squares = proxy_mean_square(proxy.mesh, strokes, -10.0);
  ImplicitModel cylinder;
  cylinder.degree = 2;
  cylinder.coefficients = Eigen::VectorXd::Zero(10);
  const double radius = 1.0 + std::sqrt(squares / 1.1);
  cylinder.coefficients[0] = -radius * radius;
  cylinder.coefficients[4] = cylinder.coefficients[7] = 1.0;  // x^2 + y^2
  SmoothFallbackSummary summary;
  EXPECT_EQ(regions_at_proxy(proxy, {cylinder}, strokes, 5.0, {}, {}, &summary), std::vector<char>{0});
  EXPECT_EQ(summary.regions, 1u);
  EXPECT_EQ(summary.pulled, 0u);
}

TEST(SmoothFallback, AModelThatReshapesTheRegionIsProjectedOntoEvenWhenFartherFromItsStrokes) {
  const Scene s = two_spheres();
  // The model corrects the proxy's shape there, it is not a detail it misses.
  const std::vector<ImplicitModel> models = reshaping_models();
  EXPECT_EQ(regions_at_proxy(s.proxy, models, s.strokes, 6.0, {}, {}), std::vector<char>(2, 0));
  SmoothFallbackOptions loose;
  loose.agree = 0.05;
  EXPECT_EQ(regions_at_proxy(s.proxy, models, s.strokes, 6.0, loose, {}), std::vector<char>({0, 1}));
}

TEST(SmoothFallback, HoldingCurvedRegionsKeepsEvenModelsThatWouldReshapeThem) {
  // A lofted proxy: every region that is not a plane stays, the exact model and the one that would
  // move the second sphere by 0.2 alike.
  const Scene s = two_spheres();
  const std::vector<ImplicitModel> models = reshaping_models();
  SmoothFallbackOptions hold;
  hold.hold_curved = true;
  SmoothFallbackSummary summary;
  EXPECT_EQ(regions_at_proxy(s.proxy, models, s.strokes, 6.0, hold, {}, &summary), std::vector<char>(2, 1));
  EXPECT_EQ(summary.kept, 2u);
  EXPECT_EQ(summary.held, s.proxy.mesh.n_vertices());
}

TEST(SmoothFallback, AtAProxyThatFollowsItsStrokesAQuadricAboutAsNearIsProjectedOnto) {
  // The second model a little farther from its strokes than the proxy (mean squared distance 1.1
  // times the proxy's): held at a smooth proxy; projected onto at one that follows the strokes
  // closely (rounded), where the proxy's own nearness is its tremor's; held there too when the
  // proxy is clearly nearer (1.5 times), or when the same sphere is a quartic's zero set.
  Scene s = two_spheres();
  const std::vector<ImplicitModel> models = second_sphere_nearer(s, 1.0 / 1.1);
  SmoothFallbackOptions rounded;
  rounded.rounded = true;
  EXPECT_EQ(regions_at_proxy(s.proxy, models, s.strokes, 6.0, {}, {})[1], kRegionHeld);
  EXPECT_EQ(regions_at_proxy(s.proxy, models, s.strokes, 6.0, rounded, {})[1], kRegionProjected);
  Scene clearly = two_spheres();
  EXPECT_EQ(regions_at_proxy(clearly.proxy, second_sphere_nearer(clearly, 1.0 / 1.5), clearly.strokes, 6.0,
                             rounded, {})[1],
            kRegionHeld);
  std::vector<ImplicitModel> quartics = models;
  quartics[1].degree = 4;
  quartics[1].coefficients.conservativeResizeLike(Eigen::VectorXd::Zero(35));
  EXPECT_EQ(regions_at_proxy(s.proxy, quartics, s.strokes, 6.0, rounded, {})[1], kRegionHeld);
}

TEST(SmoothFallback, AtAProxyThatFollowsItsStrokesAHeldRegionStaysEvenWhereItsModelWouldReshapeIt) {
  // Radius 1.2 (the reshaping model above): projected onto at a smooth proxy, held at one that
  // follows the strokes closely, where a model so far from them strays between them.
  const Scene s = two_spheres();
  const std::vector<ImplicitModel> models = reshaping_models();
  SmoothFallbackOptions rounded;
  rounded.rounded = true;
  EXPECT_EQ(regions_at_proxy(s.proxy, models, s.strokes, 6.0, rounded, {}), std::vector<char>({0, 1}));
}

TEST(SmoothFallback, APlaneIsAlwaysProjectedOnto) {
  // A unit square waved by 1% in z, drawn with lines along y on the wave: the proxy passes through
  // the strokes, the plane z = 0 misses them by up to 0.01 (less than `agree` moves it). As a
  // plane the model is projected onto; the same surface as a degree-2 model is not.
  const int n = 41;
  Eigen::MatrixX3d V(n * n, 3);
  const auto wave = [](double x) { return 0.01 * std::sin(2.0 * M_PI * x); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = i / double(n - 1), y = j / double(n - 1);
      V.row(i * n + j) << x, y, wave(x);
    }
  Eigen::MatrixX3i F(2 * (n - 1) * (n - 1), 3);
  int f = 0;
  for (int i = 0; i + 1 < n; ++i)
    for (int j = 0; j + 1 < n; ++j) {
      const int a = i * n + j, b = a + n;
      F.row(f++) << a, b, a + 1;
      F.row(f++) << a + 1, b, b + 1;
    }
  LabeledMesh proxy{mesh_from_matrices(V, F), std::vector<std::vector<int>>(n * n, {0}),
                    std::vector<int>(n * n, -1)};
  Sketch sketch;
  for (int k = 0; k <= 8; ++k) {
    const double x = 0.05 + 0.1125 * k;
    sketch.strokes.push_back(sample_curve([&](double t) { return Eigen::Vector3d(x, t, wave(x)); }, 0.0, 1.0, 0.02));
  }
  const StrokeSegments strokes = stroke_segments(sketch, false);
  ImplicitModel plane;
  plane.degree = 1;
  plane.coefficients = Eigen::Vector4d(0.0, 0.0, 0.0, 1.0);  // z
  EXPECT_EQ(regions_at_proxy(proxy, {plane}, strokes, std::sqrt(2.0), {}, {}), std::vector<char>{0});
  SmoothFallbackOptions hold;  // also when every curved region is held
  hold.hold_curved = true;
  EXPECT_EQ(regions_at_proxy(proxy, {plane}, strokes, std::sqrt(2.0), hold, {}), std::vector<char>{0});
  ImplicitModel flat_quadric;
  flat_quadric.degree = 2;
  flat_quadric.coefficients = Eigen::VectorXd::Zero(10);
  flat_quadric.coefficients[3] = 1.0;  // z
  EXPECT_EQ(regions_at_proxy(proxy, {flat_quadric}, strokes, std::sqrt(2.0), {}, {}), std::vector<char>{1});
}

TEST(SmoothFallback, OffFarOrFewStrokesKeepNothing) {
  const Scene s = two_spheres();
  const std::vector<ImplicitModel> models{sphere_model(Eigen::Vector3d::Zero(), 1.1),
                                          sphere_model(Eigen::Vector3d(4.0, 0.0, 0.0), 1.1)};
  EXPECT_EQ(regions_at_proxy(s.proxy, models, s.strokes, 6.0, {}, {}), std::vector<char>(2, 1));
  SmoothFallbackOptions off;
  off.enabled = false;
  EXPECT_EQ(regions_at_proxy(s.proxy, models, s.strokes, 6.0, off, {}), std::vector<char>(2, 0));
  // Strokes 10 diagonals away belong to no region.
  StrokeSegments far = s.strokes;
  far.points.col(1).array() += 60.0;
  SmoothFallbackSummary summary;
  EXPECT_EQ(regions_at_proxy(s.proxy, models, far, 6.0, {}, {}, &summary), std::vector<char>(2, 0));
  EXPECT_EQ(summary.regions, 0u);
  SmoothFallbackOptions many;
  many.min_points = static_cast<std::size_t>(s.strokes.points.rows());
  EXPECT_EQ(regions_at_proxy(s.proxy, models, s.strokes, 6.0, many, {}), std::vector<char>(2, 0));
}

// The same two spheres as meshes: the strokes lie exactly on the first mesh's spheres ("the proxy"); the second is the same mesh inflated by 2%
// ("an optimised surface that left the strokes").
struct Inflated {
  TriMesh proxy, inflated;
  StrokeSegments strokes;
  std::vector<std::uint8_t> sharp;
};

Inflated inflated_spheres() {
  Inflated s;
  const Eigen::Vector3d offset(4.0, 0.0, 0.0);
  s.proxy = icosphere(4, 1.0);
  append_mesh(s.proxy, icosphere(4, 1.0, offset));
  s.inflated = icosphere(4, 1.02);
  append_mesh(s.inflated, icosphere(4, 1.02, offset));
  Sketch sketch = sphere_sketch(1.0, 4), second = sphere_sketch(1.0, 4);
  transform(second, 1.0, offset);
  sketch.strokes.insert(sketch.strokes.end(), second.strokes.begin(), second.strokes.end());
  s.strokes = stroke_segments(sketch, false);
  s.sharp.assign(s.proxy.n_vertices(), 0);
  return s;
}

double max_offset(const TriMesh& mesh, const Eigen::MatrixX3d& reference, int first, int last) {
  double m = 0.0;
  for (int v = first; v < last; ++v)
    m = std::max(m, (to_eigen(mesh.point(mesh.vertex_handle(v))) - reference.row(v).transpose()).norm());
  return m;
}

TEST(SmoothFallback, ASmoothPartThatLeftItsStrokesGoesBackToTheProxy) {
  Inflated s = inflated_spheres();
  const Eigen::MatrixX3d start = vertex_matrix(s.proxy);
  const Eigen::MatrixX3d inflated = vertex_matrix(s.inflated);
  const int half = static_cast<int>(s.proxy.n_vertices() / 2);
  s.sharp[static_cast<std::size_t>(half + 3)] = 1;  // the second sphere has a crease vertex
  TriMesh mesh = s.inflated;
  SmoothFallbackSummary summary;
  keep_smooth_proxy(mesh, start, s.sharp, {}, s.strokes, 6.0, {}, &summary);
  EXPECT_EQ(summary.parts, 1u);
  EXPECT_EQ(summary.reverted, 1u);
  EXPECT_EQ(summary.vertices, static_cast<std::size_t>(half));
  EXPECT_EQ(max_offset(mesh, start, 0, half), 0.0) << "the smooth sphere is the proxy's again";
  EXPECT_EQ(max_offset(mesh, inflated, half, 2 * half), 0.0) << "the creased sphere is untouched";
}

TEST(SmoothFallback, APartCloserToItsStrokesThanTheProxyKeepsItsPositions) {
  Inflated s = inflated_spheres();
  // Now the proxy is the inflated mesh and the optimised surface the exact one.
  const Eigen::MatrixX3d start = vertex_matrix(s.inflated);
  TriMesh mesh = s.proxy;
  const Eigen::MatrixX3d exact = vertex_matrix(mesh);
  SmoothFallbackSummary summary;
  keep_smooth_proxy(mesh, start, s.sharp, {}, s.strokes, 6.0, {}, &summary);
  EXPECT_EQ(summary.parts, 2u);
  EXPECT_EQ(summary.reverted, 0u);
  EXPECT_EQ(max_offset(mesh, exact, 0, static_cast<int>(mesh.n_vertices())), 0.0);
}

// A part whose regions were all kept at the proxy had nothing fitted: it goes back to the proxy even
// where the solve's Laplacian left it closer to the strokes.
TEST(SmoothFallback, APartHeldAtTheProxyEverywhereIsTheProxy) {
  Inflated s = inflated_spheres();
  const Eigen::MatrixX3d start = vertex_matrix(s.inflated);
  TriMesh mesh = s.proxy;
  const Eigen::MatrixX3d exact = vertex_matrix(mesh);
  const int half = static_cast<int>(mesh.n_vertices() / 2);
  std::vector<char> held(mesh.n_vertices(), 0);
  std::fill(held.begin(), held.begin() + half, 1);  // the first sphere
  held[static_cast<std::size_t>(half + 3)] = 1;     // and one vertex of the second
  SmoothFallbackSummary summary;
  keep_smooth_proxy(mesh, start, s.sharp, held, s.strokes, 6.0, {}, &summary);
  EXPECT_EQ(summary.reverted, 1u);
  EXPECT_EQ(max_offset(mesh, start, 0, half), 0.0) << "the held sphere is the proxy's";
  EXPECT_EQ(max_offset(mesh, exact, half, 2 * half), 0.0) << "the other keeps its positions";
}

TEST(SmoothFallback, OffOrWithoutStrokesNearbyNothingMoves) {
  Inflated s = inflated_spheres();
  const Eigen::MatrixX3d start = vertex_matrix(s.proxy);
  SmoothFallbackOptions off;
  off.enabled = false;
  TriMesh mesh = s.inflated;
  SmoothFallbackSummary summary;
  keep_smooth_proxy(mesh, start, s.sharp, {}, s.strokes, 6.0, off, &summary);
  EXPECT_EQ(summary.reverted, 0u);
  // Strokes 10 diagonals away belong to no part.
  StrokeSegments far = s.strokes;
  far.points.col(1).array() += 60.0;
  keep_smooth_proxy(mesh, start, s.sharp, {}, far, 6.0, {}, &summary);
  EXPECT_EQ(summary.reverted, 0u);
  EXPECT_EQ(max_offset(mesh, vertex_matrix(s.inflated), 0, static_cast<int>(mesh.n_vertices())), 0.0);
}

}  // namespace
}  // namespace sketchsurf
