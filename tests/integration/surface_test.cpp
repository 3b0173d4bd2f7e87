// The final surface on generated sketches with known answers (issue 4 "Done when"): a cube on a
// rounded proxy, a cylinder with caps, an open sheet with boundary strokes, a mirrored cube.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "surfacing/extract/extract.h"
#include "surfacing/error.h"
#include "surfacing/pipeline.h"
#include "surfacing/quality/eval.h"
#include "surfacing/quality/synth.h"
#include "tests/support/shapes.h"
#include "tests/support/truth_suite.h"
#include "tests/unit/extract/fixtures.h"

namespace sketchsurf {
namespace {

const Eigen::Vector3d kHalf(0.5, 0.5, 0.5);

/// Closed 2-manifold: every edge has two faces, Euler characteristic 2 (a sphere).
void expect_closed_sphere(const TriMesh& mesh) {
  std::size_t boundary = 0;
  for (auto e : mesh.edges()) boundary += mesh.is_boundary(e);
  EXPECT_EQ(boundary, 0u);
  for (auto v : mesh.vertices()) EXPECT_TRUE(mesh.is_manifold(v));
  EXPECT_EQ(long(mesh.n_vertices()) - long(mesh.n_edges()) + long(mesh.n_faces()), 2);
}

/// Angle (degrees) between the normals of the two faces of an interior edge.
double dihedral_degrees(const TriMesh& mesh, TriMesh::EdgeHandle e) {
  const auto n0 = mesh.calc_face_normal(mesh.face_handle(mesh.halfedge_handle(e, 0)));
  const auto n1 = mesh.calc_face_normal(mesh.face_handle(mesh.halfedge_handle(e, 1)));
  return std::acos(std::clamp(OpenMesh::dot(n0, n1), -1.0, 1.0)) * 180.0 / M_PI;
}

/// The cube checks of the issue on a result whose labels are the box faces.
void expect_sharp_cube(const ExtractedSurface& out) {
  const double diagonal = 2.0 * kHalf.norm();
  double worst = 0.0, bulge = 0.0;
  Eigen::Vector3d worst_at = Eigen::Vector3d::Zero();
  for (auto v : out.mesh.vertices()) {
    const Eigen::Vector3d p = to_eigen(out.mesh.point(v));
    if (testing::box_distance(p, kHalf) > worst) worst_at = p;
    worst = std::max(worst, testing::box_distance(p, kHalf));
    // Bulge: a smooth vertex off its face plane.
    if (!out.sharp[v.idx()]) bulge = std::max(bulge, testing::box_distance(p, kHalf));
  }
  EXPECT_LT(worst, 0.003 * diagonal) << "at " << worst_at.transpose();
  EXPECT_LT(bulge, 0.003 * diagonal);
  // Seam edges: both ends sharp; their faces meet at 90 degrees (edges at a cube corner excepted:
  // there the seam turns).
  int seam_edges = 0;
  double worst_angle = 0.0;
  for (auto e : out.mesh.edges()) {
    const int a = e.v0().idx(), b = e.v1().idx();
    if (!out.sharp[a] || !out.sharp[b]) continue;
    const Eigen::Vector3d pa = to_eigen(out.mesh.point(e.v0())), pb = to_eigen(out.mesh.point(e.v1()));
    const Eigen::Vector3d mid = 0.5 * (pa + pb);
    // Not within 2% of a corner.
    if ((mid.cwiseAbs() - kHalf).cwiseAbs().maxCoeff() < 0.02) continue;
    ++seam_edges;
    if (std::abs(dihedral_degrees(out.mesh, e) - 90.0) > worst_angle) worst_at = mid;
    worst_angle = std::max(worst_angle, std::abs(dihedral_degrees(out.mesh, e) - 90.0));
  }
  EXPECT_GT(seam_edges, 12 * 8);
  EXPECT_LT(worst_angle, 5.0) << "at " << worst_at.transpose();
}

TEST(Surface, CubeOnARoundedProxyWithKnownRegions) {
  const TriMesh proxy = testing::rounded_box_mesh(4, kHalf, 0.1);
  const Sketch sketch = testing::cube_sketch();
  const ExtractedSurface out = extract(proxy, testing::box_labels(proxy, kHalf),
                                       testing::box_models(kHalf), sketch, {});
  EXPECT_TRUE(out.summary.optimization.usable) << out.summary.optimization.termination;
  expect_closed_sphere(out.mesh);
  expect_sharp_cube(out);
  EXPECT_LT(out.summary.stroke_distance.median, 0.001);
  EXPECT_LT(out.summary.stroke_distance.max, 0.01);
}

TEST(Surface, CubeSketchThroughTheWholePipeline) {
  const TriMesh proxy = testing::rounded_box_mesh(4, kHalf, 0.1);
  Params params;
  params.segment.restarts = 2;
  params.proxy.edge = 0.03;  // a coarser remesh than the paper's 0.007 keeps the test quick
  const SurfaceResult r = Surfacer(params).run(testing::cube_sketch(), &proxy);
  EXPECT_EQ(r.segmentation.models.size(), 6u);
  expect_closed_sphere(r.mesh);
  ExtractedSurface out{r.mesh, r.labels, r.sharp, r.report.extraction};
  expect_sharp_cube(out);
  EXPECT_LT(r.report.stroke_distance.median, 0.01);
  EXPECT_GT(r.report.total_s, 0.0);
  std::cerr << "proxy " << r.proxy.n_vertices() << " vertices; proxy " << r.report.proxy_s << " s, segment "
            << r.report.segment_s << " s, extract " << r.report.extraction_s << " s\n";
}

// Every stroke of the cube drawn three times, each pass about 0.7% of the diagonal off the others:
// still six flat faces meeting at sharp edges, closed, no hole.
TEST(Surface, AnOverSketchedCubeHasSixFacesAndNoHole) {
  const Sketch sketch = testing::over_sketched(testing::cube_sketch(), 3, 0.005, 7);
  ASSERT_EQ(sketch.strokes.size(), 54u);
  const SurfaceResult r = surface(sketch);
  EXPECT_EQ(r.segmentation.models.size(), 6u);
  expect_closed_sphere(r.mesh);
  const double diagonal = 2.0 * kHalf.norm();
  double worst = 0.0;
  for (auto v : r.mesh.vertices()) worst = std::max(worst, testing::box_distance(to_eigen(r.mesh.point(v)), kHalf));
  EXPECT_LT(worst, 0.015 * diagonal);
  EXPECT_LT(r.report.stroke_distance.p95, 0.01);
}

// A box drawn as a hand in VR often draws it: sections round it and one stroke along the middle
// of each long face, no edge. The sections' corners say where the edges are; the result is a box
// with sharp edges, not a tube with rounded ones (what the region borders made of it before they
// could follow the sections' corners).
TEST(Surface, ABoxDrawnWithSectionsAndNoEdgeHasSharpEdges) {
  const Eigen::Vector3d half(0.5, 0.2, 0.3);
  Sketch sketch = testing::box_sections_sketch(half, {-0.5, -0.25, 0.0, 0.25, 0.5});
  for (const Eigen::Vector3d& middle : {Eigen::Vector3d(0, half.y(), 0), Eigen::Vector3d(0, 0, half.z()),
                                        Eigen::Vector3d(0, -half.y(), 0), Eigen::Vector3d(0, 0, -half.z())})
    sketch.strokes.push_back(testing::polyline_stroke(
        {middle - Eigen::Vector3d(half.x(), 0, 0), middle + Eigen::Vector3d(half.x(), 0, 0)}, false));
  Params params;
  params.segment.restarts = 2;
  params.proxy.edge = 0.015;
  const SurfaceResult r = Surfacer(params).run(sketch);
  EXPECT_EQ(r.segmentation.summary.crease_guides, 16u);  // 4 edges x 4 gaps between sections
  expect_closed_sphere(r.mesh);
  const double diagonal = 2.0 * half.norm();
  std::vector<double> off;
  for (auto v : r.mesh.vertices()) off.push_back(testing::box_distance(to_eigen(r.mesh.point(v)), half));
  std::sort(off.begin(), off.end());
  EXPECT_LT(off[off.size() * 95 / 100], 0.001 * diagonal);
  EXPECT_LT(off.back(), 0.005 * diagonal);
}

// Half a box drawn, its long strokes stopping in the air on the plane x = 0: surfaced as the whole
// box (the mirror image added), closed and sharp; as drawn when told not to complete it.
TEST(Surface, HalfABoxDrawnUpToItsMirrorPlaneGivesTheWholeBox) {
  const Eigen::Vector3d half(0.5, 0.2, 0.3);
  Sketch sketch = testing::box_sections_sketch(half, {0.125, 0.25, 0.375, 0.5});
  for (const Eigen::Vector3d& middle :
       {Eigen::Vector3d(0, half.y(), 0), Eigen::Vector3d(0, 0, half.z()), Eigen::Vector3d(0, -half.y(), 0),
        Eigen::Vector3d(0, 0, -half.z()), Eigen::Vector3d(0, half.y(), half.z()), Eigen::Vector3d(0, -half.y(), half.z()),
        Eigen::Vector3d(0, half.y(), -half.z()), Eigen::Vector3d(0, -half.y(), -half.z())})
    sketch.strokes.push_back(testing::polyline_stroke({middle, middle + Eigen::Vector3d(half.x(), 0, 0)}, false));
  Params params;
  params.segment.restarts = 2;
  params.proxy.edge = 0.015;
  const SurfaceResult r = Surfacer(params).run(sketch);
  ASSERT_TRUE(r.report.symmetry.has_value());
  EXPECT_EQ(r.report.symmetry->half_ends, 8);
  EXPECT_NEAR(std::abs(r.report.symmetry->plane.normal.x()), 1.0, 1e-6);
  expect_closed_sphere(r.mesh);
  const double diagonal = 2.0 * half.norm();
  std::vector<double> off;
  double least_x = 0.0;
  for (auto v : r.mesh.vertices()) {
    off.push_back(testing::box_distance(to_eigen(r.mesh.point(v)), half));
    least_x = std::min(least_x, r.mesh.point(v)[0]);
  }
  std::sort(off.begin(), off.end());
  EXPECT_LT(off[off.size() * 95 / 100], 0.002 * diagonal);
  EXPECT_LT(off.back(), 0.01 * diagonal);
  EXPECT_NEAR(least_x, -half.x(), 0.005 * diagonal);

  params.prepare.complete_half = false;
  const SurfaceResult drawn = Surfacer(params).run(sketch);
  EXPECT_FALSE(drawn.report.symmetry && drawn.report.symmetry->half_ends > 0);
  double drawn_least_x = 0.0;
  for (auto v : drawn.mesh.vertices()) drawn_least_x = std::min(drawn_least_x, drawn.mesh.point(v)[0]);
  EXPECT_GT(drawn_least_x, -0.2 * half.x());
}

// A table whose legs are single lines: they stop in the air on one plane, square to it, like half
// a sketch's strokes, but hang by one end: legs (ignored), not half of a surface to mirror.
TEST(Surface, ATableWithLineLegsIsNotTakenForHalfASketch) {
  Sketch sketch = testing::cube_sketch(1.0, true);
  for (Stroke& s : sketch.strokes)
    for (Eigen::Vector3d& p : s.points) p.y() *= 0.15;
  for (double x : {-0.5, 0.5})
    for (double z : {-0.5, 0.5})
      sketch.strokes.push_back(testing::polyline_stroke({{x, -0.075, z}, {x, -0.8, z}}, false));
  Params params;
  params.segment.restarts = 2;
  const SurfaceResult r = Surfacer(params).run(sketch);
  EXPECT_FALSE(r.report.symmetry && r.report.symmetry->half_ends > 0);
  EXPECT_EQ(r.report.decorations.size(), 4u);
  double least_y = 0.0;
  for (auto v : r.mesh.vertices()) least_y = std::min(least_y, static_cast<double>(r.mesh.point(v)[1]));
  EXPECT_GT(least_y, -0.2);  // the slab, not a table mirrored under its legs
}

// Surfacing `sketch` with the default parameters is refused as depicting no surface, with a
// message that says why and what to do (each of `phrases`).
void expect_refused(const Sketch& sketch, const std::vector<std::string>& phrases) {
  try {
    surface(sketch);
    FAIL() << "a scene that depicts no surface was surfaced";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Processing);
    const std::string what = e.what();
    EXPECT_NE(what.find("do not seem to depict one surface"), std::string::npos) << what;
    for (const std::string& phrase : phrases) EXPECT_NE(what.find(phrase), std::string::npos) << what;
  }
}

// Shading strokes scattered in space depict no surface: refused with a message that says why and
// what to do, not a blob.
TEST(Surface, AHatchingSceneIsRefusedWithAClearMessage) {
  expect_refused(testing::hatching_sketch(10, 3), {"proxy mesh"});
}

// A scene of scribbled masses (strokes sweeping back and forth over an area, as painterly fills
// are drawn) depicts no surface: refused before surfacing, the message naming the scribbles; with
// the refusal off it is surfaced as asked.
TEST(Surface, AScribbledSceneIsRefusedBeforeSurfacing) {
  Sketch sketch;
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector3d at(0.4 * k, 0.2 * (k % 2), 0.3 * (k / 2));
    sketch.strokes.push_back(testing::sample_curve(
        [&](double t) {
          return Eigen::Vector3d(at + 0.2 * Eigen::Vector3d(std::sin((7 + k) * t), std::sin(11 * t + 0.3),
                                                           0.3 * std::sin(5 * t)));
        },
        0.0, 2 * M_PI, 0.002));
  }
  expect_refused(sketch, {"100% of the ink is scribbles", "--force"});
  Params forced;
  forced.checks.refuse_score = 0.0;
  EXPECT_GT(surface(sketch, forced).mesh.n_faces(), 0u);
}

