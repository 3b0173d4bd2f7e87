// `sketchsurf render` end to end: pictures written, turntable frames named, usage errors and the
// missing-driver path (exit code 4 naming the Debian package).

#include <sys/wait.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "surfacing/sketch/io/mesh_io.h"
#include "surfacing/sketch/io/sketch_io.h"
#include "tests/render/render_support.h"

namespace sketchsurf::testing {
namespace {

namespace fs = std::filesystem;

struct CliRun {
  int code = -1;
  std::string output;  // stdout and stderr
};

CliRun run(const std::string& args, const std::string& env = "") {
  const std::string command = env + " '" SKETCHSURF_CLI "' " + args + " 2>&1";
  CliRun result;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe) return result;
  char buffer[4096];
  while (std::fgets(buffer, sizeof buffer, pipe)) result.output += buffer;
  const int status = pclose(pipe);
  result.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

class RenderCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("sketchsurf_render_cli_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
    sketch_ = (dir_ / "cube.json").string();
    write_sketch(cube_sketch(), sketch_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  fs::path dir_;
  std::string sketch_;
};

TEST_F(RenderCli, WritesAPictureOfTheRequestedSize) {
  const CliRun r = run("render " + sketch_ + " -o " + path("cube.png") + " --size 64x40 --view front");
  ASSERT_EQ(r.code, 0) << r.output;
  const auto image = render::read_png(path("cube.png"));
  EXPECT_EQ(image.width, 64);
  EXPECT_EQ(image.height, 40);
  EXPECT_GT(non_background_pixels(image, render::kBackground), 50u);
}

TEST_F(RenderCli, MeshWithRegionsAndBackground) {
  const Eigen::Vector3d half(0.5, 0.5, 0.5);
  const TriMesh box = box_grid_mesh(3, half);
  MeshAttributes attributes;
  attributes.labels = box_face_labels(box, half);
  write_mesh(box, path("box.ply"), attributes);
  const CliRun r = run("render " + sketch_ + " --mesh " + path("box.ply") +
                    " --regions --no-strokes --background '#000000' -o " + path("box.png") +
                    " --size 48x48");
  ASSERT_EQ(r.code, 0) << r.output;
  const auto image = render::read_png(path("box.png"));
  EXPECT_EQ(image.at(0, 0), (std::array<std::uint8_t, 4>{0, 0, 0, 255}));
  // Region colours show: the centre of the picture is one of the palette's (lit) colours,
  // clearly not black and not the default surface colour.
  EXPECT_GT(non_background_pixels(image, render::Rgb8{0, 0, 0}), 48u * 48u / 4);
}

TEST_F(RenderCli, TurntableFramesAreNumbered) {
  const CliRun r =
      run("render " + sketch_ + " -o " + path("turn.png") + " --size 32x32 --turntable 3 --msaa 1");
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* name : {"turn_000.png", "turn_001.png", "turn_002.png"})
    EXPECT_TRUE(fs::exists(path(name))) << name;
  EXPECT_FALSE(fs::exists(path("turn.png")));
  // The cube turned by 120 degrees looks different from the first frame.
  EXPECT_NE(render::read_png(path("turn_000.png")).pixels, render::read_png(path("turn_001.png")).pixels);
}

TEST_F(RenderCli, UsageErrorsExitWithCode2) {
  for (const std::string args :
       {" --size 0x10", " --size big", " --view diagonal", " --camera 1,2,3", " --background pink",
        " --regions", " --msaa 3", " --view front --camera 0,0,5,0,0,0", " --device no-such-device-xyz"}) {
    const CliRun r = run("render " + sketch_ + " -o " + path("x.png") + args);
    EXPECT_EQ(r.code, 2) << args << ": " << r.output;
  }
  const CliRun r = run("render " + sketch_ + " -o " + path("x.jpg"));
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_EQ(run("render " + path("missing.json") + " -o " + path("x.png")).code, 3);
}

TEST_F(RenderCli, MissingVulkanDriverExitsWithCode4AndNamesThePackage) {
  const CliRun r = run("render " + sketch_ + " -o " + path("none.png"),
                    "VK_ICD_FILENAMES=/nonexistent/icd.json VK_DRIVER_FILES=/nonexistent/icd.json");
  EXPECT_EQ(r.code, 4) << r.output;
  EXPECT_NE(r.output.find("mesa-vulkan-drivers"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(path("none.png")));
}

}  // namespace
}  // namespace sketchsurf::testing
