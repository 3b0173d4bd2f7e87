// A user's files are never lost: outputs checked before any work and never an input, written
// together or not at all, Ctrl-C cancelling cleanly with no temporary file left; inputs that are
// not sketches refused with a message naming the file; option values out of range said in words.

#include <gtest/gtest.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <random>
#include <thread>

#include "surfacing/sketch/io/mesh_io.h"
#include "surfacing/sketch/io/sketch_io.h"
#include "tests/support/shapes.h"
#include "tests/unit/sketch/io_test_support.h"

namespace sketchsurf {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

struct CliResult {
  int code = -1;
  std::string err;
};

/// Starts the CLI with `args`, stderr to `err_file`, stdout to /dev/null; returns its pid.
pid_t start_cli(const std::vector<std::string>& args, const fs::path& err_file) {
  const pid_t pid = fork();
  if (pid == 0) {
    const int null = open("/dev/null", O_WRONLY);
    const int err = open(err_file.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    dup2(null, STDOUT_FILENO);
    dup2(err, STDERR_FILENO);
    std::vector<char*> argv{const_cast<char*>(SKETCHSURF_CLI)};
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(SKETCHSURF_CLI, argv.data());
    _exit(127);
  }
  return pid;
}

int exit_status(pid_t pid) {
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

/// Runs the CLI to its end. The stderr file lives outside `dir`, whose listing the tests check.
CliResult run_cli(const std::vector<std::string>& args) {
  const fs::path err = fs::temp_directory_path() / ("sketchsurf-safety-err-" + std::to_string(getpid()));
  CliResult r;
  r.code = exit_status(start_cli(args, err));
  r.err = testing::read_text(err);
  fs::remove(err);
  return r;
}

std::string joined(const std::vector<std::string>& args) {
  std::string s;
  for (const auto& a : args) s += a + " ";
  return s;
}

/// The cube with a coarse proxy resolution and two restarts: surfaced in about a second.
void write_quick_cube(const fs::path& file) {
  Sketch cube = testing::cube_sketch();
  cube.params = {{"proxy.edge", 0.03}, {"segment.restarts", 2}};
  write_sketch(cube, file);
}

TEST(FileSafety, AnOutputThatIsAnInputIsRefusedHoweverItIsNamed) {
  TempDir dir;
  write_quick_cube(dir / "c.obj");
  write_mesh(testing::rounded_box_mesh(3, {0.5, 0.5, 0.5}, 0.1), dir / "p.ply");
  fs::create_directory(dir / "sub");
  fs::create_symlink(dir / "c.obj", dir / "link.obj");
  const std::string sketch = (dir / "c.obj").string(), proxy = (dir / "p.ply").string();
  const std::string before = testing::read_text(dir / "c.obj"), proxy_before = testing::read_text(dir / "p.ply");
  const std::string dotted = (dir / "sub" / ".." / "c.obj").string();
  for (const auto& args : std::vector<std::vector<std::string>>{
           {"surface", sketch, "-o", sketch},
           {"surface", sketch, "-o", dotted},
           {"surface", sketch, "-o", (dir / "m.ply").string(), "--report", (dir / "link.obj").string()},
           {"surface", sketch, "--proxy", proxy, "-o", (dir / "m.ply").string(), "--regions", proxy},
           {"surface", sketch, "-o", (dir / "m.ply").string(), "--regions", (dir / "m.ply").string()},
           {"convert", sketch, dotted},
           {"convert", sketch, (dir / "link.obj").string()},
           {"proxy", sketch, "-o", proxy, "--from", proxy},
           {"segment", sketch, "--proxy", proxy, "-o", proxy},
           {"segment", sketch, "--proxy", proxy, "-o", (dir / "r.ply").string(), "--report", sketch}}) {
    SCOPED_TRACE(joined(args));
    const CliResult r = run_cli(args);
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_TRUE(r.err.find("is the input") != std::string::npos ||
                r.err.find("is also the output") != std::string::npos)
        << r.err;
  }
  EXPECT_EQ(testing::read_text(dir / "c.obj"), before);
  EXPECT_EQ(testing::read_text(dir / "p.ply"), proxy_before);
  EXPECT_FALSE(fs::exists(dir / "m.ply"));
}

TEST(FileSafety, OutputsAreCheckedBeforeAnyInputIsRead) {
  TempDir dir;
  // The sketch does not exist: a check made after reading would exit 3.
  const std::string missing = (dir / "missing.json").string();
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"surface", missing, "-o", (dir / "x.xyz").string()}, "give a file name ending in .obj, .ply"},
      {{"surface", missing, "-o", "/nonexistent/x.ply"}, "the directory /nonexistent does not exist; create it"},
      {{"surface", missing, "-o", (dir / "m.ply").string(), "--report", "/nonexistent/r.json"},
       "--report /nonexistent/r.json"},
      {{"surface", missing, "-o", dir.path().string()}, "is a directory"},
      {{"proxy", missing, "-o", (dir / "p.stl").string()}, "unknown extension '.stl'"},
      {{"segment", missing, "--proxy", missing, "-o", (dir / "nodir" / "s.ply").string()}, "does not exist"},
      {{"convert", missing, (dir / "c.xyz").string()}, ".json, .tilt, .obj, .curves"},
      {{"render", missing, "-o", (dir / "r.jpg").string()}, ".png"}};
  for (const auto& [args, expected] : cases) {
    SCOPED_TRACE(joined(args));
    const CliResult r = run_cli(args);
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
  }
  if (geteuid() != 0) {  // root may write anywhere
    fs::create_directory(dir / "ro");
    fs::permissions(dir / "ro", fs::perms::owner_read | fs::perms::owner_exec);
    const CliResult r = run_cli({"surface", missing, "-o", (dir / "ro" / "m.ply").string()});
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_NE(r.err.find("cannot write into the directory"), std::string::npos) << r.err;
    fs::permissions(dir / "ro", fs::perms::owner_all);
  }
}