// A smooth closed shape drawn as a clean curve network: no crease, so the final surface is at least
// as accurate as the automatic proxy it started from (the proxy is kept where one quartic per
// region would pass farther from the strokes).
TEST(Surface, ASmoothTorusIsAtLeastAsAccurateAsItsProxy) {
  const TriMesh truth = testing::truth_shape("torus").mesh;
  const SurfaceResult r = surface(synthesize_sketch(truth));
  const Evaluation final_eval = evaluate(r.mesh, truth), proxy_eval = evaluate(r.proxy, truth);
  constexpr double kSampling = 5e-6;  // the same surface sampled in another face order
  EXPECT_LE(final_eval.accuracy.median, proxy_eval.accuracy.median + kSampling);
  EXPECT_LE(final_eval.accuracy.p95, proxy_eval.accuracy.p95 + kSampling);
  EXPECT_LT(final_eval.accuracy.p95, 0.001) << "p95 beyond 0.1% of the diagonal";
  EXPECT_EQ(mesh_topology(r.mesh).genus, 1);
}

// A ground-truth shape drawn mid-air (synth's vr style, draw `seed`), surfaced with the defaults.
SurfaceResult surfaced_vr_draw(const TriMesh& truth, unsigned seed) {
  SynthOptions vr;
  vr.style = SynthOptions::Style::Vr;
  vr.seed = seed;
  return surface(synthesize_sketch(truth, vr));
}

