// Every real sketch in ../shared/data renders without error (label data): strokes are drawn,
// nothing is cut by the frame.

#include <filesystem>

#include "surfacing/sketch/io/sketch_io.h"
#include "tests/render/render_support.h"

namespace sketchsurf::testing {
namespace {

TEST(RenderData, EveryRealSketchRenders) {
  const std::filesystem::path root(SKETCHSURF_DATA_DIR);
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
    const auto ext = entry.path().extension();
    if (ext == ".tilt" || ext == ".curves" || ext == ".obj") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  ASSERT_GE(files.size(), 15u) << "expected the tilt, cassie and vns sketches under " << root;
  render::HeadlessRenderer renderer(render_context(), 96, 96);
  for (const auto& file : files) {
    SCOPED_TRACE(file.string());
    const Sketch sketch = read_sketch(file);
    const auto scene = render::build_scene(sketch);
    ASSERT_GT(scene.stroke_points, 0u);
    renderer.set_scene(scene);
    const auto image = renderer.render(render::fit_camera(scene.bounds, render::View::Iso, 1.0));
    EXPECT_GT(non_background_pixels(image, render::kBackground), 50u);
    for (int i = 0; i < 96; ++i)
      for (const auto& [x, y] : {std::pair{i, 0}, {i, 95}, {0, i}, {95, i}})
        ASSERT_EQ(image.at(x, y), (std::array<std::uint8_t, 4>{255, 255, 255, 255}))
            << "stroke cut by the frame at " << x << "," << y;
  }
}

}  // namespace
}  // namespace sketchsurf::testing
