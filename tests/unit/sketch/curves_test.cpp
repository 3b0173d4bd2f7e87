#include "surfacing/sketch/io/curves.h"

#include <gtest/gtest.h>

#include "surfacing/sketch/io/json.h"
#include "tests/support/shapes.h"
#include "tests/unit/sketch/io_test_support.h"

namespace sketchsurf {
namespace {

using testing::expect_error;
using testing::TempDir;

TEST(Curves, ReadsStrokesAndToleratesBlankLinesCrlfAndTrailingWhitespace) {
  TempDir dir;
  testing::write_text(dir / "a.curves",
                      "v 2\r\n0 0 0 \r\n1 2.5 -3e-2\t\r\n\r\n  \nv 3\n\n4 5 6\n7 8 9  \n10 11 12");
  Warnings warnings;
  const Sketch s = read_curves(dir / "a.curves", &warnings);
  ASSERT_EQ(s.strokes.size(), 2u);
  ASSERT_EQ(s.strokes[0].size(), 2u);
  ASSERT_EQ(s.strokes[1].size(), 3u);
  EXPECT_EQ(s.strokes[0].points[1], Eigen::Vector3d(1, 2.5, -3e-2));
  EXPECT_EQ(s.strokes[1].points[2], Eigen::Vector3d(10, 11, 12));
  EXPECT_EQ(s.strokes[0].id, 0);
  EXPECT_EQ(s.strokes[1].id, 1);
  EXPECT_TRUE(warnings.empty());
}

TEST(Curves, EmptyStrokesAreSkippedWithAWarning) {
  TempDir dir;
  testing::write_text(dir / "a.curves", "v 0\nv 2\n0 0 0\n1 1 1\nv 0\n");
  Warnings warnings;
  const Sketch s = read_curves(dir / "a.curves", &warnings);
  EXPECT_EQ(s.strokes.size(), 1u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("skipped 2 stroke(s)"), std::string::npos);
  EXPECT_TRUE(read_curves(dir / "a.curves").strokes.size() == 1u);  // warnings are optional
  testing::write_text(dir / "empty.curves", "");  // no stroke at all: said to be empty
  testing::expect_error([&] { read_curves(dir / "empty.curves"); }, ErrorKind::Input,
                        {"empty.curves: the file is empty"});
}

TEST(Curves, ErrorsGiveTheLineAndWhatWasExpected) {
  TempDir dir;
  struct Case {
    std::string text;
    std::vector<std::string> parts;
  };
  const std::vector<Case> cases = {
      {"v 3\n0 0 0\n1 1 1\nv 2\n0 0 0\n1 1 1\n", {"b.curves:4:", "declares 3 points but has only 2"}},
      {"v 2\n0 0 0\n", {"b.curves:2:", "declares 2 points but the file ends after 1"}},
      {"v 2\n0 0 0\n1 x 1\n", {"b.curves:3:", "expected a point 'x y z'", "'1 x 1'"}},
      {"v 2\n0 0 0\n1 1\n", {"b.curves:3:", "three numbers"}},
      {"v 2\n0 0 0\n1 1 1 1\n", {"b.curves:3:", "three numbers"}},
      {"v 1\n0 0 nan\n", {"b.curves:2:", "x y z"}},
      {"0 0 0\n", {"b.curves:1:", "expected a stroke header 'v N'"}},
      {"\n\nv -1\n", {"b.curves:3:", "a point count >= 0"}},
      {"v two\n", {"b.curves:1:", "a point count"}},
      {"v 1000000000\n0 0 0\n1 1 1\n", {"b.curves:1:", "declares 1000000000 points", "bytes remain"}},
      {"v 99999999999999999999999\n", {"b.curves:1:", "a point count"}},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.text);
    testing::write_text(dir / "b.curves", c.text);
    try {
      read_curves(dir / "b.curves");
      ADD_FAILURE() << "accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Input);
      for (const auto& p : c.parts) EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what();
    }
  }
  expect_error([&] { read_curves(dir / "missing.curves"); }, ErrorKind::Input, {"missing.curves"});
}

TEST(Curves, RoundTripThroughJsonKeepsEveryPosition) {
  TempDir dir;
  Sketch sketch = testing::cylinder_sketch(0.5, 1.0, 6);
  testing::add_noise(sketch, 1e-3, 11);  // positions with full mantissas
  write_curves(sketch, dir / "a.curves");
  const Sketch a = read_curves(dir / "a.curves");
  testing::expect_same_points(sketch, a, 0.0);  // shortest round-trip text: exact
  write_json(a, dir / "a.json");
  write_curves(read_json(dir / "a.json"), dir / "b.curves");
  EXPECT_EQ(testing::read_text(dir / "a.curves"), testing::read_text(dir / "b.curves"));
}

TEST(Curves, WriterSkipsEmptyStrokesAndRefusesNonFinitePoints) {
  TempDir dir;
  Sketch sketch = testing::cube_sketch(1.0, false);
  sketch.strokes.insert(sketch.strokes.begin() + 1, Stroke{});
  write_curves(sketch, dir / "a.curves");
  EXPECT_EQ(read_curves(dir / "a.curves").strokes.size(), 12u);
  testing::write_text(dir / "b.curves", "keep me");
  sketch.strokes.back().points.back().x() = std::numeric_limits<double>::infinity();
  expect_error([&] { write_curves(sketch, dir / "b.curves"); }, ErrorKind::Processing,
               {"stroke 12", "not finite"});
  EXPECT_EQ(testing::read_text(dir / "b.curves"), "keep me");
}

TEST(Curves, RandomCorruptionsGiveAnInputErrorOrAValidSketch) {
  TempDir dir;
  write_curves(testing::cube_sketch(1.0, false), dir / "a.curves");
  const std::string text = testing::read_text(dir / "a.curves");
  std::mt19937 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    testing::write_text(dir / "c.curves", testing::corrupt(text, rng));
    try {
      const Sketch s = read_curves(dir / "c.curves");
      for (const auto& st : s.strokes) EXPECT_TRUE(st.points.size() > 0 && st.attributes_consistent());
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Input) << e.what();
      EXPECT_NE(std::string(e.what()).find("c.curves:"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace sketchsurf