// Blended blobs drawn mid-air: no crease, so the final surface is at least as accurate as its
// proxy. Draw 1: with the paper's smoothness weight (10) the final surface's p95 is farther from
// the truth than the proxy's. Draw 2: one blob's quadric, 13% nearer its strokes than the proxy,
// bulges between them by half a percent of the diagonal unless pulled back toward the proxy
// (extract.smooth_fallback_pull_ratio).
TEST(Surface, SmoothBlobsDrawnInVrAreAtLeastAsAccurateAsTheirProxy) {
  const TriMesh truth = testing::truth_shape("metaballs").mesh;
  for (unsigned draw : {1u, 2u}) {
    SCOPED_TRACE(draw);
    const SurfaceResult r = surfaced_vr_draw(truth, draw);
    const Evaluation final_eval = evaluate(r.mesh, truth), proxy_eval = evaluate(r.proxy, truth);
    EXPECT_LE(final_eval.accuracy.median, proxy_eval.accuracy.median);
    EXPECT_LE(final_eval.accuracy.p95, proxy_eval.accuracy.p95);
  }
}

// A wineglass drawn as a clean curve network: the proxy nearly passes through the strokes and its
// bowl is the glass's, where the bowl's cubic passes farther from them. The rim, a boundary stroke
// the trimmed proxy's border passes off, is left out of that comparison; counted, it made the
// proxy look the farther one and the bowl was projected onto the cubic.
TEST(Surface, AWineglassNetsOpenBowlIsAtLeastAsAccurateAsItsProxy) {
  const TriMesh truth = testing::truth_shape("wineglass").mesh;
  const SurfaceResult r = surface(synthesize_sketch(truth));
  const Evaluation final_eval = evaluate(r.mesh, truth), proxy_eval = evaluate(r.proxy, truth);
  EXPECT_LE(final_eval.accuracy.median, proxy_eval.accuracy.median);
  EXPECT_LT(final_eval.accuracy.p95, 0.002);  // the proxy's cap over the mouth is trimmed
}

