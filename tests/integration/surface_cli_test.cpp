// `sketchsurf surface` end to end: outputs, report.json, and what bad inputs give (exit code 3 or
// 4 with a message saying what to do).

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "surfacing/palette.h"
#include "surfacing/sketch/io/mesh_io.h"
#include "surfacing/sketch/io/sketch_io.h"
#include "tests/support/shapes.h"

namespace sketchsurf {
namespace {

namespace fs = std::filesystem;

struct CliRun {
  int code = -1;
  std::string err;
};

/// Runs `[env] sketchsurf -q ARGS` (env: shell variable assignments, e.g. "NAME=value ").
CliRun run_cli(const std::string& args, const fs::path& dir, const std::string& env = {}) {
  const fs::path err = dir / "stderr.txt";
  const int status =
      std::system((env + std::string(SKETCHSURF_CLI) + " -q " + args + " 2>" + err.string()).c_str());
  std::ifstream in(err);
  std::stringstream text;
  text << in.rdbuf();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str()};
}

fs::path temp_dir(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("sketchsurf_surface_cli_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

/// Writes DIR/cube.json and a rough proxy DIR/proxy.ply, with parameters stored in the sketch (a
/// coarse proxy resolution and two restarts) that keep a run short; returns the cube sketch.
Sketch write_quick_cube(const fs::path& dir) {
  Sketch cube = testing::cube_sketch();
  cube.params = {{"proxy.edge", 0.03}, {"segment.restarts", 2}};
  write_sketch(cube, dir / "cube.json");
  write_mesh(testing::rounded_box_mesh(3, {0.5, 0.5, 0.5}, 0.1), dir / "proxy.ply");
  return cube;
}

TEST(SurfaceCli, WritesTheMeshTheRegionsAndTheReport) {
  const fs::path dir = temp_dir("ok");
  Sketch cube = write_quick_cube(dir);
  const CliRun r = run_cli("surface " + (dir / "cube.json").string() + " --proxy " +
                            (dir / "proxy.ply").string() + " -o " + (dir / "out.ply").string() +
                            " --regions " + (dir / "regions.ply").string() + " --report " +
                            (dir / "report.json").string() + " --seed 7",
                        dir);
  ASSERT_EQ(r.code, 0) << r.err;
  MeshAttributes attributes;
  const TriMesh mesh = read_mesh(dir / "out.ply", &attributes);
  EXPECT_GT(mesh.n_faces(), 1000u);
  EXPECT_EQ(attributes.labels.size(), mesh.n_vertices());
  // Region colours, and the creases per edge: they run along the cube's edges, where two of the
  // three coordinates are at the box's sides.
  ASSERT_EQ(attributes.colors.size(), mesh.n_vertices());
  for (std::size_t v = 0; v < mesh.n_vertices(); ++v)
    ASSERT_EQ(attributes.colors[v], region_color(attributes.labels[v]));
  BoundingBox box;
  for (const auto v : mesh.vertices()) box.extend(to_eigen(mesh.point(v)));
  ASSERT_GT(attributes.sharp_edges.size(), 12u);
  std::size_t on_cube_edges = 0;
  for (const auto& [a, b] : attributes.sharp_edges) {
    const Eigen::Vector3d mid = 0.5 * (to_eigen(mesh.point(TriMesh::VertexHandle(a))) +
                                       to_eigen(mesh.point(TriMesh::VertexHandle(b))));
    int sides = 0;
    for (int c = 0; c < 3; ++c)
      sides += std::min(mid[c] - box.min[c], box.max[c] - mid[c]) < 0.03 * box.diagonal();
    on_cube_edges += sides >= 2;
  }
  EXPECT_GT(on_cube_edges, attributes.sharp_edges.size() * 9 / 10);
  std::ifstream in(dir / "report.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_EQ(report["regions"], 6);
  EXPECT_LT(report["stroke_distance"]["median"].get<double>(), 0.01);
  EXPECT_GE(report["stroke_distance"]["max"].get<double>(), report["stroke_distance"]["p95"].get<double>());
  EXPECT_GT(report["timings"]["extraction_s"].get<double>(), 0.0);
  EXPECT_GE(report["timings"]["total_s"].get<double>(), report["timings"]["extraction_s"].get<double>());
  EXPECT_TRUE(fs::exists(dir / "regions.ply"));

  // --param sets a parameter over the file's own; a bad one is a usage error before any work.
  const std::string again = "surface " + (dir / "cube.json").string() + " --proxy " +
                            (dir / "proxy.ply").string() + " --report " +
                            (dir / "param.json").string() + " -o " + (dir / "param.ply").string();
  const CliRun set = run_cli(again + " --param segment.epsilon=0.02 --param segment.restarts=1", dir);
  ASSERT_EQ(set.code, 0) << set.err;
  std::ifstream param_in(dir / "param.json");
  const nlohmann::json param_report = nlohmann::json::parse(param_in);
  EXPECT_DOUBLE_EQ(param_report["parameters"]["epsilon"].get<double>(), 0.02);
  EXPECT_EQ(param_report["restarts"], 1);
  fs::remove(dir / "param.ply");
  for (const std::string bad : {"segment.epsilonn=1", "segment.epsilon", "segment.epsilon=x",
                                "segment.epsilon=-1"}) {
    const CliRun refused = run_cli(again + " --param " + bad, dir);
    EXPECT_EQ(refused.code, 2) << bad << ": " << refused.err;
    EXPECT_NE(refused.err.find("--param"), std::string::npos) << refused.err;
    EXPECT_FALSE(fs::exists(dir / "param.ply")) << bad;
  }

  // An unknown parameter in the file is an input error naming it.
  cube.params = {{"segment.epsilonn", 0.1}};
  write_sketch(cube, dir / "typo.json");
  const CliRun typo = run_cli("surface " + (dir / "typo.json").string() + " -o " + (dir / "t.ply").string(), dir);
  EXPECT_EQ(typo.code, 3);
  EXPECT_NE(typo.err.find("segment.epsilonn"), std::string::npos) << typo.err;
}

TEST(SurfaceCli, ObjOutputHasNormalsAndAGroupPerRegion) {
  const fs::path dir = temp_dir("obj");
  write_quick_cube(dir);
  const std::string args = "surface " + (dir / "cube.json").string() + " --proxy " + (dir / "proxy.ply").string();
  // Strokes go into glTF only: asked for with another output, refused before any work.
  const CliRun refused = run_cli(args + " -o " + (dir / "out.ply").string() + " --with-strokes", dir);
  EXPECT_EQ(refused.code, 2) << refused.err;
  EXPECT_NE(refused.err.find("--with-strokes: only a .glb or .gltf output"), std::string::npos) << refused.err;
  const CliRun r = run_cli(args + " -o " + (dir / "out.obj").string() + " --seed 7", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  MeshAttributes attributes;
  const TriMesh mesh = read_mesh(dir / "out.obj", &attributes);
  EXPECT_EQ(attributes.colors.size(), mesh.n_vertices());  // region colours as `v x y z r g b`
  std::ifstream in(dir / "out.obj");
  std::size_t normals = 0, faces = 0, corners_with_normals = 0;
  std::set<std::string> groups;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("vn ", 0) == 0) ++normals;
    if (line.rfind("g ", 0) == 0) {
      EXPECT_TRUE(groups.insert(line).second) << "group twice: " << line;
    }
    if (line.rfind("f ", 0) == 0) {
      ++faces;
      for (std::size_t at = line.find("//"); at != std::string::npos; at = line.find("//", at + 2))
        ++corners_with_normals;
    }
  }
  EXPECT_EQ(faces, mesh.n_faces());
  EXPECT_EQ(corners_with_normals, 3 * faces);
  EXPECT_GT(normals, mesh.n_vertices());  // split along the creases
  EXPECT_EQ(groups.size(), 6u);           // the cube's six sides
}

std::string file_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// glibc picks its exp, log, sin, cos, atan2, acos, ... by the CPU (FMA and AVX2 variants, which
// differ in the last bit of some results); GLIBC_TUNABLES hides those features from it, as on an
// older CPU. A sketch drawn by synth in the vr style (tremor, gaps, overshoots) and surfaced with
// the automatic proxy gives the same bytes either way. On a CPU without FMA and AVX2 both runs
// take the same path and the test says nothing.
TEST(SurfaceCli, ASketchSurfacesToTheSameBitsWhicheverMathTheCpuGets) {
  const fs::path dir = temp_dir("same_bits");
  write_mesh(testing::rounded_cylinder_mesh(3, 0.4, 0.5, 0.1), dir / "truth.ply");
  const std::string older_cpu = "GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2,-FMA ";
  for (const std::string& env : {std::string(), older_cpu}) {
    const std::string tag = env.empty() ? "this" : "older";
    const CliRun drawn = run_cli("synth " + (dir / "truth.ply").string() + " --style vr --seed 3 -o " +
                                     (dir / (tag + ".json")).string(),
                                 dir, env);
    ASSERT_EQ(drawn.code, 0) << drawn.err;
    const CliRun r = run_cli("surface " + (dir / (tag + ".json")).string() + " -o " +
                                 (dir / (tag + ".ply")).string() +
                                 " --param proxy.edge=0.02 --param segment.restarts=2",
                             dir, env);
    ASSERT_EQ(r.code, 0) << r.err;
  }
  EXPECT_EQ(file_bytes(dir / "this.json"), file_bytes(dir / "older.json"));
  EXPECT_EQ(file_bytes(dir / "this.ply"), file_bytes(dir / "older.ply"));
}

TEST(SurfaceCli, ACupIsOpenedWithANoteAndKeptClosedWithClosed) {
  const fs::path dir = temp_dir("cup");
  Sketch cup = testing::cup_sketch();
  cup.params = {{"proxy.edge", 0.02}, {"segment.restarts", 2}};
  write_sketch(cup, dir / "cup.json");
  const std::string base = "surface " + (dir / "cup.json").string() + " -o " + (dir / "cup.ply").string() +
                           " --report " + (dir / "report.json").string();
  const auto report = [&] {
    std::ifstream in(dir / "report.json");
    return nlohmann::json::parse(in);
  };
  // Not quiet: the note names the rim stroke and the flag.
  const int status = std::system((std::string(SKETCHSURF_CLI) + " " + base + " 2>" + (dir / "err.txt").string()).c_str());
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  std::ifstream err(dir / "err.txt");
  const std::string text((std::istreambuf_iterator<char>(err)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("opened the surface at 1 rim(s)"), std::string::npos) << text;
  EXPECT_NE(text.find("--closed"), std::string::npos) << text;
  nlohmann::json open = report();
  ASSERT_EQ(open["openings"].size(), 1u);
  EXPECT_EQ(open["openings"][0]["id"], 1);
  EXPECT_NEAR(open["openings"][0]["normal"][2].get<double>(), 1.0, 1e-3);
  EXPECT_TRUE(open["extraction"]["open"].get<bool>());

  const CliRun closed = run_cli(base + " --closed", dir);
  ASSERT_EQ(closed.code, 0) << closed.err;
  EXPECT_TRUE(report()["openings"].empty());
  EXPECT_FALSE(report()["extraction"]["open"].get<bool>());
}

TEST(SurfaceCli, AnAntennaIsLeftOutWithANoteOrDrawnAsATubeWithTubes) {
  const fs::path dir = temp_dir("antenna");
  Sketch sketch = testing::sphere_with_antenna_sketch();
  sketch.params = {{"proxy.edge", 0.02}, {"segment.restarts", 2}};
  write_sketch(sketch, dir / "antenna.json");
  const std::string base = std::string(SKETCHSURF_CLI) + " surface " + (dir / "antenna.json").string() +
                           " -o " + (dir / "out.ply").string() + " --report " + (dir / "report.json").string();
  const auto note = [&](const std::string& flags) {
    const int status = std::system((base + flags + " 2>" + (dir / "err.txt").string()).c_str());
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
    std::ifstream err(dir / "err.txt");
    return std::string((std::istreambuf_iterator<char>(err)), std::istreambuf_iterator<char>());
  };
  const auto tubes = [&] {
    std::ifstream in(dir / "report.json");
    return nlohmann::json::parse(in)["tubes"].get<int>();
  };
  const std::string left_out = note("");
  EXPECT_NE(left_out.find("ignored 1 stroke(s)"), std::string::npos) << left_out;
  EXPECT_NE(left_out.find("--tubes"), std::string::npos) << left_out;
  EXPECT_EQ(tubes(), 0);
  const std::size_t surface_faces = read_mesh(dir / "out.ply").n_faces();

  const std::string drawn = note(" --tubes");
  EXPECT_NE(drawn.find("drawn as 1 thin tube(s)"), std::string::npos) << drawn;
  EXPECT_EQ(tubes(), 1);
  EXPECT_GT(read_mesh(dir / "out.ply").n_faces(), surface_faces);

  const CliRun both = run_cli("surface " + (dir / "antenna.json").string() + " -o " +
                                  (dir / "x.ply").string() + " --tubes --keep-all-strokes",
                              dir);
  EXPECT_EQ(both.code, 2) << both.err;
  EXPECT_FALSE(fs::exists(dir / "x.ply"));
}

TEST(SurfaceCli, AHatchingSceneExits4WithoutOutputAndForceWritesIt) {
  const fs::path dir = temp_dir("hatching");
  write_sketch(testing::hatching_sketch(10, 3), dir / "hatching.json");
  const std::string base = "surface " + (dir / "hatching.json").string() + " -o " + (dir / "out.ply").string();
  const CliRun refused = run_cli(base, dir);
  EXPECT_EQ(refused.code, 4) << refused.err;
  EXPECT_NE(refused.err.find("hatching.json"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("do not seem to depict one surface"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("--force"), std::string::npos) << refused.err;
  EXPECT_FALSE(fs::exists(dir / "out.ply"));

  const CliRun forced = run_cli(base + " --force", dir);
  EXPECT_EQ(forced.code, 0) << forced.err;
  EXPECT_GT(read_mesh(dir / "out.ply").n_faces(), 0u);
}

TEST(SurfaceCli, BadInputsGiveExitCode3Or4AndSayWhatToDo) {
  const fs::path dir = temp_dir("bad");
  const std::string out = " -o " + (dir / "out.ply").string();
  write_sketch(testing::cube_sketch(), dir / "cube.json");
  const std::string cube = (dir / "cube.json").string();

  // Every stroke ignored.
  Sketch ignored = testing::cube_sketch();
  for (Stroke& s : ignored.strokes) s.ignored = true;
  write_sketch(ignored, dir / "ignored.json");
  CliRun r = run_cli("surface " + (dir / "ignored.json").string() + out, dir);
  EXPECT_EQ(r.code, 3);
  EXPECT_NE(r.err.find("ignored"), std::string::npos) << r.err;

  // Empty sketch.
  write_sketch(Sketch{}, dir / "empty.json");
  r = run_cli("surface " + (dir / "empty.json").string() + out, dir);
  EXPECT_TRUE(r.code == 3 || r.code == 4) << r.err;
  EXPECT_NE(r.err.find("stroke"), std::string::npos) << r.err;

  // A proxy that is not a triangle mesh (points and a line).
  { std::ofstream f(dir / "lines.obj"); f << "v 0 0 0\nv 1 0 0\nl 1 2\n"; }
  r = run_cli("surface " + cube + " --proxy " + (dir / "lines.obj").string() + out, dir);
  EXPECT_EQ(r.code, 3);
  EXPECT_NE(r.err.find("lines.obj"), std::string::npos) << r.err;

  // A non-manifold proxy: three triangles on one edge.
  { std::ofstream f(dir / "fin.obj"); f << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 2 3\nf 2 1 4\nf 1 2 5\n"; }
  r = run_cli("surface " + cube + " --proxy " + (dir / "fin.obj").string() + out, dir);
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("fin.obj"), std::string::npos) << r.err;

  // A proxy far from the strokes.
  write_mesh(testing::icosphere(2, 0.5, {100, 0, 0}), dir / "far.ply");
  r = run_cli("surface " + cube + " --proxy " + (dir / "far.ply").string() + out, dir);
  EXPECT_TRUE(r.code == 3 || r.code == 4) << r.err;
  EXPECT_NE(r.err.find("far"), std::string::npos) << r.err;

  // Usage errors: a bad mirror plane, an unknown boundary stroke.
  EXPECT_EQ(run_cli("surface " + cube + " --mirror 1,2" + out, dir).code, 2);
  EXPECT_EQ(run_cli("surface " + cube + " --boundary-strokes 999" + out, dir).code, 2);
  EXPECT_FALSE(fs::exists(dir / "out.ply"));
}

}  // namespace
}  // namespace sketchsurf
