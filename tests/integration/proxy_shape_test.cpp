// The automatic proxy has the shape the strokes depict, on sketches drawn (synthesize_sketch, net
// style) on ground-truth shapes: a torus keeps its hole, two nearby spheres (and boxes) stay
// apart, a chair's legs stay apart, a thin plate is not inflated, a mug is one closed part, and no
// surface runs past the strokes' extent.

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "surfacing/proxy/proxy.h"
#include "surfacing/quality/checks.h"
#include "surfacing/quality/eval.h"
#include "surfacing/quality/synth.h"
#include "tests/support/truth_suite.h"

namespace sketchsurf {
namespace {

struct Made {
  Sketch sketch;
  TriMesh proxy;
  ProxyReport report;
  MeshTopology topology;
};

Made proxy_of(const std::string& shape, const SynthOptions& style = {},
              const ProxyOptions& options = {}) {
  Made m;
  m.sketch = synthesize_sketch(testing::truth_shape(shape).mesh, style);
  m.proxy = make_proxy(m.sketch, options, {}, &m.report);
  m.topology = mesh_topology(m.proxy);
  return m;
}

// Drawn mid-air (synthesize_sketch's vr style) with the flaws of `seed`.
SynthOptions vr_style(unsigned seed) {
  SynthOptions vr;
  vr.style = SynthOptions::Style::Vr;
  vr.seed = seed;
  return vr;
}

// Generalised winding number of the closed mesh at p (1 inside, 0 outside): the solid angles of
// its triangles seen from p (Van Oosterom & Strackee 1983) over 4 pi.
double winding_number(const TriMesh& mesh, const Eigen::Vector3d& p) {
  double sum = 0.0;
  for (const auto f : mesh.faces()) {
    auto h = f.halfedge();
    const Eigen::Vector3d a = to_eigen(mesh.point(h.from())) - p,
                          b = to_eigen(mesh.point(h.to())) - p,
                          c = to_eigen(mesh.point(h.next().to())) - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    sum += 2.0 * std::atan2(a.dot(b.cross(c)),
                            la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb);
  }
  return sum / (4.0 * std::numbers::pi);
}

// No area of the proxy beyond the strokes' bounding box grown by `margin` of its diagonal.
void expect_within_strokes(const Made& m, double margin) {
  BoundingBox box = m.sketch.bounding_box();
  const double grow = margin * box.diagonal();
  box.min.array() -= grow;
  box.max.array() += grow;
  std::size_t outside = 0;
  for (const auto v : m.proxy.vertices()) {
    const Eigen::Vector3d p = to_eigen(m.proxy.point(v));
    outside += (p.array() < box.min.array()).any() || (p.array() > box.max.array()).any();
  }
  EXPECT_LE(outside, m.proxy.n_vertices() / 100) << "vertices outside the strokes' grown box";
}

TEST(ProxyShape, MugIsOneClosedPartWithinItsStrokes) {
  const Made m = proxy_of("mug");
  EXPECT_TRUE(m.topology.closed());
  EXPECT_EQ(m.topology.components, 1u);
  expect_within_strokes(m, 0.05);
}

// The truth's handle (y up, centred): a ring of radius 0.13 about (0.25, 0, 0) in the xy plane,
// tube 0.03, meeting the wall at y = +-0.115. Its centreline just outside the wall at both ends
// is inside the proxy; the middle of its opening is not (as in the truth). The proxy is one part
// within the strokes.
void expect_handle_open_and_attached(const Made& m) {
  EXPECT_EQ(m.topology.components, 1u);
  expect_within_strokes(m, 0.05);
  const TriMesh& truth = testing::truth_shape("mug").mesh;
  const Eigen::Vector3d opening(0.27, 0.0, 0.0);
  ASSERT_LT(winding_number(truth, opening), 0.5);
  EXPECT_LT(winding_number(m.proxy, opening), 0.5) << "handle opening";
  for (const double y : {-0.1256, 0.1256}) {
    const Eigen::Vector3d end(0.216, y, 0.0);
    ASSERT_GT(winding_number(truth, end), 0.5);
    EXPECT_GT(winding_number(m.proxy, end), 0.5) << "handle end at y " << y;
  }
}

// Smoothed with the ladder's second weight, the handle's opening is webbed to the rim by a bulge
// far from the strokes (and its windows' membranes close it); a less smoothed solve keeps it open
// (the net is a clean curve network: its ladder starts below the first weight).
TEST(ProxyShape, MugKeepsItsHandle) {
  const Made m = proxy_of("mug");
  EXPECT_EQ(m.topology.genus, 1);
  EXPECT_LT(m.report.lambda, ProxyOptions{}.lambda_min * ProxyOptions{}.lambda_step);
  expect_handle_open_and_attached(m);
  EXPECT_LT(m.report.missed_strokes, 0.01);
}

// The report tells a proxy that has melted away what the strokes depict: smoothed with the
// ladder's largest weight, the mug's handle is webbed into its body and a third of the stroke
// points lie farther than miss_distance from the surface.
TEST(ProxyShape, AMugSmoothedIntoABlobMissesItsHandlesStrokes) {
  ProxyOptions smooth;
  smooth.lambda = smooth.lambda_max;
  const Made m = proxy_of("mug", {}, smooth);
  EXPECT_EQ(m.topology.genus, 0);
  EXPECT_GT(m.report.missed_strokes, 0.2);
}

// Drawn mid-air (tremor, gaps, forgotten strokes), the double wall's inside layer pinches out
// between strokes: the windows it leaves are closed, the handle's opening stays. Near the
// handle's upper end a dropped stroke leaves VIPSS's surface two cones that almost touch; the
// strokes drawn across that gap bridge it, so the handle meets the wall at both ends.
// (With the ladder's second weight: this draw's body is rounded off its strokes, and the first
// weight is kept instead, which needs no bridge; see the car below.)
TEST(ProxyShape, MugDrawnInVrKeepsItsHandleAndNoWindow) {
  ProxyOptions second;
  second.rounded_misfit = 1.0;
  const Made m = proxy_of("mug", vr_style(1), second);
  EXPECT_FALSE(m.report.rounded);
  EXPECT_EQ(m.topology.genus, 1);
  EXPECT_GE(m.report.bridges, 1u);
  expect_handle_open_and_attached(m);
  const Made least = proxy_of("mug", vr_style(1));
  EXPECT_TRUE(least.report.rounded);
  EXPECT_EQ(least.topology.genus, 1);
  expect_handle_open_and_attached(least);
}

// A car drawn mid-air: the ladder's second weight (1e-4) rounds its shoulders and panels off the
// strokes, every stroke near a rounding on the same side (their misfits shared, above
// rounded_misfit); the first weight on denser samples follows the shape, not the tremor, and is
// about twice as near the truth. A sphere drawn mid-air, whose strokes wobble each on its own,
// keeps the smoother surface.
TEST(ProxyShape, ACarDrawnInVrIsNotRoundedOffItsStrokes) {
  const TriMesh& truth = testing::truth_shape("car").mesh;
  const Made m = proxy_of("car", vr_style(1));
  EXPECT_TRUE(m.report.rounded);
  EXPECT_GT(m.report.shared_misfit, ProxyOptions{}.rounded_misfit);
  EXPECT_EQ(m.report.samples, ProxyOptions{}.clean_points);
  EXPECT_EQ(m.topology.genus, 0);
  EXPECT_EQ(m.topology.components, 1u);
  const Evaluation e = evaluate(m.proxy, truth);
  EXPECT_LT(e.accuracy.median, 0.0012);
  EXPECT_LT(e.accuracy.p95, 0.005);
  ProxyOptions second;
  second.rounded_misfit = 1.0;
  const Evaluation s = evaluate(proxy_of("car", vr_style(1), second).proxy, truth);
  EXPECT_GT(s.accuracy.median, 1.5 * e.accuracy.median);
  const Made sphere = proxy_of("sphere", vr_style(1));
  EXPECT_FALSE(sphere.report.rounded);
  EXPECT_LT(sphere.report.shared_misfit, 0.3);
}

// Another draw (seed 2): the smoother weights web the handle to the wall (a third of the surface
// far from every stroke); the least smoothed solve keeps the opening.
TEST(ProxyShape, MugDrawnInVrWithoutAWebOverItsHandle) {
  const Made m = proxy_of("mug", vr_style(2));
  EXPECT_LT(m.report.far_area, 0.05);
  expect_handle_open_and_attached(m);
  // A window through its front wall, whose saddle lies just inside the surface (the inside layer
  // thinner than a cell there), is closed as well: the handle is the one opening.
  EXPECT_EQ(m.topology.genus, 1);
}

// The share of the mug's floor that lies inside the proxy: the points of its mid-plane (the truth's
// outside bottom is 0.05 below the cavity's, of a height of 0.7) within 0.7 of the body's radius
// of its axis, on a grid of 0.02.
double floor_inside(const TriMesh& proxy) {
  const TriMesh& truth = testing::truth_shape("mug").mesh;
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e9), hi = -lo;
  for (const auto v : truth.vertices()) {
    lo = lo.cwiseMin(to_eigen(truth.point(v)));
    hi = hi.cwiseMax(to_eigen(truth.point(v)));
  }
  const double radius = 0.5 * (hi.z() - lo.z()), y = lo.y() + 0.025 / 0.7 * (hi.y() - lo.y());
  const Eigen::Vector3d axis(lo.x() + radius, y, 0.5 * (lo.z() + hi.z()));
  EXPECT_GT(winding_number(truth, axis), 0.5);
  int floor = 0, inside = 0;
  for (double x = -0.7 * radius; x <= 0.7 * radius; x += 0.02)
    for (double z = -0.7 * radius; z <= 0.7 * radius; z += 0.02) {
      if (std::hypot(x, z) > 0.7 * radius) continue;
      ++floor;
      inside += winding_number(proxy, axis + Eigen::Vector3d(x, 0.0, z)) > 0.5;
    }
  return static_cast<double>(inside) / floor;
}

// Drawn mid-air (seed 3), the mug's floor, a double wall, pinches out between its strokes into a
// window wider than the narrow windows (its saddle's value 0.044 of the diagonal; with
// window_undrawn = 0, 77% of the floor is inside the proxy). The strokes stand all round it, none
// winds round it or runs along it, so it is closed as well; the handle, whose C winds round its
// opening, stays open. Low on the wall beside the handle, the wall's inside layer thins below
// the polygonisation's cells along a strip: its saddle lies just inside the surface, so close to
// the floor that the space across it rises only from the saddle's value, and the strip runs on
// past the saddle's own membrane; it is flooded as a window's open region is, and the handle is
// the one opening.
TEST(ProxyShape, MugDrawnInVrHasNoWindowThroughItsFloor) {
  const Made m = proxy_of("mug", vr_style(3));
  EXPECT_GT(floor_inside(m.proxy), 0.99);
  expect_handle_open_and_attached(m);
  EXPECT_EQ(m.topology.genus, 1);
}

// Drawn mid-air (seed 2), a curved shell's inside layer thins below the polygonisation's cells at
// two points between strokes: their saddles lie just inside the surface, yet the polygonised
// surface opens a window at each; they are closed as windows are.
TEST(ProxyShape, CurvedShellDrawnInVrHasNoWindow) {
  const Made m = proxy_of("curved_shell", vr_style(2));
  EXPECT_EQ(m.topology.components, 1u);
  EXPECT_EQ(m.topology.genus, 0);
  EXPECT_GT(m.report.windows, 0u);
}

// Drawn mid-air, a thin plate's two faces pinch out between strokes into long slots through it;
// their open region is flooded from the slots' saddles and closed (seed 2: four handles without).
TEST(ProxyShape, ThinPlateDrawnInVrHasNoSlots) {
  const Made m = proxy_of("thin_plate", vr_style(2));
  EXPECT_EQ(m.topology.components, 1u);
  EXPECT_EQ(m.topology.genus, 0);
  EXPECT_GT(m.report.windows, 0u);
  expect_within_strokes(m, 0.05);
}

TEST(ProxyShape, TorusKeepsItsHole) {
  const Made m = proxy_of("torus");
  EXPECT_EQ(m.topology.components, 1u);
  EXPECT_EQ(m.topology.genus, 1);
  // The centre of the hole is outside.
  const Eigen::Vector3d centre = 0.5 * (m.sketch.bounding_box().min + m.sketch.bounding_box().max);
  EXPECT_LT(winding_number(m.proxy, centre), 0.5);
  expect_within_strokes(m, 0.05);
}

// A clean curve network (every stroke on the surface, crossings exact) is not smoothed: the
// metaballs' bulges between their sections keep their shape. Drawn mid-air, the same strokes pass
// each other by the hand's tremor and are smoothed.
TEST(ProxyShape, ACleanCurveNetworkOfBlobsIsNotSmoothedAway) {
  const TriMesh& truth = testing::truth_shape("metaballs").mesh;
  const Made net = proxy_of("metaballs");
  EXPECT_GE(net.report.crossing_gap, 0.0);
  EXPECT_LT(net.report.crossing_gap, ProxyOptions{}.clean_gap);
  EXPECT_EQ(net.report.lambda, ProxyOptions{}.clean_lambda);
  // Bounds that the surface smoothed from the ladder's first weight exceeds.
  const Evaluation e = evaluate(net.proxy, truth);
  EXPECT_LT(e.accuracy.median, 0.00011);
  EXPECT_LT(e.accuracy.p95, 0.0008);
  const Made vr = proxy_of("metaballs", vr_style(1));
  EXPECT_GT(vr.report.crossing_gap, 5.0 * ProxyOptions{}.clean_gap);
  EXPECT_GT(vr.report.lambda, ProxyOptions{}.lambda_min);
  EXPECT_EQ(vr.report.samples, ProxyOptions{}.points);
}

// A creased shape's clean network: a section cuts the corner where it turns across a crease, and
// passes the crossing stroke there by that chord; its straight crossings are exact, so it is read
// as clean and smoothed less. Its proxy follows the faces that a smoother one rounds between the
// strokes (p95 0.58% of the diagonal read as drawn).
TEST(ProxyShape, ACreasedShapesCleanNetworkIsReadAsClean) {
  const Made m = proxy_of("wedge");
  EXPECT_GE(m.report.crossing_gap, 0.0);
  EXPECT_LT(m.report.crossing_gap, ProxyOptions{}.clean_gap);
  EXPECT_FALSE(m.report.clean_windows);
  EXPECT_EQ(m.topology.genus, 0);
  EXPECT_LT(evaluate(m.proxy, testing::truth_shape("wedge").mesh).accuracy.p95, 0.004);
}

// An L-bracket's clean network: between its few sections the nearly interpolating first solve
// sinks through the thin walls in windows (9 handles); the ladder goes on as for a drawn sketch.
TEST(ProxyShape, ACleanNetworkOfThinWallsIsSmoothedAsDrawn) {
  const Made m = proxy_of("l_bracket");
  EXPECT_LT(m.report.crossing_gap, ProxyOptions{}.clean_gap);
  EXPECT_TRUE(m.report.clean_windows);
  EXPECT_GT(m.report.lambda, ProxyOptions{}.lambda_min);
  EXPECT_EQ(m.topology.genus, 0);
  EXPECT_EQ(m.topology.components, 1u);
}

// A clean network's sparse sections of a long, gently curved body (a car's) are followed between
// the samples only with denser samples: with the count a hand-drawn sketch gets, the body sinks
// between them.
TEST(ProxyShape, ACleanNetworksBodyFollowsItsStrokesBetweenTheSamples) {
  const Made net = proxy_of("car");
  EXPECT_EQ(net.report.samples, ProxyOptions{}.clean_points);
  const Evaluation e = evaluate(net.proxy, testing::truth_shape("car").mesh);
  EXPECT_LT(e.accuracy.median, 0.0004);
  EXPECT_LT(e.accuracy.p95, 0.003);
  ProxyOptions sparse;
  sparse.clean_points = sparse.points;
  const Evaluation s = evaluate(proxy_of("car", {}, sparse).proxy, testing::truth_shape("car").mesh);
  EXPECT_GT(s.accuracy.median, 1.5 * e.accuracy.median);
}

// A cup's clean network: no weight below the ladder's last closes its zero set (the rim is open),
// and the last (1e-3) rounds the cup off its strokes; the less smoothed solve, whose surface past
// the rim the strokes' neighbourhood confines as well, is kept, about twice as near the truth.
TEST(ProxyShape, ACleanCupIsNotRoundedOffItsStrokes) {
  const TriMesh& truth = testing::truth_shape("cup").mesh;
  const Made m = proxy_of("cup");
  EXPECT_TRUE(m.report.rounded);
  EXPECT_LT(m.report.lambda, ProxyOptions{}.lambda_max);
  EXPECT_EQ(m.topology.genus, 0);
  EXPECT_EQ(m.topology.components, 1u);
  expect_within_strokes(m, 0.02);
  const Evaluation e = evaluate(m.proxy, truth);
  EXPECT_LT(e.accuracy.median, 0.00016);
  ProxyOptions smooth;
  smooth.rounded_misfit = 1.0;
  const Made s = proxy_of("cup", {}, smooth);
  EXPECT_EQ(s.report.lambda, ProxyOptions{}.lambda_max);
  EXPECT_GT(evaluate(s.proxy, truth).accuracy.median, 1.5 * e.accuracy.median);
}

// A wedge's slope is a face that the strokes draw, at no axis: it is cut on its strokes as the
// box's sides are, and no bulb hangs past the acute edge. A mug's supporting planes only touch
// its round body, along short arcs of its strokes: none is a drawn face.
TEST(ProxyShape, AWedgesSlopeIsCutOnItsStrokes) {
  const TriMesh& truth = testing::truth_shape("wedge").mesh;
  for (const SynthOptions& style : {SynthOptions{}, vr_style(3)}) {
    const Made m = proxy_of("wedge", style);
    EXPECT_GE(m.report.planes_drawn_in, 1u);
    const Evaluation e = evaluate(m.proxy, truth);
    EXPECT_LT(e.accuracy.p95, 0.02);
    EXPECT_LT(e.accuracy.max, 0.035);
  }
  EXPECT_EQ(proxy_of("mug").report.planes_drawn_in, 0u);
}

TEST(ProxyShape, TwoNearbySpheresStayApart) {
  const Made m = proxy_of("two_spheres");
  EXPECT_EQ(m.topology.components, 2u);
  EXPECT_EQ(m.topology.genus, 0);
  expect_within_strokes(m, 0.05);
}

// Drawn mid-air, the two boxes' facing edges nearly touch and VIPSS joins them by thin strands
// (two in draw 1: a handle; one in draw 3), which no stroke runs along: the necks are cut.
TEST(ProxyShape, TwoNearbyBoxesDrawnInVrStayApart) {
  for (const unsigned seed : {1u, 3u}) {
    const Made m = proxy_of("two_boxes", vr_style(seed));
    EXPECT_EQ(m.topology.components, 2u) << "draw " << seed;
    EXPECT_EQ(m.topology.genus, 0) << "draw " << seed;
    EXPECT_GT(m.report.necks, 0u) << "draw " << seed;
    expect_within_strokes(m, 0.05);
  }
}

// Between the legs, below the seat (+y up), the proxy is empty, as the truth is: under the seat's
// middle and, with `sides`, between each two neighbouring legs (where a wall would hang); and
// at most `far_most` of its surface is far from every stroke.
void expect_legs_apart(const SynthOptions& style, bool sides = false, double far_most = 0.05) {
  const testing::TruthShape chair = testing::truth_shape("chair");
  const Made m = proxy_of("chair", style);
  BoundingBox legs;
  for (const auto v : chair.mesh.vertices()) legs.extend(to_eigen(chair.mesh.point(v)));
  const Eigen::Vector3d size = legs.max - legs.min;
  // (x, z) as fractions of the box: its middle, and the middles of its sides on the legs' line.
  std::vector<std::pair<double, double>> probes{{0.5, 0.5}};
  if (sides) probes.insert(probes.end(), {{0.04, 0.5}, {0.96, 0.5}, {0.5, 0.04}, {0.5, 0.96}});
  for (const auto& [fx, fz] : probes)
    for (const double t : {0.1, 0.2}) {
      const Eigen::Vector3d under = legs.min + Eigen::Vector3d(fx, t, fz).cwiseProduct(size);
      EXPECT_LT(winding_number(chair.mesh, under), 0.5) << "the truth is empty at " << under.transpose();
      EXPECT_LT(winding_number(m.proxy, under), 0.5) << "legs webbed at " << under.transpose();
    }
  EXPECT_LT(m.report.far_area, far_most);
  expect_within_strokes(m, 0.05);
}

// The smoother weight of the ladder melts legs, seat and back into one block (its faces far from
// every stroke); the proxy keeps the less smooth solve.
TEST(ProxyShape, ChairLegsStayApart) { expect_legs_apart({}); }

// Drawn mid-air (seed 2), the ladder's second weight webs a leg to the seat (9% of the surface far
// from every stroke); the least smoothed solve keeps them apart.
TEST(ProxyShape, ChairDrawnInVrLegsStayApart) { expect_legs_apart(vr_style(2)); }

// Drawn mid-air (seed 3), VIPSS's normals at the legs' inner sides are those of a blob round each
// side's two legs: a wall hangs between them. The legs' own strokes surround their axes; solved
// again with those normals kept, the legs stand apart on every side (the back's thin plate,
// drawn by its rim, keeps a tenth of the surface far from every stroke; the walls were another).
TEST(ProxyShape, ChairDrawnInVrHasNoWallBetweenItsLegs) {
  expect_legs_apart(vr_style(3), true, 0.12);
  ProxyOptions without;
  without.part_reach = 0.0;
  const Made webbed = proxy_of("chair", vr_style(3), without);
  EXPECT_GT(webbed.report.far_area, 0.2);
}

// VIPSS pinches the glass's stem thinner than its strokes (radius 0.009 of the diagonal under
// strokes 0.02 from its axis, net and vr draw 2): the stem is a neck, but its strokes cross it, so
// it is not cut.
TEST(ProxyShape, WineglassStemIsNotCut) {
  SynthOptions net;
  for (const SynthOptions& style : {net, vr_style(2)}) {
    const Made m = proxy_of("wineglass", style);
    EXPECT_EQ(m.topology.components, 1u);
    EXPECT_EQ(m.topology.genus, 0);
  }
}

TEST(ProxyShape, WineglassFootEndsAtItsRim) {
  // The foot is a disc of radius 0.26 about the y axis (y from -0.5 to -0.45), drawn by its rim and
  // strokes across its top. Past the rim no stroke is; drawn mid-air, VIPSS's smoothed zero set
  // runs on there as a skirt to the box around the strokes (radius 0.39 at the box's corners)
  // unless the outline stops it. The clean net's nearly interpolating solve ends at the rim.
  const testing::TruthShape glass = testing::truth_shape("wineglass");
  const ProxyOptions outline;  // the defaults cut at the outline
  for (const SynthOptions::Style style : {SynthOptions::Style::Net, SynthOptions::Style::Vr}) {
    SynthOptions options;
    options.style = style;
    Made m;
    m.sketch = synthesize_sketch(glass.mesh, options);
    m.proxy = make_proxy(m.sketch, outline, {}, &m.report);
    if (style == SynthOptions::Style::Vr) {
      EXPECT_TRUE(m.report.outline_cut);
    }
    const double diagonal = m.sketch.bounding_box().diagonal();
    double widest = 0.0;
    for (const auto v : m.proxy.vertices()) {
      const Eigen::Vector3d p = to_eigen(m.proxy.point(v));
      if (p.y() < -0.44) widest = std::max(widest, std::hypot(p.x(), p.z()));
    }
    EXPECT_GT(widest, 0.24) << "the foot is kept";
    EXPECT_LT(widest, 0.26 + 0.06 * diagonal) << "no skirt past the rim";
  }
}

TEST(ProxyShape, ThinPlateIsNotInflated) {
  const testing::TruthShape plate = testing::truth_shape("thin_plate");
  Made m;
  m.sketch = synthesize_sketch(plate.mesh);
  m.proxy = make_proxy(m.sketch, {}, {}, &m.report);
  // The plate's thin axis is its bounding box's shortest; the proxy's extent along it stays small.
  BoundingBox truth, proxy;
  for (const auto v : plate.mesh.vertices()) truth.extend(to_eigen(plate.mesh.point(v)));
  for (const auto v : m.proxy.vertices()) proxy.extend(to_eigen(m.proxy.point(v)));
  Eigen::Index thin = 0;
  (truth.max - truth.min).minCoeff(&thin);
  const double diagonal = truth.diagonal();
  EXPECT_LT(proxy.max[thin] - proxy.min[thin], 0.15 * diagonal);
  expect_within_strokes(m, 0.05);
  // Between its strokes the plate's two faces come within a cell of each other: no window opens
  // through it there.
  const MeshTopology topology = mesh_topology(m.proxy);
  EXPECT_EQ(topology.components, 1u);
  EXPECT_EQ(topology.genus, 0);
}

// How far the proxy reaches past the strokes' bounding box, on its farthest side.
double farthest_past_strokes_box(const Made& m) {
  const BoundingBox strokes = m.sketch.bounding_box();
  BoundingBox proxy;
  for (const auto v : m.proxy.vertices()) proxy.extend(to_eigen(m.proxy.point(v)));
  return std::max((proxy.max - strokes.max).maxCoeff(), (strokes.min - proxy.min).maxCoeff());
}

// A face drawn at the strokes' extreme (a box's side, a plate's face) is cut by the box round the
// strokes; drawn in after the choice of smoothing, the cut lies on them, not two hundredths (or
// two thousandths) of the diagonal out, and no area is left on the check's box there.
TEST(ProxyShape, FacesAtTheStrokesExtremeAreCutCloseToThem) {
  for (const std::string shape : {"box", "plate_two_holes"}) {
    const testing::TruthShape truth = testing::truth_shape(shape);
    const Made m = proxy_of(shape);
    EXPECT_EQ(m.report.box_drawn_in, 6) << shape;
    const Evaluation e = evaluate(m.proxy, truth.mesh);
    EXPECT_LT(e.accuracy.median, 0.0005) << shape << ": the faces on their strokes";
    EXPECT_LT(e.accuracy.p95, 0.007) << shape;
    EXPECT_LT(e.completeness.p95, 0.007) << shape;
    EXPECT_EQ(check_shape(m.proxy, {}, m.sketch, false).outside_box, 0.0) << shape;
    EXPECT_EQ(m.topology.genus, truth.genus) << shape;
  }
}

// Drawn mid-air, the strokes across a box's face run on past its edges by up to 2% of the
// diagonal: the face is drawn in where the strokes along it lie, not at those ends (cut there, the
// whole face stood 1-2% out: p95 1.6-1.8%). A chair's feet, drawn only by the ends of its legs'
// strokes, have no stroke along the floor and keep their full length.
TEST(ProxyShape, FacesDrawnInVrLieOnTheirStrokesNotWhereStrokesOvershoot) {
  ProxyOptions at_ends;
  at_ends.overshoot = 0.0;
  for (const std::string shape : {"box", "wedge"})
    for (unsigned draw : {1u, 2u}) {
      SCOPED_TRACE(shape + " " + std::to_string(draw));
      const TriMesh& truth = testing::truth_shape(shape).mesh;
      const Evaluation e = evaluate(proxy_of(shape, vr_style(draw)).proxy, truth);
      EXPECT_LT(e.accuracy.median, 0.0045);
      EXPECT_LT(e.accuracy.p95, 0.0095);
      EXPECT_GT(evaluate(proxy_of(shape, vr_style(draw), at_ends).proxy, truth).accuracy.p95, 0.015);
    }
  const Made chair = proxy_of("chair", vr_style(2));
  const BoundingBox strokes = chair.sketch.bounding_box();
  double lowest = std::numeric_limits<double>::infinity();
  for (const auto v : chair.proxy.vertices()) lowest = std::min(lowest, to_eigen(chair.proxy.point(v)).y());
  EXPECT_LT(lowest - strokes.min.y(), 0.005 * strokes.diagonal()) << "the feet are cut short";
}

// Blobs drawn by a few loops (metaballs, vr) only touch the sides of their box: their smooth
// surface bulges past the strokes there, and a closer cut would flatten it.
TEST(ProxyShape, BlobsReachingPastTheirStrokesAreNotFlattened) {
  const Made m = proxy_of("metaballs", vr_style(3));
  EXPECT_EQ(m.report.box_drawn_in, 0);
  EXPECT_GT(farthest_past_strokes_box(m), 0.011 * m.sketch.bounding_box().diagonal()) << "the surface past a side";
}

// An L-bracket drawn mid-air: the thin end of each arm is a face on a side of the strokes' box,
// but fills a fifth of it, under the span that makes a side a drawn face. Its rim and a stroke
// across it run flat along the side: drawn in on them, the end is cut close to its strokes
// instead of bulging out to the wider box (max 4.1-4.2% of the diagonal before).
TEST(ProxyShape, TheThinEndsOfAnLBracketDrawnInVrAreCutOnTheirStrokes) {
  const TriMesh& truth = testing::truth_shape("l_bracket").mesh;
  for (unsigned draw : {1u, 2u, 3u}) {
    SCOPED_TRACE(draw);
    const Made m = proxy_of("l_bracket", vr_style(draw));
    const Evaluation e = evaluate(m.proxy, truth);
    EXPECT_LT(e.accuracy.max, 0.03);
    EXPECT_LT(e.accuracy.p95, 0.02);
  }
  ProxyOptions whole_sides_only;
  whole_sides_only.confine_box_partial = 1.0;
  const Made m = proxy_of("l_bracket", vr_style(3), whole_sides_only);
  EXPECT_GT(evaluate(m.proxy, truth).accuracy.max, 0.035);
}

// A sphere's top, drawn in vr by loops round it, touches its box's sides with arcs that are not
// flat over the band: no side is drawn in, partly or whole.
TEST(ProxyShape, ASpheresTopIsNotAPartialFace) {
  for (unsigned draw : {1u, 2u}) EXPECT_EQ(proxy_of("sphere", vr_style(draw)).report.box_drawn_in, 0) << draw;
}

// Where drawing the box in would pierce the surface (a wineglass's thin foot, drawn in vr, whose
// top dips towards its flat bottom: two holes, even halfway out), that side keeps the wider cut;
// the other face the strokes draw (the mouth's rim) is drawn in on its own.
TEST(ProxyShape, DrawingTheBoxInPiercesNoThinFoot) {
  const Made m = proxy_of("wineglass", vr_style(3));
  EXPECT_EQ(m.report.box_drawn_in, 1);
  EXPECT_EQ(m.topology.genus, 0);
  EXPECT_EQ(m.topology.components, 1u);
  const BoundingBox strokes = m.sketch.bounding_box();
  BoundingBox proxy;
  for (const auto v : m.proxy.vertices()) proxy.extend(to_eigen(m.proxy.point(v)));
  EXPECT_LT(proxy.max.y() - strokes.max.y(), 0.003 * strokes.diagonal()) << "the mouth on its rim";
  EXPECT_GT(strokes.min.y() - proxy.min.y(), 0.01 * strokes.diagonal()) << "the foot at the wider box";
}

// Drawn mid-air (seed 1), the wineglass's thin foot dips through its drawn-in bottom face between
// the strokes across it, and a thin plate's faces pinch through its drawn-in side: the cuts open
// holes through them (genus 2 each without the membranes), closed by a membrane on the face, as
// no stroke draws an opening there. The glass's foot is then a whole disc.
TEST(ProxyShape, HolesAFaceDrawnInCutsThroughAThinPartAreClosed) {
  for (const char* shape : {"wineglass", "thin_plate"}) {
    const Made m = proxy_of(shape, vr_style(1));
    EXPECT_EQ(m.topology.genus, 0) << shape;
    EXPECT_EQ(m.topology.components, 1u) << shape;
    EXPECT_GT(m.report.face_holes, 0u) << shape;
    if (std::string(shape) != "wineglass") continue;
    // The foot (a disc of radius 0.26 from y = -0.5 to -0.45, thinning towards its rim) is inside
    // the proxy just above its bottom, out to near its rim, but for a few points where VIPSS's foot
    // is thinner than that (26 of 60 without the membranes, 48 with them).
    int inside = 0, count = 0;
    for (double r = 0.0; r < 0.2; r += 0.04)
      for (int k = 0; k < 12; ++k, ++count) {
        const double t = 2.0 * std::numbers::pi * k / 12;
        inside += winding_number(m.proxy, Eigen::Vector3d(r * std::cos(t), -0.49, r * std::sin(t))) > 0.5;
      }
    EXPECT_GE(inside, count * 3 / 4) << "of " << count << " points over the foot's bottom";
  }
}

// Where the close cut would pierce the foot but one halfway out does not (the wineglass drawn as a
// curve network: its rim's cap and its foot's bottom), the faces are cut halfway out, inside the
// check's box and still one closed surface.
TEST(ProxyShape, ACutThatWouldPierceIsMadeHalfwayOut) {
  const Made m = proxy_of("wineglass");
  EXPECT_EQ(m.report.box_drawn_in, 2);
  EXPECT_EQ(m.topology.genus, 0);
  EXPECT_EQ(m.topology.components, 1u);
  EXPECT_LT(farthest_past_strokes_box(m), 0.0105 * m.sketch.bounding_box().diagonal()) << "the surface past a side";
  EXPECT_EQ(check_shape(m.proxy, {}, m.sketch, false).outside_box, 0.0);
}

}  // namespace
}  // namespace sketchsurf