// A chair drawn as a clean curve network: every weight of the ladder above the first webs the legs
// a little more to the seat (the surface far from every stroke grows from 0.8% to 2.5%) and none
// closes; the last rounds the shape off the strokes, and the least smoothed solve stays (the
// first table's proxy, interpolating on 1000 samples: median 0.129%, p95 0.975%; the ladder's
// 1e-4, kept before: 0.172%, 1.035%).
TEST(Surface, AChairDrawnAsACleanNetworkKeepsItsLeastSmoothedProxy) {
  const TriMesh truth = testing::truth_shape("chair").mesh;
  const SurfaceResult r = surface(synthesize_sketch(truth));
  EXPECT_EQ(r.report.proxy.lambda, Params().proxy.clean_lambda);
  EXPECT_TRUE(r.report.proxy.rounded);
  EXPECT_LT(r.report.proxy.far_area, 0.015);
  EXPECT_EQ(mesh_topology(r.proxy).genus, 0);
  const Evaluation proxy_eval = evaluate(r.proxy, truth), final_eval = evaluate(r.mesh, truth);
  EXPECT_LT(proxy_eval.accuracy.median, 0.0012);
  EXPECT_LT(proxy_eval.accuracy.p95, 0.008);
  EXPECT_LE(final_eval.accuracy.median, proxy_eval.accuracy.median);
  EXPECT_LT(final_eval.accuracy.p95, 0.007);
  EXPECT_LT(final_eval.accuracy.p99, 0.02);
}

