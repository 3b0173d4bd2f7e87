#include "surfacing/sketch/io/obj_polylines.h"

#include <gtest/gtest.h>

#include "surfacing/sketch/io/json.h"
#include "tests/support/shapes.h"
#include "tests/unit/sketch/io_test_support.h"

namespace sketchsurf {
namespace {

using testing::expect_error;
using testing::TempDir;

// Vertex k (1-based) of the hand-made graph sits at (k, 0, 0), so a stroke's x coordinates are
// the OBJ indices of its vertices.
std::string numbered_vertices(int count) {
  std::string text;
  for (int k = 1; k <= count; ++k) text += "v " + std::to_string(k) + " 0 0\n";
  return text;
}

std::vector<int> indices_of(const Stroke& s) {
  std::vector<int> out;
  for (const auto& p : s.points) out.push_back(static_cast<int>(p.x()));
  return out;
}

TEST(ObjPolylines, SegmentsBecomeChainsSplitAtJunctionsLoopsAndEnds) {
  TempDir dir;
  // A T junction at 3 (arms 1-2-3, 3-4-5, 3-6-7), a square loop 8-9-10-11, a path 12-13-14.
  // Segments in scrambled order and directions.
  const std::string text = numbered_vertices(14) +
                           "l 4 3\nl 9 10\nl 13 12\nl 2 1\nl 6 7\nl 11 10\nl 3 2\nl 5 4\n"
                           "l 8 11\nl 14 13\nl 3 6\nl 9 8\n";
  testing::write_text(dir / "g.obj", text);
  Warnings warnings;
  const Sketch s = read_obj_polylines(dir / "g.obj", &warnings);
  EXPECT_TRUE(warnings.empty());
  ASSERT_EQ(s.strokes.size(), 5u);
  // Chains from their smaller end, by that vertex, then in the file order of their segments;
  // loops last, from their smallest vertex towards its smaller neighbour, closed.
  EXPECT_EQ(indices_of(s.strokes[0]), (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(indices_of(s.strokes[1]), (std::vector<int>{3, 4, 5}));
  EXPECT_EQ(indices_of(s.strokes[2]), (std::vector<int>{3, 6, 7}));
  EXPECT_EQ(indices_of(s.strokes[3]), (std::vector<int>{12, 13, 14}));
  EXPECT_EQ(indices_of(s.strokes[4]), (std::vector<int>{8, 9, 10, 11, 8}));
  for (std::size_t i = 0; i < s.strokes.size(); ++i) EXPECT_EQ(s.strokes[i].id, static_cast<int>(i));
}

TEST(ObjPolylines, ChainOrderDoesNotDependOnSegmentOrder) {
  TempDir dir;
  const std::vector<std::string> segments = {"l 1 2\n", "l 2 3\n", "l 3 4\n", "l 4 5\n", "l 3 6\n"};
  std::vector<std::vector<int>> first;
  std::vector<std::size_t> order = {0, 1, 2, 3, 4};
  do {
    std::string text = numbered_vertices(6);
    for (std::size_t i : order) text += segments[i];
    testing::write_text(dir / "p.obj", text);
    const Sketch s = read_obj_polylines(dir / "p.obj");
    std::vector<std::vector<int>> got;
    for (const auto& st : s.strokes) got.push_back(indices_of(st));
    std::sort(got.begin(), got.end());
    if (first.empty()) first = got;
    EXPECT_EQ(got, first);
  } while (std::next_permutation(order.begin(), order.end()));
  EXPECT_EQ(first, (std::vector<std::vector<int>>{{1, 2, 3}, {3, 4, 5}, {3, 6}}));
}

TEST(ObjPolylines, LongerLineRecordsAreStrokesAsWritten) {
  TempDir dir;
  // One 3-vertex record: every record is a stroke, 2-vertex ones too; negative indices count
  // back from the last vertex; `v/vt` forms keep the vertex index.
  testing::write_text(dir / "l.obj", numbered_vertices(6) + "l 3 2 1\nl -1 -2\nl 4/1 6/2 5/3\n");
  const Sketch s = read_obj_polylines(dir / "l.obj");
  ASSERT_EQ(s.strokes.size(), 3u);
  EXPECT_EQ(indices_of(s.strokes[0]), (std::vector<int>{3, 2, 1}));
  EXPECT_EQ(indices_of(s.strokes[1]), (std::vector<int>{6, 5}));
  EXPECT_EQ(indices_of(s.strokes[2]), (std::vector<int>{4, 6, 5}));
}

TEST(ObjPolylines, FacesAreIgnoredWithOneWarningAndOtherRecordsSilently) {
  TempDir dir;
  testing::write_text(dir / "f.obj",
                      "# comment\nmtllib x.mtl\no thing\ng group\n" + numbered_vertices(4) +
                          "vn 0 0 1\nvt 0 0\ns off\nusemtl m\nf 1 2 3\nf 1 3 4\nl 1 2 3\n");
  Warnings warnings;
  const Sketch s = read_obj_polylines(dir / "f.obj", &warnings);
  ASSERT_EQ(s.strokes.size(), 1u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("ignored 2 face(s)"), std::string::npos) << warnings[0];
}

TEST(ObjPolylines, ErrorsGiveTheLine) {
  TempDir dir;
  struct Case {
    std::string text;
    std::vector<std::string> parts;
  };
  const std::vector<Case> cases = {
      {numbered_vertices(3) + "l 1 4\n", {"e.obj:4:", "vertex index 4 is out of range (3 vertices"}},
      {numbered_vertices(3) + "l 1 -4\n", {"e.obj:4:", "index -4 is out of range"}},
      {numbered_vertices(3) + "l 1 0\n", {"e.obj:4:", "'0' is not a vertex index"}},
      {numbered_vertices(3) + "l 1 x\n", {"e.obj:4:", "'x' is not a vertex index"}},
      {numbered_vertices(3) + "l 1\n", {"e.obj:4:", "at least 2 vertices"}},
      {"v 1 2\n", {"e.obj:1:", "3 coordinates"}},
      {"v 1 2 z\n", {"e.obj:1:", "'z' is not a number"}},
      {"l 1 2\nv 0 0 0\nv 1 1 1\n", {"e.obj:1:", "out of range (0 vertices"}},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.text);
    testing::write_text(dir / "e.obj", c.text);
    try {
      read_obj_polylines(dir / "e.obj");
      ADD_FAILURE() << "accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Input);
      for (const auto& p : c.parts) EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what();
    }
  }
}

TEST(ObjPolylines, RoundTripThroughJsonKeepsEveryPosition) {
  TempDir dir;
  Sketch sketch = testing::torus_sketch(0.5, 0.2, 6);
  testing::add_noise(sketch, 1e-3, 5);
  write_obj_polylines(sketch, dir / "a.obj");
  const Sketch a = read_obj_polylines(dir / "a.obj");
  testing::expect_same_points(sketch, a, 0.0);
  write_json(a, dir / "a.json");
  write_obj_polylines(read_json(dir / "a.json"), dir / "b.obj");
  EXPECT_EQ(testing::read_text(dir / "a.obj"), testing::read_text(dir / "b.obj"));
}

TEST(ObjPolylines, TwoPointStrokesRoundTripAsSeparateChains) {
  // Every record is then a 2-vertex segment, read as chains: strokes share no vertex, so each
  // chain is one stroke again, in the same order and direction.
  TempDir dir;
  Sketch sketch;
  for (int i = 0; i < 4; ++i) {
    Stroke s;
    s.points = {{1.0 * i, 0, 0}, {1.0 * i, 1, 0}};
    sketch.strokes.push_back(s);
  }
  sketch.strokes.push_back(Stroke{});  // too short for an OBJ line: not written
  write_obj_polylines(sketch, dir / "s.obj");
  sketch.strokes.pop_back();
  testing::expect_same_points(sketch, read_obj_polylines(dir / "s.obj"), 0.0);
}

TEST(ObjPolylines, RandomCorruptionsGiveAnInputErrorOrAValidSketch) {
  TempDir dir;
  write_obj_polylines(testing::cube_sketch(1.0, false), dir / "a.obj");
  const std::string polylines = testing::read_text(dir / "a.obj");
  const std::string segments = numbered_vertices(9) + "l 1 2\nl 2 3\nl 3 4\nl 4 1\nl 3 5\nl 6 7\nf 1 2 3\n";
  std::mt19937 rng(8);
  for (int trial = 0; trial < 300; ++trial) {
    testing::write_text(dir / "c.obj", testing::corrupt(trial % 2 ? polylines : segments, rng));
    try {
      const Sketch s = read_obj_polylines(dir / "c.obj");
      for (const auto& st : s.strokes) EXPECT_GE(st.points.size(), 2u);
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Input) << e.what();
      EXPECT_NE(std::string(e.what()).find("c.obj:"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace sketchsurf
