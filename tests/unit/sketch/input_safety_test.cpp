// What the readers do with inputs that are not sketches: files over the size and line limits,
// pipes and devices, empty files, NaN and huge coordinates, broken lines full of NUL bytes; and
// what clean() does with NaN attributes. Every refusal is an Error (Input) naming the file.

#include <sys/stat.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <limits>

#include "surfacing/error.h"
#include "surfacing/sketch/io/input_limits.h"
#include "surfacing/sketch/io/mesh_io.h"
#include "surfacing/sketch/io/sketch_io.h"
#include "tests/unit/sketch/io_test_support.h"
#include "tests/unit/sketch/tilt_builder.h"

namespace sketchsurf {
namespace {

using testing::TempDir;

/// Sets an environment variable for the scope of a test.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) { setenv(name, value, 1); }
  ~ScopedEnv() { unsetenv(name_); }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
};

/// The message of the Error (Input) that reading `file` as a sketch throws.
std::string input_error(const std::filesystem::path& file) {
  try {
    read_sketch(file);
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input) << e.what();
    return e.what();
  }
  ADD_FAILURE() << file << " was read";
  return {};
}

std::string curves_text(std::size_t points) {
  std::string text = "v " + std::to_string(points) + "\n";
  for (std::size_t i = 0; i < points; ++i) text += std::to_string(i) + ".125 0.5 -0.25\n";
  return text;
}

TEST(InputLimits, DefaultsAndEnvironment) {
  EXPECT_EQ(InputLimits::from_environment().file_bytes, 256ull << 20);
  EXPECT_EQ(InputLimits::from_environment().line_bytes, 4ull << 20);
  {
    const ScopedEnv mb("SKETCHSURF_MAX_INPUT_MB", "2048");
    const ScopedEnv kb("SKETCHSURF_MAX_LINE_KB", "1");
    EXPECT_EQ(InputLimits::from_environment().file_bytes, 2048ull << 20);
    EXPECT_EQ(InputLimits::from_environment().line_bytes, 1024u);
  }
  const ScopedEnv bad("SKETCHSURF_MAX_INPUT_MB", "-5");  // ignored: the default stays
  EXPECT_EQ(InputLimits::from_environment().file_bytes, 256ull << 20);
  EXPECT_EQ(InputLimits::from_environment().points, 10'000'000u);
  const ScopedEnv points("SKETCHSURF_MAX_POINTS", "25000000");
  EXPECT_EQ(InputLimits::from_environment().points, 25'000'000u);
}

TEST(InputLimits, SketchesOverThePointLimitAreRefusedInEveryFormat) {
  TempDir dir;
  Sketch sketch;
  for (int s = 0; s < 3; ++s) {
    Stroke stroke;
    for (int i = 0; i < 40; ++i) stroke.points.emplace_back(0.01 * i, 0.1 * s, 0.5);
    sketch.strokes.push_back(stroke);
  }
  for (const std::string ext : {".json", ".tilt", ".obj", ".curves"})
    write_sketch(sketch, dir / ("s" + ext));
  for (const std::string ext : {".json", ".tilt", ".obj", ".curves"}) {
    const auto file = dir / ("s" + ext);
    {
      const ScopedEnv points("SKETCHSURF_MAX_POINTS", "120");  // exactly the sketch's points
      EXPECT_EQ(read_sketch(file).point_count(), 120u) << ext;
    }
    const ScopedEnv points("SKETCHSURF_MAX_POINTS", "119");
    const std::string what = input_error(file);
    EXPECT_NE(what.find(file.string()), std::string::npos) << what;
    EXPECT_NE(what.find("more than 119 points"), std::string::npos) << what;
    EXPECT_NE(what.find("SKETCHSURF_MAX_POINTS=<count>"), std::string::npos) << what;
  }
}