// A chair drawn mid-air (vr draw 3): VIPSS webs each side's front and back legs into a wall that
// hangs from the seat, framed by the legs and the seat but open below them. The proxy is cut back
// nearer the strokes there, and solved again with the normals that the legs' strokes give (the
// walls were the last run of the ground-truth suite past p99 2% and max 5%: 6.7% and 10.1%).
// Under the seat, beside the front leg, a window opens through the seat's underside whose space
// across runs into the leg (no window by its saddle's open space, and no stroke depicts an
// opening there): closed on the kept solve, the proxy and the chair have no handle.
TEST(Surface, AChairDrawnInVrHasNoWallBetweenItsLegsNorAWindowUnderItsSeat) {
  const TriMesh truth = testing::truth_shape("chair").mesh;
  const SurfaceResult r = surfaced_vr_draw(truth, 3);
  EXPECT_EQ(r.report.proxy.confine_radius, Params().proxy.confine_near);
  EXPECT_GT(r.report.proxy.part_normals, 0u);
  EXPECT_EQ(mesh_topology(r.proxy).genus, 0);
  EXPECT_EQ(mesh_topology(r.mesh).genus, 0);
  EXPECT_EQ(mesh_topology(r.mesh).components, 1u);
  const Evaluation eval = evaluate(r.mesh, truth);
  EXPECT_LT(eval.accuracy.p99, 0.02);
  EXPECT_LT(eval.accuracy.max, 0.05);
}

// A bar with three holes drawn mid-air (vr draw 1): one end face is drawn by three of its four
// edges, and the bottom edges at one of its corners are missing, so a vertical edge touches the
// others by its top end only. Taken for an antenna and left out, its face's region wrapped round
// the undrawn corner and bulged 1-2% of the diagonal there (final p95 0.66% over its proxy's 0.64%).
// Lying along a side of the strokes' box, it is the face's edge and is kept.
TEST(Surface, ABarDrawnInVrKeepsAnEndFacesEdgeWhoseCornerIsUndrawn) {
  const TriMesh truth = testing::truth_shape("bar_three_holes").mesh;
  const SurfaceResult r = surfaced_vr_draw(truth, 1);
  EXPECT_TRUE(r.report.decorations.empty());
  const Evaluation final_eval = evaluate(r.mesh, truth), proxy_eval = evaluate(r.proxy, truth);
  EXPECT_LE(final_eval.accuracy.median, proxy_eval.accuracy.median);
  EXPECT_LE(final_eval.accuracy.p95, proxy_eval.accuracy.p95);
  EXPECT_LT(final_eval.accuracy.p99, 0.02);
}

// An L-bracket drawn mid-air (vr draw 1): its thin end faces are drawn by their rims only and the
// proxy rounds them. With the paper's smoothness weight (10) curved models wrap those corners,
// follow the proxy's bulge and fail both bounds; with the weaker default, the planes' borders
// follow the rims and the ends come out flat.
TEST(Surface, AnLBracketDrawnInVrHasFlatThinEndFaces) {
  const TriMesh truth = testing::truth_shape("l_bracket").mesh;
  const Evaluation eval = evaluate(surfaced_vr_draw(truth, 1).mesh, truth);
  EXPECT_LT(eval.accuracy.p99, 0.02);
  EXPECT_LT(eval.accuracy.max, 0.05);
}

