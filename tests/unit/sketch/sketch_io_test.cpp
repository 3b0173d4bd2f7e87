#include "surfacing/sketch/io/sketch_io.h"

#include <gtest/gtest.h>

#include "tests/support/shapes.h"
#include "tests/unit/sketch/io_test_support.h"

namespace sketchsurf {
namespace {

using testing::expect_error;
using testing::TempDir;

TEST(SketchIo, EveryWritableExtensionReadsBackTheSamePoints) {
  TempDir dir;
  Sketch sketch = testing::sphere_sketch(0.5, 4);
  testing::add_noise(sketch, 1e-4, 3);
  for (const auto& ext : writable_sketch_extensions()) {
    SCOPED_TRACE(ext);
    const auto file = dir / ("s" + ext);
    write_sketch(sketch, file);
    const Sketch back = read_sketch(file);
    // .tilt stores float32 positions; the text formats are exact.
    testing::expect_same_points(sketch, back, ext == ".tilt" ? 1e-6 : 0.0);
  }
  const auto readable = readable_sketch_extensions();
  for (const auto& ext : writable_sketch_extensions())
    EXPECT_NE(std::find(readable.begin(), readable.end(), ext), readable.end()) << ext;
}

TEST(SketchIo, ExtensionsAreCaseInsensitive) {
  TempDir dir;
  const Sketch sketch = testing::cube_sketch(2.0, false);
  write_sketch(sketch, dir / "S.JSON");
  EXPECT_EQ(read_sketch(dir / "S.JSON").point_count(), sketch.point_count());
  write_sketch(sketch, dir / "S.Curves");
  EXPECT_EQ(read_sketch(dir / "S.Curves").point_count(), sketch.point_count());
}

TEST(SketchIo, UnknownExtensionIsAUsageErrorMissingFileAnInputError) {
  TempDir dir;
  const Sketch sketch = testing::cube_sketch();
  expect_error([&] { write_sketch(sketch, dir / "s.svg"); }, ErrorKind::Usage,
               {"s.svg", "unknown sketch extension '.svg'", ".json"});
  testing::write_text(dir / "s.txt", "v 1\n0 0 0\n");
  expect_error([&] { read_sketch(dir / "s.txt"); }, ErrorKind::Usage, {"unknown sketch extension"});
  expect_error([&] { read_sketch(dir / "nothere.json"); }, ErrorKind::Input,
               {"nothere.json", "no such file"});
  std::filesystem::create_directory(dir / "folder.json");
  expect_error([&] { read_sketch(dir / "folder.json"); }, ErrorKind::Input,
               {"folder.json", "is a directory"});
  EXPECT_EQ(dir.files(), (std::vector<std::string>{"folder.json", "s.txt"}));
}

TEST(SketchIo, WriteIntoAMissingDirectoryIsAProcessingError) {
  TempDir dir;
  expect_error([&] { write_sketch(testing::cube_sketch(), dir / "no" / "s.json"); },
               ErrorKind::Processing, {"s.json", "cannot create"});
}

}  // namespace
}  // namespace sketchsurf
