// The bundled examples in tests/data are the output of their generators (tests/support/examples.h);
// regenerate them with `build/tests/make_examples tests/data` when a generator changes.
#include <gtest/gtest.h>

#include "surfacing/sketch/io/json.h"
#include "surfacing/sketch/io/mesh_io.h"
#include "tests/support/examples.h"

namespace sketchsurf::testing {
namespace {

TEST(BundledExamples, MatchTheirGenerators) {
  for (const auto& [name, expected] : bundled_examples()) {
    SCOPED_TRACE(name);
    const auto file = std::filesystem::path(SKETCHSURF_TESTS_DIR) / "data" / (name + ".json");
    const Sketch actual = read_json(file);
    ASSERT_EQ(actual.strokes.size(), expected.strokes.size());
    for (std::size_t i = 0; i < actual.strokes.size(); ++i) {
      const Stroke &a = actual.strokes[i], &b = expected.strokes[i];
      ASSERT_EQ(a.points.size(), b.points.size());
      // Within 1e-12, not bit for bit: a build for another CPU (SKETCHSURF_NATIVE) fuses
      // multiply-adds in the generators and moves the last bit of some coordinates.
      for (std::size_t k = 0; k < a.points.size(); ++k)
        EXPECT_LT((a.points[k] - b.points[k]).norm(), 1e-12) << "point " << k << " of stroke " << i;
      EXPECT_EQ(a.boundary, b.boundary);
      EXPECT_EQ(a.ignored, b.ignored);
    }
    EXPECT_EQ(actual.mirror.has_value(), expected.mirror.has_value());
  }
}

TEST(BundledExamples, ProxiesMatchTheirGenerators) {
  for (const auto& [name, expected] : bundled_example_proxies()) {
    SCOPED_TRACE(name);
    const TriMesh actual = read_mesh(std::filesystem::path(SKETCHSURF_TESTS_DIR) / "data" / (name + ".obj"));
    ASSERT_EQ(actual.n_vertices(), expected.n_vertices());
    ASSERT_EQ(actual.n_faces(), expected.n_faces());
    for (auto v : expected.vertices())
      EXPECT_LT((actual.point(actual.vertex_handle(v.idx())) - expected.point(v)).norm(), 1e-12);
  }
}

}  // namespace
}  // namespace sketchsurf::testing