// A thin plate drawn mid-air (vr draw 2) by strokes round its thin sides: where one stroke is drawn
// a little higher than the next, its top corner lies nearer the next one's bottom corner than that
// one's top corner. Joined by distance alone, that crease guide runs across the thin side, whose
// region then wraps it and rounds the plate's edges (crease error median 5.3 degrees); corners
// join the nearest that points the same way.
TEST(Surface, AThinPlateDrawnInVrHasSharpEdgesRoundItsThinSides) {
  const TriMesh truth = testing::truth_shape("thin_plate").mesh;
  const Evaluation eval = evaluate(surfaced_vr_draw(truth, 2).mesh, truth);
  EXPECT_GT(eval.creases.found, 0.9);
  EXPECT_LT(eval.creases.error.median, 5.0);
  EXPECT_LT(eval.accuracy.p99, 0.02);
}

// A wineglass drawn mid-air (vr draw 3): the foot's underside is flat, and the proxy's bulge past
// the foot's rim would be projected onto its plane as a flange round the foot. Flat regions end
// at their drawn outline. Its thin foot keeps folds both fills leave; held at the proxy it would
// hang on the proxy's bulge below the drawn foot, which the fold hold's stroke-distance p95 gate
// refuses.
TEST(Surface, AWineglassDrawnInVrHasNoFlangeRoundItsFoot) {
  const TriMesh truth = testing::truth_shape("wineglass").mesh;
  const Evaluation eval = evaluate(surfaced_vr_draw(truth, 3).mesh, truth);
  EXPECT_LT(eval.accuracy.p99, 0.02);
  EXPECT_LT(eval.accuracy.max, 0.05);
}

TEST(Surface, CylinderWithCapsHasSharpRimsAndARoundSide) {
  const double radius = 0.5, half_height = 0.5;
  const TriMesh proxy = testing::rounded_cylinder_mesh(4, radius, half_height, 0.08);
  // Labels: 0 side, 1 top, 2 bottom, by which surface the vertex is relatively closest to.
  std::vector<int> labels;
  for (auto v : proxy.vertices()) {
    const Eigen::Vector3d p = to_eigen(proxy.point(v));
    const double rho = std::hypot(p.x(), p.y());
    labels.push_back(rho / radius > std::abs(p.z()) / half_height ? 0 : (p.z() > 0 ? 1 : 2));
  }
  ImplicitModel side;  // x^2 + y^2 - r^2
  side.degree = 2;
  side.coefficients = Eigen::VectorXd::Zero(10);
  side.coefficients << -radius * radius, 0, 0, 0, 1, 0, 0, 1, 0, 0;
  const std::vector<ImplicitModel> models{side, testing::plane_model({0, 0, 1}, half_height),
                                          testing::plane_model({0, 0, -1}, half_height)};
  const ExtractedSurface out = extract(proxy, labels, models, testing::cylinder_sketch(radius, 2 * half_height), {});
  expect_closed_sphere(out.mesh);
  double radius_error = 0.0, rim_error = 0.0;
  std::size_t rims = 0;
  for (auto v : out.mesh.vertices()) {
    const Eigen::Vector3d p = to_eigen(out.mesh.point(v));
    const double rho = std::hypot(p.x(), p.y());
    if (out.labels[v.idx()] == 0 && !out.sharp[v.idx()])
      radius_error = std::max(radius_error, std::abs(rho - radius) / radius);
    if (out.sharp[v.idx()]) {
      ++rims;
      rim_error = std::max(rim_error, std::hypot(rho - radius, std::abs(p.z()) - half_height));
    }
  }
  EXPECT_LT(radius_error, 0.01);
  EXPECT_GT(rims, 60u);
  EXPECT_LT(rim_error, 0.01);
}

/// An open grid over [-extent, extent]^2 following z = c (x^2 - y^2) + lift.
TriMesh saddle_grid(double extent, int n, double curvature, double lift) {
  Eigen::MatrixX3d V((n + 1) * (n + 1), 3);
  Eigen::MatrixX3i F(2 * n * n, 3);
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double x = -extent + 2 * extent * i / n, y = -extent + 2 * extent * j / n;
      V.row(i * (n + 1) + j) << x, y, curvature * (x * x - y * y) + lift;
    }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const int a = i * (n + 1) + j, b = a + n + 1;
      F.row(2 * (i * n + j)) << a, b, b + 1;
      F.row(2 * (i * n + j) + 1) << a, b + 1, a + 1;
    }
  return mesh_from_matrices(V, F);
}