TEST(FileSafety, AFailedRunChangesNoOutput) {
  TempDir dir;
  write_quick_cube(dir / "cube.json");
  testing::write_text(dir / "m.ply", "the user's old mesh");
  testing::write_text(dir / "r.json", "the user's old report");
  // The report cannot be written: refused before the work, m.ply untouched.
  CliResult r = run_cli({"surface", (dir / "cube.json").string(), "-o", (dir / "m.ply").string(),
                         "--report", "/nonexistent/r.json"});
  EXPECT_EQ(r.code, 2) << r.err;
  // The sketch has no usable stroke: the run fails (exit 3, naming the file), nothing changes.
  Sketch dots;
  dots.strokes.resize(2);
  dots.strokes[0].points = {Eigen::Vector3d(0, 0, 0)};
  dots.strokes[1].points = {Eigen::Vector3d(1, 0, 0)};
  write_sketch(dots, dir / "dots.json");
  r = run_cli({"surface", (dir / "dots.json").string(), "-o", (dir / "m.ply").string(), "--report",
               (dir / "r.json").string()});
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("dots.json: the sketch has no stroke"), std::string::npos) << r.err;
  EXPECT_EQ(testing::read_text(dir / "m.ply"), "the user's old mesh");
  EXPECT_EQ(testing::read_text(dir / "r.json"), "the user's old report");
  EXPECT_EQ(dir.files(), (std::vector<std::string>{"cube.json", "dots.json", "m.ply", "r.json"}));
}

