// `sketchsurf eval`: the measures of two spheres a known distance apart, the coloured deviation
// mesh, the JSON; a missing truth, a wrong output extension and an output that is an input are
// refused with the file or option named.

#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "surfacing/sketch/io/mesh_io.h"
#include "surfacing/sketch/io/sketch_io.h"
#include "tests/support/cli_run.h"
#include "tests/support/shapes.h"

namespace sketchsurf {
namespace {

namespace fs = std::filesystem;

fs::path scratch() { return testing::scratch_dir("sketchsurf_eval_cli_"); }

std::string q(const fs::path& p) { return testing::quoted(p); }

TEST(EvalCli, SpheresTwoPercentApart) {
  const fs::path dir = scratch();
  write_mesh(testing::icosphere(4, 0.5), dir / "truth.ply");
  write_mesh(testing::icosphere(4, 0.52), dir / "result.ply");
  write_sketch(testing::sphere_sketch(0.5, 4), dir / "sketch.json");
  const auto run = testing::run_cli("eval " + q(dir / "result.ply") + " --truth " + q(dir / "truth.ply") +
                                        " --sketch " + q(dir / "sketch.json") + " --json " + q(dir / "r.json") +
                                        " --deviation " + q(dir / "d.ply"),
                                    dir);
  ASSERT_EQ(run.exit_code, 0) << run.err;
  std::ifstream in(dir / "r.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  const double diagonal = j["diagonal"];
  EXPECT_NEAR(diagonal, std::sqrt(3.0), 0.01);  // the icosphere's box is almost the unit cube
  EXPECT_NEAR(double(j["accuracy"]["median"]) * diagonal, 0.02, 0.003);
  EXPECT_NEAR(double(j["completeness"]["median"]) * diagonal, 0.02, 0.003);
  EXPECT_EQ(j["creases"]["sharp_edges"], 0);
  EXPECT_EQ(j["checks"]["genus"], 0);
  MeshAttributes attributes;
  const TriMesh colored = read_mesh(dir / "d.ply", &attributes);
  EXPECT_EQ(colored.n_vertices(), testing::icosphere(4, 0.52).n_vertices());
  EXPECT_EQ(attributes.colors.size(), colored.n_vertices());
}

TEST(EvalCli, BadFilesAndOptionsAreNamed) {
  const fs::path dir = scratch();
  write_mesh(testing::icosphere(2, 0.5), dir / "result.ply");
  auto run = testing::run_cli("eval " + q(dir / "result.ply") + " --truth " + q(dir / "missing.ply"), dir);
  EXPECT_EQ(run.exit_code, 3);
  EXPECT_NE(run.err.find("missing.ply"), std::string::npos) << run.err;
  run = testing::run_cli("eval " + q(dir / "result.ply") + " --truth " + q(dir / "result.ply") +
                             " --deviation " + q(dir / "d.xyz"),
                         dir);
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(run.err.find("--deviation"), std::string::npos) << run.err;
  run = testing::run_cli("eval " + q(dir / "result.ply") + " --truth " + q(dir / "result.ply") +
                             " --deviation " + q(dir / "result.ply"),
                         dir);
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_TRUE(fs::exists(dir / "result.ply"));
  EXPECT_GT(read_mesh(dir / "result.ply").n_faces(), 0u);  // the input is untouched
}

}  // namespace
}  // namespace sketchsurf