TEST(Surface, OpenSheetIsTrimmedAlongItsBoundaryStrokes) {
  const double half = 0.5, curvature = 0.4;
  const Sketch sketch = testing::sheet_sketch(half, curvature);
  const TriMesh proxy = saddle_grid(0.7, 70, curvature, 0.01);
  ImplicitModel saddle;  // z - c x^2 + c y^2
  saddle.degree = 2;
  saddle.coefficients = Eigen::VectorXd::Zero(10);
  saddle.coefficients << 0, 0, 0, 1, -curvature, 0, 0, curvature, 0, 0;
  const ExtractedSurface out =
      extract(proxy, std::vector<int>(proxy.n_vertices(), 0), {saddle}, sketch, {});
  EXPECT_TRUE(out.summary.open);
  EXPECT_GT(out.summary.trimmed_faces, 0u);
  const double diagonal = sketch.bounding_box().diagonal();
  // Boundary on the boundary strokes: every boundary vertex within 1% of the diagonal of the
  // square [-half, half]^2 (in x, y) ...
  std::size_t boundary = 0;
  for (auto v : out.mesh.vertices()) {
    if (!out.mesh.is_boundary(v)) continue;
    ++boundary;
    const Eigen::Vector3d p = to_eigen(out.mesh.point(v));
    const double to_square = std::abs(std::max(std::abs(p.x()), std::abs(p.y())) - half);
    EXPECT_LT(to_square, 0.01 * diagonal) << p.transpose();
    EXPECT_NEAR(p.z(), curvature * (p.x() * p.x() - p.y() * p.y()), 0.003 * diagonal);
  }
  EXPECT_GT(boundary, 100u);
  // ... and no shrinkage: every boundary-stroke point is within 1% of the surface.
  Sketch strokes_on_border;
  for (const Stroke& s : sketch.strokes)
    if (s.boundary) strokes_on_border.strokes.push_back(s);
  EXPECT_LT(stroke_distance(out.mesh, strokes_on_border, diagonal).max, 0.01);
}

TEST(Surface, MirroredCubeIsSymmetricWithoutGapOrDoubleFaces) {
  Plane plane;  // x = 0, keep x >= 0
  Sketch sketch = testing::cube_sketch();
  sketch.mirror = plane;
  const ClippedMesh half = clip_to_half_space(testing::rounded_box_mesh(4, kHalf, 0.1), plane, 1e-9);
  const ExtractedSurface out = extract(half.mesh, testing::box_labels(half.mesh, kHalf),
                                       testing::box_models(kHalf), half_sketch(sketch, plane), {});
  EXPECT_TRUE(out.summary.mirrored);
  expect_closed_sphere(out.mesh);
  expect_sharp_cube(out);
  double worst = 0.0;
  for (auto v : out.mesh.vertices()) {
    const Eigen::Vector3d r = plane.reflect(to_eigen(out.mesh.point(v)));
    double best = std::numeric_limits<double>::infinity();
    for (auto u : out.mesh.vertices()) best = std::min(best, (to_eigen(out.mesh.point(u)) - r).norm());
    worst = std::max(worst, best);
  }
  EXPECT_LT(worst, 1e-9);
}

}  // namespace
}  // namespace sketchsurf