TEST(InputLimits, PointsAreCountedBeforeTheirMemoryIsTaken) {
  TempDir dir;
  // OBJ `l` records that name one vertex again and again: 2.4 MB of text would be 400k points.
  std::string obj = "v 0 0 0\nv 1 0 0\n";
  for (int r = 0; r < 2; ++r) {
    obj += "l";
    for (int i = 0; i < 200000; ++i) obj += i % 2 ? " 2" : " 1";
    obj += "\n";
  }
  testing::write_text(dir / "repeat.obj", obj);
  EXPECT_EQ(read_sketch(dir / "repeat.obj").point_count(), 400000u);
  {
    const ScopedEnv points("SKETCHSURF_MAX_POINTS", "300000");
    EXPECT_NE(input_error(dir / "repeat.obj").find("more than 300000 points"), std::string::npos);
  }
  // A .curves header is refused as soon as it is read, not after its points.
  testing::write_text(dir / "declared.curves", "v 2\n0 0 0\n1 0 0\nv 3\n0 0 1\n1 1 1\n2 2 2\n");
  const ScopedEnv points("SKETCHSURF_MAX_POINTS", "4");
  EXPECT_NE(input_error(dir / "declared.curves").find("more than 4 points"), std::string::npos);
  // A JSON per-point attribute may not outgrow the limit either (checked against the points
  // only at the stroke's end).
  testing::write_text(dir / "pressures.json",
                      R"({"format": "sketchsurf-sketch", "version": 1, "strokes": [)"
                      R"({"points": [[0, 0, 0]], "pressures": [1, 1, 1, 1, 1, 1]}]})");
  const std::string what = input_error(dir / "pressures.json");
  EXPECT_NE(what.find("strokes[0].pressures[4]: more entries than the limit of 4 points"),
            std::string::npos)
      << what;
}

TEST(InputLimits, FilesOverTheSizeLimitAreRefusedSayingHowToRaiseIt) {
  TempDir dir;
  testing::write_text(dir / "big.curves", curves_text(80000));  // about 1.5 MB
  testing::write_text(dir / "big.json", std::string(1100000, ' ') + "{}");
  testing::write_text(dir / "big.ply", "ply\n" + std::string(1100000, ' '));
  const ScopedEnv mb("SKETCHSURF_MAX_INPUT_MB", "1");
  for (const std::string name : {"big.curves", "big.json"}) {
    const std::string what = input_error(dir / name);
    EXPECT_NE(what.find(name), std::string::npos) << what;
    EXPECT_NE(what.find("over the input limit of 1 MiB"), std::string::npos) << what;
    EXPECT_NE(what.find("SKETCHSURF_MAX_INPUT_MB"), std::string::npos) << what;
  }
  testing::expect_error([&] { read_mesh(dir / "big.ply"); }, ErrorKind::Input,
                        {"big.ply", "SKETCHSURF_MAX_INPUT_MB"});
}

TEST(InputLimits, TiltEntriesInflatingOverTheLimitAreRefused) {
  // A valid 1.04 MB data.sketch that Deflate packs into about 1 KB.
  testing::RawStroke stroke;
  stroke.points.assign(30000, testing::RawPoint{});
  const auto sketch = testing::data_sketch({stroke});
  const auto tilt = testing::tilt_file(testing::zip_archive(
      {{"data.sketch", sketch, true, {}}, {"metadata.json", testing::bytes_of("{}"), false, {}}}));
  TempDir dir;
  testing::write_text(dir / "bomb.tilt", std::string(tilt.begin(), tilt.end()));
  EXPECT_EQ(read_sketch(dir / "bomb.tilt").point_count(), 30000u);
  const ScopedEnv mb("SKETCHSURF_MAX_INPUT_MB", "1");
  const std::string what = input_error(dir / "bomb.tilt");
  EXPECT_NE(what.find("inflates to"), std::string::npos) << what;
  EXPECT_NE(what.find("SKETCHSURF_MAX_INPUT_MB"), std::string::npos) << what;
}

TEST(InputLimits, OverlongLinesAreRefusedWithAShortMessageWithoutRawBytes) {
  TempDir dir;
  // 5 MB of NUL bytes: one line over the default limit of 4 MiB.
  testing::write_text(dir / "nul.obj", std::string(5 << 20, '\0'));
  testing::write_text(dir / "nul.curves", std::string(5 << 20, '\0'));
  for (const std::string name : {"nul.obj", "nul.curves"}) {
    const std::string what = input_error(dir / name);
    EXPECT_NE(what.find(name + ":1:"), std::string::npos) << what;
    EXPECT_NE(what.find("SKETCHSURF_MAX_LINE_KB"), std::string::npos) << what;
    EXPECT_LT(what.size(), 400u);
  }
  testing::expect_error([&] { read_mesh(dir / "nul.obj"); }, ErrorKind::Input,
                        {"nul.obj:1:", "SKETCHSURF_MAX_LINE_KB"});
  // Under the limit, a broken line is quoted cut to 80 characters, NUL bytes escaped.
  testing::write_text(dir / "bad.curves", "v 1\n" + std::string(10000, '\0') + "\n");
  testing::write_text(dir / "bad.obj", "v 1 2 " + std::string(10000, 'x') + "\n");
  for (const std::string name : {"bad.curves", "bad.obj"}) {
    const std::string what = input_error(dir / name);
    EXPECT_EQ(what.find('\0'), std::string::npos);
    EXPECT_LT(what.size(), 300u) << what;
    EXPECT_NE(what.find("(10000 bytes)"), std::string::npos) << what;
  }
  EXPECT_NE(input_error(dir / "bad.curves").find("\\x00\\x00"), std::string::npos);
  const ScopedEnv kb("SKETCHSURF_MAX_LINE_KB", "1");
  testing::write_text(dir / "long.curves", "v 1\n" + std::string(2000, '1') + " 0 0\n");
  EXPECT_NE(input_error(dir / "long.curves").find("long.curves:2: the line is 2004 bytes long"),
            std::string::npos);
}