TEST(FileSafety, CtrlCDuringWritesLeavesNoTemporaryFileAndNoPartialOutput) {
  TempDir dir;
  // A 40k-point sketch: reading and writing take a few hundred milliseconds.
  Sketch big = testing::sphere_sketch(0.5, 400);
  testing::add_noise(big, 1e-4, 3);
  write_sketch(big, dir / "big.json");
  const std::string expected_out = [&] {
    write_sketch(read_sketch(dir / "big.json"), dir / "reference.curves");
    return testing::read_text(dir / "reference.curves");
  }();
  fs::remove(dir / "reference.curves");
  const auto start = std::chrono::steady_clock::now();
  const pid_t probe = start_cli({"convert", (dir / "big.json").string(), (dir / "probe.curves").string()},
                                "/dev/null");
  ASSERT_EQ(exit_status(probe), 0);
  const auto full = std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() - start);
  fs::remove(dir / "probe.curves");

  std::mt19937 rng(7);
  int cancelled = 0, finished = 0;
  for (int trial = 0; trial < 16; ++trial) {
    const std::string out = (dir / "out.curves").string();
    fs::remove(out);
    const pid_t pid = start_cli({"convert", (dir / "big.json").string(), out}, "/dev/null");
    std::this_thread::sleep_for(full * std::uniform_real_distribution<double>(0.2, 1.1)(rng));
    kill(pid, SIGINT);
    const int code = exit_status(pid);
    SCOPED_TRACE("trial " + std::to_string(trial) + ", exit " + std::to_string(code));
    ASSERT_TRUE(code == 0 || code == 130);
    (code == 0 ? finished : cancelled) += 1;
    if (fs::exists(out)) EXPECT_EQ(testing::read_text(out), expected_out);  // never partial
    else EXPECT_EQ(code, 130);
    for (const auto& name : dir.files()) EXPECT_EQ(name.find(".tmp-"), std::string::npos) << name;
  }
  EXPECT_GT(cancelled, 0);
  std::cerr << "SIGINT trials: " << cancelled << " cancelled, " << finished << " finished\n";
}

TEST(FileSafety, CtrlCDuringSurfacingExitsWith130AndWritesNothing) {
  TempDir dir;
  write_sketch(testing::cube_sketch(), dir / "cube.json");  // the automatic proxy: several seconds
  const fs::path err = dir.path().parent_path() / ("sketchsurf-safety-sigint-" + std::to_string(getpid()));
  const pid_t pid = start_cli({"surface", (dir / "cube.json").string(), "-o", (dir / "m.ply").string(),
                               "--report", (dir / "r.json").string()},
                              err);
  std::this_thread::sleep_for(std::chrono::milliseconds(800));
  kill(pid, SIGINT);
  EXPECT_EQ(exit_status(pid), 130);
  EXPECT_NE(testing::read_text(err).find("cancelled"), std::string::npos) << testing::read_text(err);
  fs::remove(err);
  EXPECT_EQ(dir.files(), std::vector<std::string>{"cube.json"});
}

TEST(FileSafety, OptionValuesOutOfRangeAreSaidInWords) {
  TempDir dir;
  write_quick_cube(dir / "c.json");
  const std::string in = (dir / "c.json").string(), out = (dir / "m.ply").string();
  for (const auto& [args, expected] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"surface", in, "-o", out, "--seed", "-1"}, "--seed: expected a whole number from 0 to"},
           {{"surface", in, "-o", out, "--threads", "100000"}, "expected a whole number from 0 to 1024"},
           {{"segment", in, "--proxy", in, "-o", out, "--restarts", "0"}, "from 1 to 1000, got '0'"},
           {{"segment", in, "--proxy", in, "-o", out, "--epsilon", "-1"}, "--epsilon: expected a number > 0"},
           {{"segment", in, "--proxy", in, "-o", out, "--seed", "1e3"}, "whole number"},
           {{"proxy", in, "-o", out, "--edge", "0"}, "--edge: expected a number > 0, got '0'"},
           {{"proxy", in, "-o", out, "--lambda", "-1"}, "--lambda: expected a number >= 0"},
           {{"proxy", in, "-o", out, "--lambda", "nan"}, "expected a number >= 0"},
           {{"proxy", in, "-o", out, "--points", "5"}, "from 10 to 20000"},
           {{"render", in, "-o", (dir / "r.png").string(), "--size", "16384x16384", "--msaa", "4"},
            "of image memory"}}) {
    SCOPED_TRACE(joined(args));
    const CliResult r = run_cli(args);
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("1797693"), std::string::npos) << r.err;
    EXPECT_LT(r.err.size(), 400u) << r.err;
  }
  EXPECT_EQ(dir.files(), std::vector<std::string>{"c.json"});
}