namespace sketchsurf {
namespace {

TEST(Surface, AnAntennaStrokeIsIgnoredAndMakesNoSpike) {
  const Sketch sketch = testing::sphere_with_antenna_sketch();
  Params params;
  params.segment.restarts = 2;
  const SurfaceResult r = Surfacer(params).run(sketch);
  ASSERT_EQ(r.report.decorations.size(), 1u);
  EXPECT_EQ(r.report.decorations[0].id, static_cast<std::int64_t>(sketch.strokes.size() - 1));
  double farthest = 0.0;
  for (auto v : r.mesh.vertices()) farthest = std::max(farthest, to_eigen(r.mesh.point(v)).norm());
  EXPECT_LT(farthest, 0.56);  // the sphere of radius 0.5, no spike towards x = 0.9
  EXPECT_LT(r.report.checks.beyond, 0.001);
  // The sphere and its antenna along +x are mirror-symmetric about y = 0 and z = 0: reported.
  ASSERT_TRUE(r.report.symmetry.has_value());
  EXPECT_LT(std::abs(r.report.symmetry->plane.normal.x()), 1e-3);
  EXPECT_LT(std::abs(r.report.symmetry->plane.offset), 1e-3);
}

TEST(Surface, AnAntennaAskedForAsATubeIsOneApartFromTheSameSurface) {
  const Sketch sketch = testing::sphere_with_antenna_sketch();
  Params params;
  params.segment.restarts = 2;
  const SurfaceResult plain = Surfacer(params).run(sketch);
  params.prepare.decoration_tubes = true;
  const SurfaceResult r = Surfacer(params).run(sketch);
  EXPECT_EQ(r.report.tubes, 1u);
  // The surface is the one made without the tube, vertex for vertex; the tube's vertices follow.
  const std::size_t n = plain.mesh.n_vertices();
  ASSERT_GT(r.mesh.n_vertices(), n);
  for (std::size_t i = 0; i < n; ++i)
    ASSERT_EQ(to_eigen(r.mesh.point(TriMesh::VertexHandle(static_cast<int>(i)))),
              to_eigen(plain.mesh.point(TriMesh::VertexHandle(static_cast<int>(i)))));
  EXPECT_EQ(r.report.checks.genus, plain.report.checks.genus);
  const MeshTopology t = mesh_topology(r.mesh);
  EXPECT_EQ(t.components, 2u);
  EXPECT_TRUE(t.closed());
  // Round the antenna (x from 0.5 to 0.9 on the x axis): within the radius of the segment, the
  // tip one radius past its end, labelled after the last region and not sharp.
  const double radius = params.prepare.tubes.radius * r.report.diagonal;
  double farthest = 0.0;
  for (std::size_t i = n; i < r.mesh.n_vertices(); ++i) {
    const Eigen::Vector3d p = to_eigen(r.mesh.point(TriMesh::VertexHandle(static_cast<int>(i))));
    const double x = std::clamp(p.x(), 0.5, 0.9);
    EXPECT_LT((p - Eigen::Vector3d(x, 0, 0)).norm(), radius * (1 + 1e-6));
    farthest = std::max(farthest, p.x());
    EXPECT_EQ(r.labels[i], static_cast<int>(r.segmentation.models.size()));
    EXPECT_EQ(r.sharp[i], 0);
  }
  EXPECT_NEAR(farthest, 0.9 + radius, 1e-3 * radius);
}

}  // namespace
}  // namespace sketchsurf

namespace sketchsurf {
namespace {

/// Boundary loops of a mesh (closed chains of boundary halfedges).
std::size_t boundary_loops(const TriMesh& mesh) {
  std::vector<std::uint8_t> seen(mesh.n_halfedges(), 0);
  std::size_t loops = 0;
  for (auto h : mesh.halfedges()) {
    if (!mesh.is_boundary(h) || seen[h.idx()]) continue;
    ++loops;
    for (auto g = h; !seen[g.idx()]; g = mesh.next_halfedge_handle(g)) seen[g.idx()] = 1;
  }
  return loops;
}

/// The surfaced cup: open at its rim (one boundary loop on the rim stroke, nothing left of the
/// cap), closed when asked; `mirrored` surfaces half of it about x = 0.
void expect_open_cup(bool mirrored) {
  Sketch cup = testing::cup_sketch();  // rim radius 0.5 at z = 0.8
  if (mirrored) cup.mirror = Plane{};
  Params params;
  params.segment.restarts = 2;
  const SurfaceResult open = Surfacer(params).run(cup);
  ASSERT_EQ(open.report.openings.size(), 1u);
  EXPECT_EQ(open.report.openings[0].id, 1);
  EXPECT_TRUE(open.report.extraction.open);
  EXPECT_EQ(boundary_loops(open.mesh), 1u);
  for (auto v : open.mesh.vertices()) {
    const Eigen::Vector3d p = to_eigen(open.mesh.point(v));
    EXPECT_LT(p.z(), 0.8 + 0.01);
    if (open.mesh.is_boundary(v)) {  // on the rim stroke
      EXPECT_NEAR(p.z(), 0.8, 0.01);
      EXPECT_NEAR(std::hypot(p.x(), p.y()), 0.5, 0.01);
    } else if (p.z() > 0.7) {        // no cap left: everything up there is the wall
      EXPECT_GT(std::hypot(p.x(), p.y()), 0.4) << p.transpose();
    }
  }
  EXPECT_TRUE(open.report.checks.warnings.empty());

  params.prepare.open_rims = false;
  const SurfaceResult closed = Surfacer(params).run(cup);
  EXPECT_TRUE(closed.report.openings.empty());
  EXPECT_EQ(boundary_loops(closed.mesh), 0u);
}

TEST(Surface, ACupIsOpenAtItsRim) { expect_open_cup(false); }

TEST(Surface, AMirroredCupIsOpenAtItsRim) { expect_open_cup(true); }

}  // namespace
}  // namespace sketchsurf
