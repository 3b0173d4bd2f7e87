// `sketchsurf batch`: every sketch of a folder surfaced side by side, a corrupt one reported
// without stopping the others, exit 0 only when all succeed, outputs that would collide refused.

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "surfacing/sketch/io/mesh_io.h"
#include "surfacing/sketch/io/sketch_io.h"
#include "tests/support/cli_run.h"
#include "tests/support/shapes.h"

namespace sketchsurf {
namespace {

namespace fs = std::filesystem;
using testing::quoted;

// A sketch that surfaces in about a second: a coarse proxy and two restarts, stored with it.
void write_quick(Sketch sketch, const fs::path& file) {
  sketch.params = {{"proxy.edge", 0.03}, {"proxy.points", 150}, {"segment.restarts", 2}};
  fs::create_directories(file.parent_path());
  write_sketch(sketch, file);
}

nlohmann::json read_json(const fs::path& file) {
  std::ifstream in(file);
  return nlohmann::json::parse(in);
}

// The summary row of the sketch whose output is `output`.
nlohmann::json row(const nlohmann::json& summary, const std::string& output) {
  for (const auto& r : summary)
    if (r["output"] == output) return r;
  ADD_FAILURE() << "no summary row for " << output;
  return {};
}

TEST(BatchCli, SurfacesEverySketchAndReportsTheCorruptOne) {
  const fs::path dir = testing::scratch_dir("sketchsurf_batch_");
  write_quick(testing::cube_sketch(), dir / "in" / "cube.json");
  write_quick(testing::cylinder_sketch(), dir / "in" / "parts" / "cylinder.json");
  std::ofstream(dir / "in" / "broken.json") << R"({"format": "sketchsurf-sketch", "version": 1, "strokes": [)";
  std::ofstream(dir / "in" / "notes.txt") << "not a sketch\n";

  const testing::CliRun r = testing::run_cli(
      "batch " + quoted(dir / "in") + " -o " + quoted(dir / "out") + " --jobs 2", dir);
  EXPECT_EQ(r.exit_code, 4) << r.err;  // one failed
  EXPECT_NE(r.err.find("1 of 3 sketches failed (broken)"), std::string::npos) << r.err;

  const nlohmann::json summary = read_json(dir / "out" / "summary.json");
  ASSERT_EQ(summary.size(), 3u);  // the three sketches, not notes.txt
  const nlohmann::json broken = row(summary, "broken.ply");
  EXPECT_EQ(broken["status"], "failed");
  EXPECT_EQ(broken["exit_code"], 3);  // invalid input
  EXPECT_NE(broken["error"].get<std::string>().find("broken.json"), std::string::npos) << broken;

  // The others surfaced as `surface` would: the cube's six faces, the cylinder's side and caps.
  const nlohmann::json cube = row(summary, "cube.ply");
  EXPECT_EQ(cube["status"], "ok");
  EXPECT_EQ(cube["result"]["regions"], 6);
  const nlohmann::json cylinder = row(summary, "parts/cylinder.ply");
  EXPECT_EQ(cylinder["status"], "ok");
  EXPECT_GE(cylinder["result"]["regions"].get<int>(), 3);
  for (const char* name : {"cube", "parts/cylinder"}) {
    MeshAttributes attributes;
    const TriMesh mesh = read_mesh(dir / "out" / (std::string(name) + ".ply"), &attributes);
    EXPECT_GT(mesh.n_faces(), 500u) << name;
    EXPECT_EQ(attributes.labels.size(), mesh.n_vertices()) << name;
    EXPECT_LT(read_json(dir / "out" / (std::string(name) + ".json"))["stroke_distance"]["median"].get<double>(), 0.005)
        << name;
  }
  EXPECT_TRUE(fs::exists(dir / "out" / "broken.log"));
  EXPECT_FALSE(fs::exists(dir / "out" / "broken.ply"));

  // Files named one by one, all good: exit 0.
  const testing::CliRun good = testing::run_cli(
      "batch " + quoted(dir / "in" / "cube.json") + " -o " + quoted(dir / "again") + " --format obj", dir);
  EXPECT_EQ(good.exit_code, 0) << good.err;
  EXPECT_GT(read_mesh(dir / "again" / "cube.obj").n_faces(), 500u);
}

// `batch` run on `sketch` alone (written as in/NAME.json) with `options`: its report.
nlohmann::json batch_report(const Sketch& sketch, const std::string& name, const std::string& options) {
  const fs::path dir = testing::scratch_dir("sketchsurf_batch_");
  write_quick(sketch, dir / "in" / (name + ".json"));
  const testing::CliRun r =
      testing::run_cli("batch " + quoted(dir / "in") + " -o " + quoted(dir / "out") + " " + options, dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return r.exit_code == 0 ? read_json(dir / "out" / (name + ".json")) : nlohmann::json{};
}

TEST(BatchCli, TubesReachEverySketch) {
  EXPECT_EQ(batch_report(testing::sphere_with_antenna_sketch(), "antenna", "--tubes")["tubes"], 1);
}

TEST(BatchCli, ParametersReachEveryRunAndAWrongNameStopsBeforeAny) {
  // The sketch file says 2 restarts; --param wins.
  EXPECT_EQ(batch_report(testing::cube_sketch(), "cube", "--param segment.restarts=1")["restarts"], 1);

  const fs::path dir = testing::scratch_dir("sketchsurf_batch_");
  write_quick(testing::cube_sketch(), dir / "in" / "cube.json");
  const testing::CliRun wrong = testing::run_cli(
      "batch " + quoted(dir / "in") + " -o " + quoted(dir / "wrong") + " --param segment.restart=1", dir);
  EXPECT_EQ(wrong.exit_code, 2) << wrong.err;
  EXPECT_NE(wrong.err.find("segment.restart"), std::string::npos) << wrong.err;
  EXPECT_FALSE(fs::exists(dir / "wrong"));
}

TEST(BatchCli, RefusesTwoSketchesThatWouldWriteTheSameOutput) {
  const fs::path dir = testing::scratch_dir("sketchsurf_batch_");
  write_quick(testing::cube_sketch(), dir / "a" / "shape.json");
  write_quick(testing::cube_sketch(0.5), dir / "b" / "shape.json");
  const testing::CliRun r = testing::run_cli("batch " + quoted(dir / "a" / "shape.json") + " " +
                                                 quoted(dir / "b" / "shape.json") + " -o " + quoted(dir / "out"),
                                             dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("give their folders instead"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "out"));

  const testing::CliRun missing =
      testing::run_cli("batch " + quoted(dir / "nothing_here") + " -o " + quoted(dir / "out"), dir);
  EXPECT_EQ(missing.exit_code, 2) << missing.err;
}

}  // namespace
}  // namespace sketchsurf
