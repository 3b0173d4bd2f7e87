// Every render path under the Khronos validation layer: no warning, no error, nothing leaked
// (the layer reports undestroyed objects when the device is destroyed).

#include "tests/render/render_support.h"

namespace sketchsurf::testing {
namespace {

TEST(Validation, NoMessagesWhileRenderingEverything) {
  std::vector<std::string> lines;
  {
    vk::ContextOptions options;
    options.validation = vk::Validation::On;
    options.log = [&lines](const std::string& line) { lines.push_back(line); };
    const vk::Context context(options);
    ASSERT_TRUE(context.validation_enabled())
        << "the validation layer is not installed (Debian package vulkan-validationlayers)";

    const Eigen::Vector3d half(0.6, 0.4, 0.3);
    const TriMesh box = box_grid_mesh(4, half);
    MeshAttributes attributes;
    attributes.labels = box_face_labels(box, half);
    render::SceneOptions scene_options;
    scene_options.regions = true;
    scene_options.wireframe = true;
    const auto full = render::build_scene(cube_sketch(), &box, &attributes, scene_options);
    const auto strokes_only = render::build_scene(torus_sketch());
    const auto empty = render::build_scene(Sketch{});

    render::HeadlessRenderer renderer(context, 64, 48);
    for (const auto* scene : {&full, &strokes_only, &empty}) {
      renderer.set_scene(*scene);
      for (int turn = 0; turn < 2; ++turn)
        renderer.render(render::orbit(render::fit_camera(scene->bounds, render::View::Iso, 64.0 / 48),
                                      turn * 1.0));
    }
    render::HeadlessRenderer odd_size(context, 17, 5);  // row pitch != width * 4 on some drivers
    odd_size.set_scene(full);
    odd_size.render(render::fit_camera(full.bounds, render::View::Top, 17.0 / 5));
  }
  std::vector<std::string> messages;
  for (const auto& l : lines)
    if (l.rfind("validation", 0) == 0) messages.push_back(l);
  EXPECT_TRUE(messages.empty()) << messages.size() << " validation messages, first: "
                                << (messages.empty() ? "" : messages.front());
}

}  // namespace
}  // namespace sketchsurf::testing
