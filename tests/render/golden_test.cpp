// Golden images (tests/render/golden/*.png, 256x256, reviewed by eye): strokes, a shaded mesh,
// regions with sharp edges and the depth-aware stroke overlay.

#include "tests/render/render_support.h"

namespace sketchsurf::testing {
namespace {

using render::build_scene;

constexpr int kSize = 256;

TEST(Golden, Strokes) {
  const auto scene = build_scene(cube_sketch(1.0, true));
  expect_golden(render_picture(scene, kSize, kSize), "strokes");
}

TEST(Golden, ShadedMesh) {
  const TriMesh torus = torus_mesh(64, 32, 0.5, 0.2);
  const auto scene = build_scene(Sketch{}, &torus);
  expect_golden(render_picture(scene, kSize, kSize), "shaded_mesh");
}

TEST(Golden, RegionsWithSharpEdges) {
  const Eigen::Vector3d half(0.6, 0.4, 0.3);
  const TriMesh box = box_grid_mesh(8, half);
  MeshAttributes attributes;
  attributes.labels = box_face_labels(box, half);
  render::SceneOptions options;
  options.regions = true;
  const auto scene = build_scene(Sketch{}, &box, &attributes, options);
  EXPECT_GT(scene.outlined_edges, 0u);
  expect_golden(render_picture(scene, kSize, kSize), "regions_sharp_edges");
}

TEST(Golden, DepthAwareOverlay) {
  // Great circles on a sphere: their halves at the back are hidden by the surface and must be
  // drawn faint, the front halves normally.
  const TriMesh sphere = icosphere(4, 0.5);
  const auto scene = build_scene(sphere_sketch(0.5, 4), &sphere);
  expect_golden(render_picture(scene, kSize, kSize), "depth_overlay");
}

}  // namespace
}  // namespace sketchsurf::testing
