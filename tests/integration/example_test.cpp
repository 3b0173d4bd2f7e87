// The bundled example of the README's first command (tests/data/cube.json with the rough
// tests/data/cube_proxy.obj): what the README promises of it, stage by stage.

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "surfacing/proxy/proxy.h"
#include "surfacing/segment/pearl.h"
#include "surfacing/sketch/io/mesh_io.h"
#include "surfacing/sketch/io/sketch_io.h"

namespace sketchsurf {
namespace {

const std::string kData = std::string(SKETCHSURF_TESTS_DIR) + "/data/";

// Every PEARL restart finds the cube's six faces as six planes. With Eq. 6's per-vertex normal
// alignment the rough proxy's tilted normals pulled each plane fit off its coplanar stroke points
// (a 5 degree tilt, E_fidelity 0.16 instead of ~0), quartics won the faces, and the restarts ended
// anywhere between 0.013 and 0.22 with 6 to 10 regions depending on the seed.
TEST(BundledCube, EveryRestartFindsTheSixFacesAsPlanes) {
  const Sketch sketch = read_sketch(kData + "cube.json");
  const TriMesh proxy = attract_proxy(read_mesh(kData + "cube_proxy.obj"), sketch, ProxyOptions{});
  for (std::uint64_t seed : {123u, 1u}) {
    SegmentOptions options;
    options.seed = seed;
    const Segmentation s = segment(sketch, proxy, options);
    ASSERT_EQ(s.models.size(), 6u) << "seed " << seed;
    for (const ImplicitModel& m : s.models) EXPECT_EQ(m.degree, 1) << "seed " << seed;
    const auto& e = s.summary.restart_energies;
    ASSERT_EQ(e.size(), 10u);
    const auto [lo, hi] = std::minmax_element(e.begin(), e.end());
    EXPECT_LT(*hi, 1.05 * *lo) << "seed " << seed << ": restarts end at different energies";
  }
}

}  // namespace
}  // namespace sketchsurf