TEST(FileSafety, InputsThatAreNotSketchesExit3NamingTheFile) {
  TempDir dir;
  testing::write_text(dir / "e.curves", "");
  testing::write_text(dir / "e.obj", "\n\n");
  ASSERT_EQ(mkfifo((dir / "f.json").c_str(), 0600), 0);
  testing::write_text(dir / "nul.obj", std::string(100000, '\0') + "\n" + std::string(100000, '\0'));
  testing::write_text(dir / "huge.curves", "v 3\n0 0 0\n1e308 0 0\n1 1 1\n");
  testing::write_text(dir / "big.curves", "v 1\n" + std::string(3 << 20, ' ') + "0 0 0\n");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"e.curves", "e.curves: the file is empty"},
      {"e.obj", "e.obj: the file is empty"},
      {"f.json", "f.json: is not a regular file"},
      {"nul.obj", "nul.obj: warning: ignored records of unknown kind '\\x00"},
      {"huge.curves", "huge.curves: stroke 0 point 1"}};
  for (const auto& [name, expected] : cases) {
    SCOPED_TRACE(name);
    const CliResult r = run_cli({"surface", (dir / name).string(), "-o", (dir / "m.ply").string()});
    EXPECT_EQ(r.code, 3) << r.err.substr(0, 300);
    EXPECT_NE(r.err.find(expected), std::string::npos) << r.err.substr(0, 300);
    EXPECT_EQ(r.err.find('\0'), std::string::npos);
    EXPECT_LT(r.err.size(), 1000u);
  }
  const std::string big = (dir / "big.curves").string();
  setenv("SKETCHSURF_MAX_INPUT_MB", "2", 1);
  CliResult r = run_cli({"info", big});
  unsetenv("SKETCHSURF_MAX_INPUT_MB");
  EXPECT_EQ(r.code, 3) << r.err;
  EXPECT_NE(r.err.find("big.curves: 3145738 bytes is over the input limit of 2 MiB"), std::string::npos) << r.err;
  EXPECT_EQ(run_cli({"info", big}).code, 0);  // under the default limit
  EXPECT_FALSE(fs::exists(dir / "m.ply"));
}

TEST(FileSafety, ProxyMeshesThatCannotBeOneExit3NamingTheFile) {
  TempDir dir;
  write_quick_cube(dir / "c.json");
  const TriMesh sphere = testing::icosphere(2, 0.7);
  TriMesh big = sphere, far_vertex = sphere, flat = sphere;
  for (const auto v : big.vertices()) big.set_point(v, big.point(v) * 1e6);  // millimetres?
  far_vertex.set_point(TriMesh::VertexHandle(0), OpenMesh::Vec3d(1e300, 0, 0));
  for (const auto v : flat.vertices()) flat.set_point(v, OpenMesh::Vec3d(flat.point(v)[0], 0, 0));
  write_mesh(big, dir / "big.obj");
  write_mesh(far_vertex, dir / "far.ply");
  write_mesh(flat, dir / "flat.obj");
  const std::string sketch = (dir / "c.json").string(), out = (dir / "m.ply").string();
  for (const auto& [args, expected] : std::vector<std::pair<std::vector<std::string>, std::string>>{
           {{"surface", sketch, "--proxy", (dir / "big.obj").string(), "-o", out},
            "big.obj: the mesh is 1.4e+06 times larger than the strokes"},
           {{"surface", sketch, "--proxy", (dir / "far.ply").string(), "-o", out},
            "far.ply: the mesh has vertex 0 at (1e+300, 0, 0)"},
           {{"segment", sketch, "--proxy", (dir / "flat.obj").string(), "-o", out},
            "flat.obj: the mesh has no area"},
           {{"proxy", sketch, "--from", (dir / "big.obj").string(), "-o", out}, "big.obj: the mesh is"}}) {
    SCOPED_TRACE(joined(args));
    const auto start = std::chrono::steady_clock::now();
    const CliResult r = run_cli(args);
    EXPECT_EQ(r.code, 3) << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << r.err;
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(20));  // refused, not worked on
  }
  EXPECT_FALSE(fs::exists(dir / "m.ply"));
}

}  // namespace
}  // namespace sketchsurf
