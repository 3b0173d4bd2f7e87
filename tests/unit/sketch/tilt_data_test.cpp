// The .tilt reader on the real sketches in ../shared/data/tilt. Stroke and point counts were
// established independently (a Python zipfile/struct walk of data.sketch).

#include <gtest/gtest.h>

#include <map>

#include "surfacing/sketch/io/json.h"
#include "surfacing/sketch/io/tilt.h"
#include "tests/unit/sketch/tilt_builder.h"

namespace sketchsurf {
namespace {

namespace fs = std::filesystem;
using namespace sketchsurf::testing;

const fs::path kTiltDir = fs::path(SKETCHSURF_DATA_DIR) / "tilt";

struct Counts {
  std::size_t strokes;
  std::size_t points;
};
const std::map<std::string, Counts> kExpected = {
    {"sketch1.tilt", {5, 912}},        {"Dungeon_Chest.tilt", {168, 3938}},
    {"Dungeon_Arrow.tilt", {3, 54}},   {"Dungeon_Torch.tilt", {33, 681}},
    {"Bristles.tilt", {67, 1231}},     {"OneStroke.tilt", {1, 4}}};

std::vector<fs::path> tilt_files() {
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(kTiltDir))
    if (e.path().extension() == ".tilt") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  return files;
}

TEST(TiltData, EveryFileReadsWithExpectedCounts) {
  const auto files = tilt_files();
  ASSERT_GE(files.size(), kExpected.size());
  for (const auto& file : files) {
    SCOPED_TRACE(file.string());
    Warnings warnings;
    const Sketch sketch = read_tilt(file, &warnings);
    EXPECT_TRUE(warnings.empty()) << warnings.front();
    if (auto it = kExpected.find(file.filename().string()); it != kExpected.end()) {
      EXPECT_EQ(sketch.strokes.size(), it->second.strokes);
      EXPECT_EQ(sketch.point_count(), it->second.points);
    }
    for (const auto& stroke : sketch.strokes) {
      EXPECT_TRUE(stroke.attributes_consistent());
      EXPECT_EQ(stroke.orientations.size(), stroke.size());
      EXPECT_EQ(stroke.timestamps_ms.size(), stroke.size());
      EXPECT_FALSE(stroke.brush.empty());
      EXPECT_GT(stroke.width, 0.0);
      for (const auto& p : stroke.points) EXPECT_TRUE(p.allFinite());
      for (const auto& q : stroke.orientations) EXPECT_NEAR(q.norm(), 1.0, 1e-5);
      EXPECT_TRUE(std::is_sorted(stroke.timestamps_ms.begin(), stroke.timestamps_ms.end()));
    }
    // Metres, floor at y = 0: objects up to a few metres standing in a room.
    const BoundingBox box = sketch.bounding_box();
    EXPECT_GT(box.diagonal(), 0.005);  // OneStroke.tilt is a 1 cm dab
    EXPECT_LT(box.diagonal(), 5.0);
    EXPECT_GT(box.min.y(), -0.1);
    EXPECT_LT(box.max.y(), 3.0);
  }
}

TEST(TiltData, MirrorPlanesAreUprightAndThroughTheSketch) {
  // Both files carry an untouched symmetry widget, turned with the scene about the vertical axis:
  // a vertical plane (horizontal normal) close to the middle of the sketch.
  for (const char* name : {"Bristles.tilt", "Dungeon_Arrow.tilt"}) {
    SCOPED_TRACE(name);
    const Sketch sketch = read_tilt(kTiltDir / name);
    ASSERT_TRUE(sketch.mirror);
    EXPECT_NEAR(sketch.mirror->normal.norm(), 1.0, 1e-9);
    EXPECT_NEAR(sketch.mirror->normal.y(), 0.0, 1e-6);
    const BoundingBox box = sketch.bounding_box();
    EXPECT_LT(std::abs(sketch.mirror->signed_distance(0.5 * (box.min + box.max))), 0.1 * box.diagonal());
  }
  EXPECT_FALSE(read_tilt(kTiltDir / "Dungeon_Chest.tilt").mirror);
}

TEST(TiltData, RoundTripsThroughWriterAndJson) {
  const auto dir = scratch_dir();
  for (const auto& file : tilt_files()) {
    SCOPED_TRACE(file.string());
    const Sketch first = read_tilt(file);
    write_tilt(first, dir / "again.tilt");
    expect_same_strokes(first, read_tilt(dir / "again.tilt"));
    write_json(first, dir / "again.json");
    write_tilt(read_json(dir / "again.json"), dir / "from_json.tilt");
    expect_same_strokes(first, read_tilt(dir / "from_json.tilt"));
  }
}

}  // namespace
}  // namespace sketchsurf
