// `sketchsurf synth`: writes a readable sketch; bad input and options give exit 3 and 2 naming
// the file or the option.

#include <gtest/gtest.h>

#include <fstream>

#include "surfacing/sketch/io/mesh_io.h"
#include "surfacing/sketch/io/sketch_io.h"
#include "tests/support/cli_run.h"
#include "tests/support/shapes.h"

namespace sketchsurf {
namespace {

namespace fs = std::filesystem;

using testing::CliRun;

CliRun synth(const std::string& args, const fs::path& dir) { return testing::run_cli("synth " + args, dir); }

fs::path scratch() { return testing::scratch_dir("sketchsurf_synth_cli_"); }

TEST(SynthCli, WritesAReadableSketchInEveryStyle) {
  const fs::path dir = scratch();
  write_mesh(testing::icosphere(3, 0.5), dir / "sphere.ply");
  for (const std::string style : {"net", "vr"}) {
    const fs::path out = dir / ("sphere_" + style + ".json");
    const CliRun run = synth(testing::quoted(dir / "sphere.ply") + " -o " + testing::quoted(out) + " --style " + style + " --seed 4 --sections 2",
                             dir);
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const Sketch sketch = read_sketch(out);
    EXPECT_GE(sketch.strokes.size(), 6u) << style;
  }
  const fs::path curves = dir / "sphere.curves";
  ASSERT_EQ(synth(testing::quoted(dir / "sphere.ply") + " -o " + testing::quoted(curves), dir).exit_code, 0);
  EXPECT_FALSE(read_sketch(curves).strokes.empty());
  fs::remove_all(dir);
}

TEST(SynthCli, ErrorsNameTheFileOrOption) {
  const fs::path dir = scratch();
  std::ofstream(dir / "broken.obj") << "v 0 0 0\nf 1 2 3\n";
  CliRun run = synth(testing::quoted(dir / "broken.obj") + " -o " + testing::quoted(dir / "out.json"), dir);
  EXPECT_EQ(run.exit_code, 3) << run.err;
  EXPECT_NE(run.err.find("broken.obj"), std::string::npos) << run.err;
  EXPECT_FALSE(fs::exists(dir / "out.json"));

  run = synth(testing::quoted(dir / "missing.ply") + " -o " + testing::quoted(dir / "out.json"), dir);
  EXPECT_EQ(run.exit_code, 3) << run.err;
  EXPECT_NE(run.err.find("missing.ply"), std::string::npos) << run.err;

  write_mesh(testing::icosphere(2, 0.5), dir / "sphere.obj");
  const std::string mesh = testing::quoted(dir / "sphere.obj");
  run = synth(mesh + " -o " + testing::quoted(dir / "out.json") + " --style pencil", dir);
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(run.err.find("--style"), std::string::npos) << run.err;
  run = synth(mesh + " -o " + testing::quoted(dir / "out.json") + " --gap 2", dir);
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(run.err.find("--gap"), std::string::npos) << run.err;
  run = synth(mesh + " -o " + testing::quoted(dir / "out.png"), dir);
  EXPECT_EQ(run.exit_code, 2) << run.err;
  EXPECT_NE(run.err.find("out.png"), std::string::npos) << run.err;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace sketchsurf
