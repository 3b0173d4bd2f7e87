// `sketchsurf info` on broken .tilt files: exit code 3 and a message on stderr naming the file,
// never a crash (a crash gives a signal, not exit code 3).

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "surfacing/sketch/io/tilt.h"
#include "tests/unit/sketch/tilt_builder.h"

namespace sketchsurf {
namespace {

namespace fs = std::filesystem;
using namespace sketchsurf::testing;

struct Run {
  int exit_code = -1;
  std::string err;
};

Run info(const fs::path& file, const fs::path& dir) {
  const fs::path err = dir / "stderr.txt";
  const std::string command = std::string("'") + SKETCHSURF_CLI + "' info '" + file.string() +
                              "' > /dev/null 2> '" + err.string() + "'";
  const int status = std::system(command.c_str());
  Run run;
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(err);
  std::stringstream text;
  text << in.rdbuf();
  run.err = text.str();
  return run;
}

void write(const fs::path& file, const ByteVec& bytes) {
  std::ofstream(file, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

void expect_invalid_input(const fs::path& file, const fs::path& dir) {
  const Run run = info(file, dir);
  EXPECT_EQ(run.exit_code, 3) << file << ": " << run.err;
  EXPECT_NE(run.err.find(file.filename().string()), std::string::npos) << run.err;
}

TEST(TiltCli, BrokenFilesExitWithCode3) {
  const fs::path dir = scratch_dir();
  Sketch sketch;
  Stroke stroke;
  stroke.points = {{0, 1, 0}, {0.1, 1, 0}, {0.2, 1.1, 0}};
  sketch.strokes = {stroke, stroke};
  write_tilt(sketch, dir / "good.tilt");
  EXPECT_EQ(info(dir / "good.tilt", dir).exit_code, 0);

  const ByteVec good = read_bytes(dir / "good.tilt");
  for (std::size_t length : {std::size_t{0}, std::size_t{10}, std::size_t{17}, good.size() / 2, good.size() - 1}) {
    const fs::path cut = dir / ("cut" + std::to_string(length) + ".tilt");
    write(cut, ByteVec(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(length)));
    expect_invalid_input(cut, dir);
  }
  ByteVec magic = good;
  magic[1] = 'X';
  write(dir / "magic.tilt", magic);
  expect_invalid_input(dir / "magic.tilt", dir);

  ByteVec sketch_bytes = data_sketch({});
  for (int i = 0; i < 4; ++i) sketch_bytes[16 + i] = i == 3 ? 0x7F : 0xFF;  // 2^31 - 1 strokes
  write(dir / "absurd.tilt", simple_tilt(sketch_bytes, R"({"BrushIndex":[]})"));
  expect_invalid_input(dir / "absurd.tilt", dir);

  write(dir / "huge_entry.tilt",
        tilt_file(zip_archive({{"data.sketch", data_sketch({}), true, 100'000'000'000ull},
                               {"metadata.json", bytes_of("{}"), false, {}}})));
  expect_invalid_input(dir / "huge_entry.tilt", dir);
  expect_invalid_input(dir / "missing.tilt", dir);
}

}  // namespace
}  // namespace sketchsurf
