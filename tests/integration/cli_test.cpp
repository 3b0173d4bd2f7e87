// The sketchsurf executable: `info`, `convert`, exit codes, --help and --version.

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <nlohmann/json.hpp>
#include <sstream>

#include "surfacing/sketch/io/mesh_io.h"
#include "surfacing/sketch/io/sketch_io.h"
#include "tests/support/shapes.h"
#include "tests/unit/sketch/io_test_support.h"

namespace sketchsurf {
namespace {

using testing::TempDir;

struct CliResult {
  int code = -1;
  std::string out, err;
};

/// Runs the CLI with `args` (each single-quoted for the shell), capturing both streams.
CliResult run_cli(const TempDir& dir, const std::vector<std::string>& args) {
  std::string command = std::string("'") + SKETCHSURF_CLI + "'";
  for (const auto& a : args) command += " '" + a + "'";
  command += " > '" + (dir / "stdout.txt").string() + "' 2> '" + (dir / "stderr.txt").string() + "'";
  const int status = std::system(command.c_str());
  CliResult r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = testing::read_text(dir / "stdout.txt");
  r.err = testing::read_text(dir / "stderr.txt");
  std::filesystem::remove(dir / "stdout.txt");
  std::filesystem::remove(dir / "stderr.txt");
  return r;
}

Sketch example() {
  Sketch sketch = testing::cylinder_sketch(0.3, 0.8, 5);
  testing::transform(sketch, 1.0, Eigen::Vector3d(0.1, 1.2, -0.4));
  testing::add_noise(sketch, 1e-4, 9);
  return sketch;
}

const std::vector<std::string> kFormats = {".json", ".curves", ".obj", ".tilt"};

TEST(Cli, InfoJsonMatchesTheLibraryForEveryFormat) {
  TempDir dir;
  for (const auto& ext : kFormats) {
    SCOPED_TRACE(ext);
    const auto file = dir / ("s" + ext);
    write_sketch(example(), file);
    const Sketch sketch = read_sketch(file);
    const CliResult r = run_cli(dir, {"info", file.string(), "--json"});
    ASSERT_EQ(r.code, 0) << r.err;
    const auto j = nlohmann::json::parse(r.out);  // one JSON object, nothing else on stdout
    ASSERT_TRUE(j.is_object());
    EXPECT_EQ(j["strokes"].get<std::size_t>(), sketch.strokes.size());
    EXPECT_EQ(j["points"].get<std::size_t>(), sketch.point_count());
    const BoundingBox box = sketch.bounding_box();
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(j["bbox_min"][c].get<double>(), box.min[c], 1e-12);
      EXPECT_NEAR(j["bbox_max"][c].get<double>(), box.max[c], 1e-12);
    }
    EXPECT_NEAR(j["diagonal"].get<double>(), box.diagonal(), 1e-12);
  }
}

TEST(Cli, InfoInPlainTextNamesTheCounts) {
  TempDir dir;
  write_sketch(example(), dir / "s.json");
  const CliResult r = run_cli(dir, {"info", (dir / "s.json").string()});
  ASSERT_EQ(r.code, 0) << r.err;
  const Sketch sketch = read_sketch(dir / "s.json");
  EXPECT_NE(r.out.find("strokes       " + std::to_string(sketch.strokes.size())), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("points        " + std::to_string(sketch.point_count())), std::string::npos);
}

TEST(Cli, ConvertBetweenEveryPairOfFormats) {
  TempDir dir;
  const Sketch sketch = example();
  for (const auto& from : kFormats) {
    const auto in = dir / ("in" + from);
    write_sketch(sketch, in);
    const Sketch source = read_sketch(in);
    for (const auto& to : writable_sketch_extensions()) {
      SCOPED_TRACE(from + " -> " + to);
      const auto out = dir / ("out" + to);
      const CliResult r = run_cli(dir, {"convert", in.string(), out.string()});
      ASSERT_EQ(r.code, 0) << r.err;
      // .tilt keeps float32 positions; every other pair is exact.
      testing::expect_same_points(source, read_sketch(out), to == ".tilt" ? 1e-6 : 0.0);
      std::filesystem::remove(out);
    }
  }
}

TEST(Cli, UsageErrorsExitWith2) {
  TempDir dir;
  write_sketch(example(), dir / "s.json");
  const std::string in = (dir / "s.json").string();
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"info", in, "--no-such-option"},
           {"--no-such-option"},
           {},
           {"no-such-command"},
           {"info"},
           {"convert", in, (dir / "out.xyz").string()},
           {"convert", (dir / "missing.json").string(), (dir / "out.xyz").string()},
           {"convert", in, in},
           {"proxy", in, "-o", (dir / "p.ply").string(), "--param", "segment.epsilon=0.1"},
           {"proxy", in, "-o", (dir / "p.ply").string(), "--param", "proxy.lambda"},
           {"proxy", in, "-o", (dir / "p.ply").string(), "--param", "proxy.confine_radius=2"}}) {
    std::string joined;
    for (const auto& a : args) joined += a + " ";
    SCOPED_TRACE(joined);
    const CliResult r = run_cli(dir, args);
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_FALSE(r.err.empty());
  }
  EXPECT_NE(run_cli(dir, {"convert", in, (dir / "out.xyz").string()}).err.find("out.xyz"),
            std::string::npos);
  EXPECT_FALSE(std::filesystem::exists(dir / "out.xyz"));
  EXPECT_FALSE(std::filesystem::exists(dir / "p.ply"));
}