TEST(InputSafety, PipesAndDevicesAreRefused) {
  TempDir dir;
  ASSERT_EQ(mkfifo((dir / "fifo.json").c_str(), 0600), 0);
  std::filesystem::create_symlink("/dev/zero", dir / "zero.curves");
  std::filesystem::create_symlink("/dev/zero", dir / "zero.tilt");
  for (const std::string name : {"fifo.json", "zero.curves", "zero.tilt"}) {
    const std::string what = input_error(dir / name);
    EXPECT_NE(what.find(name + ": is not a regular file"), std::string::npos) << what;
  }
  std::filesystem::create_symlink("/dev/zero", dir / "zero.ply");
  testing::expect_error([&] { read_mesh(dir / "zero.ply"); }, ErrorKind::Input,
                        {"zero.ply", "not a regular file"});
}

TEST(InputSafety, EmptyFilesSaySo) {
  TempDir dir;
  for (const std::string name : {"e.curves", "e.obj", "e.json", "blank.curves", "blank.obj"}) {
    testing::write_text(dir / name, name.starts_with("blank") ? " \n\r\n\t\n" : "");
    EXPECT_EQ(input_error(dir / name), (dir / name).string() + ": the file is empty");
  }
}

TEST(InputSafety, NonFiniteTiltPointsAreRefusedNamingStrokeAndPoint) {
  testing::RawStroke stroke;
  stroke.points.assign(4, testing::RawPoint{});
  for (std::size_t i = 0; i < 4; ++i) stroke.points[i].x = static_cast<float>(i);
  testing::RawStroke bad = stroke;
  bad.points[2].y = std::numeric_limits<float>::quiet_NaN();
  const auto tilt = testing::simple_tilt(testing::data_sketch({stroke, bad}), "{}");
  TempDir dir;
  testing::write_text(dir / "nan.tilt", std::string(tilt.begin(), tilt.end()));
  const std::string what = input_error(dir / "nan.tilt");
  EXPECT_NE(what.find("nan.tilt: stroke 1 point 2"), std::string::npos) << what;
  EXPECT_NE(what.find("not finite"), std::string::npos) << what;
}

TEST(InputSafety, CoordinatesTooLargeToSurfaceAreRefusedNamingStrokeAndPoint) {
  TempDir dir;
  testing::write_text(dir / "huge.curves", "v 3\n0 0 0\n1e308 0 0\n1 1 1\n");
  const Sketch sketch = read_sketch(dir / "huge.curves");  // a reader keeps any finite value
  testing::expect_error([&] { check_extent(sketch, dir / "huge.curves"); }, ErrorKind::Input,
                        {"huge.curves: stroke 0 point 1", "beyond"});
  Sketch fine = sketch;
  fine.strokes[0].points[1].x() = 1e9;
  EXPECT_NO_THROW(check_extent(fine, dir / "huge.curves"));
}

TEST(InputSafety, CleanResetsNonFiniteColourWidthAndPressure) {
  Sketch sketch;
  Stroke s;
  s.points = {Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0)};
  s.pressures = {0.5f, std::numeric_limits<float>::infinity()};
  s.color = {0.2f, std::numeric_limits<float>::quiet_NaN(), 0.1f, 1.f};
  s.width = std::numeric_limits<double>::quiet_NaN();
  sketch.strokes = {s};
  const CleanReport report = clean(sketch);
  EXPECT_EQ(report.non_finite_attributes, 3u);
  EXPECT_TRUE(report.changed());
  ASSERT_EQ(sketch.strokes.size(), 1u);
  EXPECT_EQ(sketch.strokes[0].color, Stroke{}.color);
  EXPECT_EQ(sketch.strokes[0].width, 0.0);
  EXPECT_EQ(sketch.strokes[0].pressures, (std::vector<float>{0.5f, 1.f}));
  // The cleaned sketch can be written: nothing non-finite is left.
  TempDir dir;
  EXPECT_NO_THROW(write_sketch(sketch, dir / "clean.json"));
}

}  // namespace
}  // namespace sketchsurf
