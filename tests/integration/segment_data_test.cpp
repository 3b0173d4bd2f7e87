// Segmentation of every real CASSIE (.curves) and VNS (.obj) sketch in SKETCHSURF_DATA_DIR on a
// proxy built here: an icosphere shrink-wrapped radially onto the strokes. Checks that PEARL
// finishes, that the energy never increases over its iterations, and that the result is usable.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>

#include "surfacing/segment/pearl.h"
#include "surfacing/sketch/io/sketch_io.h"
#include "tests/support/shapes.h"

namespace sketchsurf {
namespace {

namespace fs = std::filesystem;
using V3 = Eigen::Vector3d;

// A star-shaped proxy around the sketch: every icosphere direction d gets the radius of the
// farthest stroke point within 25 degrees of d (projected on d), radii then smoothed over the
// sphere's graph. Crude for concave sketches, enough to give PEARL a manifold domain.
TriMesh envelope_proxy(const Sketch& sketch, int subdivisions) {
  const BoundingBox box = sketch.bounding_box();
  const V3 c = 0.5 * (box.min + box.max);
  TriMesh mesh = testing::icosphere(subdivisions, 1.0);
  const double cos_cone = std::cos(25.0 * M_PI / 180);
  std::vector<double> radius(mesh.n_vertices(), 0.0);
  for (auto v : mesh.vertices()) {
    const V3 d = to_eigen(mesh.point(v)).normalized();
    for (const auto& s : sketch.strokes)
      for (const auto& p : s.points) {
        const V3 q = p - c;
        const double n = q.norm();
        if (n > 0 && q.dot(d) >= cos_cone * n) radius[v.idx()] = std::max(radius[v.idx()], q.dot(d));
      }
  }
  const double fallback = 0.1 * box.diagonal();
  for (double& r : radius) r = std::max(r, fallback);
  for (int it = 0; it < 10; ++it) {
    std::vector<double> next(radius.size());
    for (auto v : mesh.vertices()) {
      double sum = radius[v.idx()];
      int n = 1;
      for (auto w : mesh.vv_range(v)) sum += radius[w.idx()], ++n;
      next[v.idx()] = sum / n;
    }
    radius = next;
  }
  for (auto v : mesh.vertices())
    mesh.set_point(v, to_openmesh(c + radius[v.idx()] * to_eigen(mesh.point(v)).normalized()));
  return mesh;
}

std::vector<std::string> data_sketches() {
  std::vector<std::string> files;
  for (const auto& [dir, ext] : {std::pair{"cassie", ".curves"}, std::pair{"vns", ".obj"}}) {
    const fs::path folder = fs::path(SKETCHSURF_DATA_DIR) / dir;
    if (!fs::is_directory(folder)) continue;
    for (const auto& entry : fs::directory_iterator(folder))
      if (entry.path().extension() == ext) files.push_back(entry.path().string());
  }
  std::sort(files.begin(), files.end());
  return files;
}

class SegmentData : public ::testing::TestWithParam<std::string> {};

TEST_P(SegmentData, FinishesWithMonotoneEnergy) {
  Sketch sketch = read_sketch(GetParam());
  clean(sketch);
  ASSERT_FALSE(sketch.strokes.empty());
  resample(sketch, 0.005 * sketch.bounding_box().diagonal());  // METHOD.md §0
  const TriMesh proxy = envelope_proxy(sketch, 4);
  SegmentOptions options;
  options.restarts = 2;  // the paper's 10 are the benchmark's business
  const Segmentation s = segment(sketch, proxy, options);

  const auto& h = s.summary.energy_history;
  ASSERT_FALSE(h.empty());
  for (std::size_t i = 1; i < h.size(); ++i) EXPECT_LE(h[i], h[i - 1] * (1 + 1e-12)) << "iteration " << i;
  EXPECT_TRUE(s.summary.converged || s.summary.iterations == options.max_iterations);
  ASSERT_EQ(s.labels.size(), proxy.n_vertices());
  EXPECT_EQ(std::set<int>(s.labels.begin(), s.labels.end()).size(), s.models.size());
  const SegmentEnergy& E = s.summary.energy;
  EXPECT_TRUE(std::isfinite(E.total));
  EXPECT_NEAR(E.total,
              E.fidelity + options.w_smooth * E.smoothness + options.w_simp * E.simplicity, 1e-9);
  for (const auto& m : s.models) {
    EXPECT_TRUE(m.coefficients.allFinite());
    EXPECT_GE(m.degree, 1);
    EXPECT_LE(m.degree, 4);
  }
  // The strokes are explained: the mean fidelity per point is within a few eps.
  EXPECT_LT(E.fidelity, 25.0);
  RecordProperty("regions", static_cast<int>(s.models.size()));
  std::cout << fs::path(GetParam()).filename().string() << ": " << s.models.size() << " regions, E "
            << E.total << " (fid " << E.fidelity << "), " << s.summary.iterations << " iterations, "
            << s.summary.association_s + s.summary.init_s + s.summary.segmentation_s << " s\n";
}

INSTANTIATE_TEST_SUITE_P(Real, SegmentData, ::testing::ValuesIn(data_sketches()),
                         [](const ::testing::TestParamInfo<std::string>& test) {
                           std::string name = fs::path(test.param).parent_path().filename().string() +
                                              "_" + fs::path(test.param).stem().string();
                           for (char& ch : name)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return name;
                         });

}  // namespace
}  // namespace sketchsurf