TEST(Cli, ProxyParamsReachTheProxy) {
  TempDir dir;
  write_sketch(example(), dir / "s.json");
  const CliResult r = run_cli(dir, {"-q", "proxy", (dir / "s.json").string(), "-o",
                                    (dir / "p.ply").string(), "--report", (dir / "r.json").string(),
                                    "--param", "proxy.lambda=0.002", "--param", "proxy.edge=0.03"});
  ASSERT_EQ(r.code, 0) << r.err;
  const auto report = nlohmann::json::parse(testing::read_text(dir / "r.json"));
  EXPECT_DOUBLE_EQ(report["vipss"]["lambda"].get<double>(), 0.002);
  EXPECT_DOUBLE_EQ(report["parameters"]["edge"].get<double>(), 0.03);
}

TEST(Cli, ProxyLeavesOutAStrokeThatDepictsNoSurfaceAsSurfaceDoes) {
  // A sphere of radius 0.5 with an antenna from (0.5, 0, 0) to (1, 0, 0) and a tap on its top:
  // the proxy command prepares the strokes as `surface` does, so the antenna is ignored, not
  // wrapped in a horn, and the tap too.
  TempDir dir;
  Sketch sketch = testing::sphere_sketch(0.5, 4);
  sketch.strokes.push_back(testing::sample_curve(
      [](double t) { return Eigen::Vector3d(0.5 + 0.5 * t, 0.0, 0.0); }, 0.0, 1.0, 0.005));
  sketch.strokes.push_back(testing::sample_curve(
      [](double t) { return Eigen::Vector3d(0.004 * t, 0.5, 0.003 * t); }, 0.0, 1.0, 0.002));
  write_sketch(sketch, dir / "s.json");
  const auto reach = [&] {  // the proxy's largest x
    double x = -1.0;
    const TriMesh proxy = read_mesh(dir / "p.ply");
    for (const auto v : proxy.vertices()) x = std::max(x, static_cast<double>(proxy.point(v)[0]));
    return x;
  };
  CliResult r = run_cli(dir, {"proxy", (dir / "s.json").string(), "-o", (dir / "p.ply").string(),
                              "--report", (dir / "r.json").string()});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_LT(reach(), 0.55);
  EXPECT_GT(reach(), 0.45);
  EXPECT_NE(r.err.find("note: ignored 2 stroke(s) that depict no surface"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("(hangs by one end)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("(a dot)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--keep-all-strokes keeps them"), std::string::npos) << r.err;
  const auto report = nlohmann::json::parse(testing::read_text(dir / "r.json"));
  ASSERT_EQ(report["decorations"].size(), 2u);
  EXPECT_EQ(report["decorations"][0]["kind"], "dangling");
  EXPECT_EQ(report["decorations"][1]["kind"], "dot");
  // Kept, the antenna is fitted: the surface reaches out along it.
  r = run_cli(dir, {"-q", "proxy", (dir / "s.json").string(), "-o", (dir / "p.ply").string(),
                    "--keep-all-strokes"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_GT(reach(), 0.9);
}

TEST(Cli, ProxyAndSurfaceSayWhenTheProxyIsLoftedThroughSections) {
  // A dress: a four-lobed hem at z = 0, a waist circle at z = 2, two profile lines. VIPSS's
  // surface lies 69% far from every stroke; with outline_most 0.5 that counts as framing no
  // surface, and the proxy is lofted through the two sections.
  TempDir dir;
  Sketch sketch;
  const auto section = [](double z, double r, double lobes) {
    return testing::sample_curve(
        [=](double a) {
          const double radius = r * (1.0 + lobes * std::cos(4.0 * a));
          return Eigen::Vector3d(radius * std::cos(a), radius * std::sin(a), z);
        },
        0.0, 2.0 * M_PI, 0.01);
  };
  sketch.strokes.push_back(section(0.0, 1.0, 0.3));
  sketch.strokes.push_back(section(2.0, 0.5, 0.0));
  for (const double side : {-1.0, 1.0})
    sketch.strokes.push_back(testing::sample_curve(
        [=](double t) { return Eigen::Vector3d(side * (1.3 - 0.8 * t), 0.0, 2.0 * t); }, 0.0, 1.0, 0.01));
  write_sketch(sketch, dir / "s.json");
  const CliResult r = run_cli(dir, {"proxy", (dir / "s.json").string(), "-o", (dir / "p.ply").string(),
                                    "--report", (dir / "r.json").string(), "--param",
                                    "proxy.outline_most=0.5"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("lofted through 2 section strokes"), std::string::npos) << r.err;
  const auto report = nlohmann::json::parse(testing::read_text(dir / "r.json"));
  EXPECT_EQ(report["vipss"]["loft_sections"], 2);
  // Between the sections, within the hem's lobes.
  const TriMesh proxy = read_mesh(dir / "p.ply");
  for (const auto v : proxy.vertices()) {
    const Eigen::Vector3d p = to_eigen(proxy.point(v));
    ASSERT_GT(p.z(), -0.01);
    ASSERT_LT(p.z(), 2.01);
    ASSERT_LT(std::hypot(p.x(), p.y()), 1.31);
  }
  // Without it, VIPSS's surface is kept.
  const CliResult plain = run_cli(dir, {"proxy", (dir / "s.json").string(), "-o", (dir / "p.ply").string()});
  ASSERT_EQ(plain.code, 0) << plain.err;
  EXPECT_EQ(plain.err.find("lofted"), std::string::npos) << plain.err;
  // `surface` says so too, and how to keep VIPSS's surface.
  const CliResult surfaced = run_cli(dir, {"surface", (dir / "s.json").string(), "-o",
                                           (dir / "s.ply").string(), "--param", "proxy.outline_most=0.5"});
  ASSERT_EQ(surfaced.code, 0) << surfaced.err;
  EXPECT_NE(surfaced.err.find("lofted through 2 section strokes (--param proxy.loft_fit=0"),
            std::string::npos)
      << surfaced.err;
}

TEST(Cli, MissingOrInvalidFilesExitWith3NamingTheFile) {
  TempDir dir;
  testing::write_text(dir / "broken.json", R"({"format": "sketchsurf-sketch", "version": 1, "strokes": [)");
  testing::write_text(dir / "broken.curves", "v 3\n0 0 0\n");
  testing::write_text(dir / "broken.tilt", "not a tilt file");
  for (const std::string name : {"missing.json", "broken.json", "broken.curves", "broken.tilt"}) {
    SCOPED_TRACE(name);
    for (const std::string command : {"info", "convert"}) {
      std::vector<std::string> args = {command, (dir / name).string()};
      if (command == "convert") args.push_back((dir / "out.json").string());
      const CliResult r = run_cli(dir, args);
      EXPECT_EQ(r.code, 3) << r.err;
      EXPECT_NE(r.err.find(name), std::string::npos) << r.err;
      EXPECT_TRUE(r.out.empty()) << r.out;
    }
  }
  EXPECT_FALSE(std::filesystem::exists(dir / "out.json"));
}

TEST(Cli, HelpOnEveryCommandAndVersion) {
  TempDir dir;
  const CliResult help = run_cli(dir, {"--help"});
  ASSERT_EQ(help.code, 0);
  // The subcommands listed by the top-level help, each with its own --help.
  std::istringstream lines(help.out);
  std::string line;
  std::vector<std::string> commands;
  bool in_list = false;
  while (std::getline(lines, line)) {
    if (line.starts_with("Subcommands:")) {
      in_list = true;
      continue;
    }
    if (in_list && !line.empty() && line[0] == ' ') {
      std::istringstream words(line);
      std::string name;
      words >> name;
      commands.push_back(name);
    } else if (in_list && !line.empty()) {
      in_list = false;
    }
  }
  EXPECT_NE(std::find(commands.begin(), commands.end(), "info"), commands.end()) << help.out;
  EXPECT_NE(std::find(commands.begin(), commands.end(), "convert"), commands.end()) << help.out;
  for (const auto& c : commands) {
    const CliResult r = run_cli(dir, {c, "--help"});
    EXPECT_EQ(r.code, 0) << c << ": " << r.err;
    EXPECT_NE(r.out.find(c), std::string::npos) << r.out;
  }
  const CliResult version = run_cli(dir, {"--version"});
  EXPECT_EQ(version.code, 0);
  EXPECT_TRUE(version.out.starts_with("sketchsurf ")) << version.out;
}

}  // namespace
}  // namespace sketchsurf
