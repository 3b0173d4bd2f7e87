#include "surfacing/segment/pearl.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>

#include "surfacing/error.h"
#include "tests/support/shapes.h"

namespace sketchsurf {
namespace {

using V3 = Eigen::Vector3d;

TriMesh cube_proxy() { return testing::rounded_box_mesh(3, V3(0.5, 0.5, 0.5), 0.04); }

SegmentOptions small_options() {
  SegmentOptions o;
  o.restarts = 3;
  return o;
}

// Proxy vertices nearest to the centre of face (axis, sign) of the cube, within `radius`.
std::vector<int> face_patch(const TriMesh& mesh, int axis, double sign, double radius) {
  V3 c = V3::Zero();
  c[axis] = 0.5 * sign;
  std::vector<int> out;
  for (auto v : mesh.vertices())
    if ((to_eigen(mesh.point(v)) - c).norm() < radius) out.push_back(v.idx());
  return out;
}

TEST(SegmentOptions, RejectsInvalidValues) {
  std::string why;
  EXPECT_TRUE(SegmentOptions{}.valid(&why)) << why;
  auto broken = [](auto change) {
    SegmentOptions o;
    change(o);
    std::string w;
    return !o.valid(&w) && !w.empty();
  };
  EXPECT_TRUE(broken([](SegmentOptions& o) { o.epsilon = 0; }));
  EXPECT_TRUE(broken([](SegmentOptions& o) { o.w_smooth = -1; }));
  EXPECT_TRUE(broken([](SegmentOptions& o) { o.cluster_counts.clear(); }));
  EXPECT_TRUE(broken([](SegmentOptions& o) { o.max_degree = 5; }));
  EXPECT_TRUE(broken([](SegmentOptions& o) { o.restarts = 0; }));
  EXPECT_TRUE(broken([](SegmentOptions& o) { o.min_gain = -0.1; }));
  EXPECT_TRUE(broken([](SegmentOptions& o) { o.min_gain = 1.0; }));
  EXPECT_TRUE(broken([](SegmentOptions& o) { o.fold = -0.1; }));
  EXPECT_TRUE(broken([](SegmentOptions& o) { o.fold_share = 1.0; }));
  EXPECT_TRUE(broken([](SegmentOptions& o) { o.association.uncrossed_weight = 0; }));
  SegmentOptions bad;
  bad.max_iterations = 0;
  EXPECT_THROW(segment(testing::cube_sketch(), cube_proxy(), bad), Error);
}

TEST(Pearl, TheNextLowerDegreeLadderStopsAtPlanes) {
  // all_lower_degrees off (§4.2's d - 1 proposals): the cube's faces come down to planes, whose
  // regions must not ask for a degree-0 fit (that threw, and was reported as "cancelled").
  SegmentOptions o = small_options();
  o.all_lower_degrees = false;
  const Segmentation s = segment(testing::cube_sketch(1.0), cube_proxy(), o);
  EXPECT_GE(s.models.size(), 6u);
  EXPECT_TRUE(std::any_of(s.models.begin(), s.models.end(),
                          [](const ImplicitModel& m) { return m.degree == 1; }));
}

TEST(Pearl, DeterministicWhateverTheThreadCount) {
  const Sketch sketch = testing::cube_sketch(1.0);
  const TriMesh proxy = cube_proxy();
  SegmentOptions one = small_options(), two = small_options();
  one.threads = 1;
  two.threads = 2;
  const Segmentation a = segment(sketch, proxy, one), b = segment(sketch, proxy, two);
  EXPECT_EQ(a.labels, b.labels);
  EXPECT_EQ(a.summary.restart_energies, b.summary.restart_energies);
  EXPECT_EQ(a.summary.energy_history, b.summary.energy_history);
  ASSERT_EQ(a.models.size(), b.models.size());
  for (std::size_t i = 0; i < a.models.size(); ++i) EXPECT_EQ(a.models[i].coefficients, b.models[i].coefficients);
  // A different seed is a different (valid) run.
  SegmentOptions other = one;
  other.seed = 7;
  EXPECT_EQ(segment(sketch, proxy, other).models.size(), a.models.size());
}

// Users wait on this stage: progress moves within the runs (not only between restarts), never
// backwards, and a cancellation during a run stops the segmentation with ErrorKind::Cancelled.
TEST(Pearl, ReportsProgressWithinRunsAndCancels) {
  const Sketch sketch = testing::cube_sketch(1.0);
  const TriMesh proxy = cube_proxy();
  SegmentOptions options;
  options.restarts = 1;
  options.threads = 1;
  Segmenter segmenter(sketch, proxy, options);
  std::vector<double> fractions;
  const Segmentation s = segmenter.run(Progress([&](std::string_view stage, double f) {
    EXPECT_EQ(stage, "segmentation");
    fractions.push_back(f);
    return true;
  }));
  ASSERT_GE(s.summary.iterations, 2);
  EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
  const auto within = std::count_if(fractions.begin(), fractions.end(),
                                    [](double f) { return f > 0.0 && f < 1.0; });
  EXPECT_GE(within, s.summary.iterations - 1);  // every iteration but the last reports
  EXPECT_EQ(fractions.back(), 1.0);

  try {
    segmenter.run(Progress([](std::string_view, double f) { return f == 0.0; }));
    FAIL() << "a cancelled run returned";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Cancelled);
  }
}

TEST(Pearl, WithoutATieWindowTheLowestEnergyRunIsKept) {
  SegmentOptions o = small_options();
  o.tie = 0.0;
  o.fold = 0.0;
  const Segmentation s =
      segment(testing::cylinder_sketch(), testing::rounded_cylinder_mesh(3, 0.5, 0.5, 0.04), o);
  const auto& e = s.summary.restart_energies;
  ASSERT_EQ(e.size(), 3u);
  EXPECT_EQ(e[s.summary.best_restart], *std::min_element(e.begin(), e.end()));
  EXPECT_TRUE(s.summary.restart_departures.empty());
}

TEST(Pearl, EnergyNeverIncreasesAndBestRestartIsKept) {
  const Segmentation s = segment(testing::cylinder_sketch(), testing::rounded_cylinder_mesh(3, 0.5, 0.5, 0.04),
                                 small_options());
  const auto& h = s.summary.energy_history;
  ASSERT_FALSE(h.empty());
  EXPECT_EQ(static_cast<int>(h.size()), s.summary.iterations);
  for (std::size_t i = 1; i < h.size(); ++i) EXPECT_LE(h[i], h[i - 1] * (1 + 1e-12)) << "iteration " << i;
  // The kept run is the lowest in energy or, within `tie` of it, one that the projection moves
  // far on fewer of the proxy's vertices by more than tie_share, the fewest of such runs; then the
  // same within the wider `fold` window and fold_share.
  const SegmentOptions o = small_options();
  const auto& e = s.summary.restart_energies;
  const auto& d = s.summary.restart_departures;
  ASSERT_EQ(e.size(), 3u);
  ASSERT_EQ(d.size(), 3u);
  for (const double share : d) {
    EXPECT_GE(share, 0.0);
    EXPECT_LE(share, 1.0);
  }
  const auto lowest = static_cast<std::size_t>(std::min_element(e.begin(), e.end()) - e.begin());
  const auto prefer = [&](std::size_t kept, double window, double share) {
    std::size_t fewest = kept;
    for (std::size_t r = 0; r < e.size(); ++r)
      if (e[r] <= e[lowest] * (1.0 + window) && d[r] < d[fewest]) fewest = r;
    return d[fewest] < d[kept] - share ? fewest : kept;
  };
  EXPECT_EQ(static_cast<std::size_t>(s.summary.best_restart),
            prefer(prefer(lowest, o.tie, o.tie_share), o.fold, o.fold_share));
  EXPECT_TRUE(s.summary.converged);
  EXPECT_GT(s.summary.initial_models, 20);
  EXPECT_LT(s.summary.graph_vertices, s.summary.proxy_vertices);
  // Labels are compacted: every model is used.
  std::set<int> used(s.labels.begin(), s.labels.end());
  EXPECT_EQ(used.size(), s.models.size());
}

TEST(Pearl, RunsStopWhenAStepGainsLessThanMinGain) {
  // With min_gain 0 the kept run goes on until its labeling is stable; with a large min_gain it
  // stops at the first step that lowers the energy by less than that fraction, and not before.
  const Sketch sketch = testing::cylinder_sketch();
  const TriMesh proxy = testing::rounded_cylinder_mesh(3, 0.5, 0.5, 0.04);
  SegmentOptions all = small_options();
  all.min_gain = 0.0;
  all.restarts = 1;
  SegmentOptions early = all;
  early.min_gain = 0.35;
  const Segmentation a = segment(sketch, proxy, all);
  const Segmentation b = segment(sketch, proxy, early);
  const auto& h = b.summary.energy_history;
  ASSERT_GE(h.size(), 2u);
  EXPECT_LT(h.size(), a.summary.energy_history.size());
  EXPECT_TRUE(b.summary.converged);
  EXPECT_LT(h[h.size() - 2] - h.back(), early.min_gain * h[h.size() - 2]);
  for (std::size_t i = 1; i + 1 < h.size(); ++i)
    EXPECT_GE(h[i - 1] - h[i], early.min_gain * h[i - 1]) << "step " << i;
  // Same steps up to the stop.
  for (std::size_t i = 0; i < h.size(); ++i) EXPECT_EQ(h[i], a.summary.energy_history[i]);
}

TEST(Pearl, SimplificationDoesNotChangeTheResult) {
  const Sketch sketch = testing::cube_sketch(1.0);
  const TriMesh proxy = cube_proxy();
  SegmentOptions fine = small_options();
  fine.simplify = false;
  const Segmentation coarse = segment(sketch, proxy, small_options()), full = segment(sketch, proxy, fine);
  EXPECT_EQ(coarse.models.size(), full.models.size());
  EXPECT_EQ(full.summary.graph_vertices, full.summary.proxy_vertices);
  // The same partition of the proxy (labels may be numbered differently).
  std::size_t disagreements = 0;
  for (auto e : proxy.edges()) {
    const auto h = proxy.halfedge_handle(e, 0);
    const int a = proxy.from_vertex_handle(h).idx(), b = proxy.to_vertex_handle(h).idx();
    disagreements += (coarse.labels[a] == coarse.labels[b]) != (full.labels[a] == full.labels[b]);
  }
  EXPECT_LT(disagreements, proxy.n_edges() / 50);
}

TEST(Scribbles, MergeJoinsTheScribbledRegions) {
  const TriMesh proxy = cube_proxy();
  Segmenter segmenter(testing::cube_sketch(1.0), proxy, small_options());
  const Segmentation before = segmenter.run();
  ASSERT_EQ(before.models.size(), 6u);
  std::vector<int> scribble = face_patch(proxy, 0, 1.0, 0.2);
  const std::vector<int> other = face_patch(proxy, 1, 1.0, 0.2);
  ASSERT_FALSE(scribble.empty());
  ASSERT_FALSE(other.empty());
  scribble.insert(scribble.end(), other.begin(), other.end());
  const Segmentation after = segmenter.merge_regions(scribble);
  std::set<int> labels;
  for (int v : scribble) labels.insert(after.labels[v]);
  ASSERT_EQ(labels.size(), 1u);
  // The shared model was fitted to both faces: it passes through both face centres.
  const ImplicitModel& merged = after.models[*labels.begin()];
  EXPECT_LT(merged.distance(V3(0.5, 0, 0)), 0.02);  // about eps (1% of the diagonal)
  EXPECT_LT(merged.distance(V3(0, 0.5, 0)), 0.02);
  EXPECT_LE(after.models.size(), before.models.size() + 1);
  EXPECT_EQ(after.summary.association_s, before.summary.association_s);  // not re-associated
}

TEST(Scribbles, InsertGivesTheScribbledVerticesOneNewRegion) {
  const TriMesh proxy = cube_proxy();
  Segmenter segmenter(testing::cube_sketch(1.0), proxy, small_options());
  EXPECT_THROW(segmenter.insert_region({0}), Error);  // no run yet
  const Segmentation before = segmenter.run();
  // Scribble over a band across the top face's cross stroke and two cube edges.
  std::vector<int> scribble;
  for (auto v : proxy.vertices()) {
    const V3 p = to_eigen(proxy.point(v));
    if (std::abs(p.x()) < 0.12 && p.z() > 0.2) scribble.push_back(v.idx());
  }
  const Segmentation after = segmenter.insert_region(scribble);
  std::map<int, int> count;
  for (int v : scribble) ++count[after.labels[v]];
  int most = 0;
  for (const auto& [l, c] : count) most = std::max(most, c);
  EXPECT_GE(most, static_cast<int>(0.9 * scribble.size()));
  EXPECT_THROW(segmenter.insert_region({}), Error);
  EXPECT_THROW(segmenter.merge_regions({-1}), Error);
  EXPECT_THROW(segmenter.insert_region({static_cast<int>(proxy.n_vertices())}), Error);
}

TEST(Pearl, RejectsSketchesWithNothingToSegment) {
  Sketch sketch = testing::cube_sketch(1.0);
  for (auto& s : sketch.strokes) s.ignored = true;
  EXPECT_THROW(segment(sketch, cube_proxy(), small_options()), Error);
  EXPECT_THROW(segment(Sketch{}, cube_proxy(), small_options()), Error);
}

}  // namespace
}  // namespace sketchsurf
