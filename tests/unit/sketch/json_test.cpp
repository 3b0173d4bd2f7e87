#include "surfacing/sketch/io/json.h"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <random>

#include "tests/unit/sketch/io_test_support.h"

namespace sketchsurf {
namespace {

using testing::expect_error;
using testing::TempDir;

Sketch read_text(const std::string& text, Warnings* warnings = nullptr) {
  return read_json_text(text, "t.json", warnings);
}

// A valid document around one stroke object and optional extra root keys.
std::string document(const std::string& stroke, const std::string& extra = "") {
  return R"({"format": "sketchsurf-sketch", "version": 1,)" + extra + R"( "strokes": [)" + stroke +
         "]}";
}

TEST(Json, RoundTripKeepsEveryAttributeBitForBit) {
  TempDir dir;
  const Sketch sketch = testing::sketch_with_every_attribute(7);
  write_json(sketch, dir / "s.json");
  Warnings warnings;
  const Sketch back = read_json(dir / "s.json", &warnings);
  testing::expect_identical(sketch, back);
  EXPECT_TRUE(warnings.empty());
  // Writing what was read gives the same bytes: the format has one spelling per sketch.
  write_json(back, dir / "t.json");
  EXPECT_EQ(testing::read_text(dir / "s.json"), testing::read_text(dir / "t.json"));
}

TEST(Json, RoundTripOfOptionalAttributesAbsentAndEmptySketch) {
  TempDir dir;
  Sketch sketch;
  Stroke plain;
  plain.points = {{0, 0, 0}, {1, 2, 3}};
  sketch.strokes.push_back(plain);
  sketch.strokes.push_back(Stroke{});  // no points at all
  write_json(sketch, dir / "s.json");
  const Sketch back = read_json(dir / "s.json");
  testing::expect_identical(sketch, back);
  EXPECT_FALSE(back.mirror);
  EXPECT_TRUE(back.strokes[0].pressures.empty());

  write_json(Sketch{}, dir / "empty.json");
  EXPECT_TRUE(read_json(dir / "empty.json").strokes.empty());
}

TEST(Json, ParamsAreNestedObjectsInTheFileAndDottedNamesInMemory) {
  TempDir dir;
  Sketch sketch;
  sketch.params = {{"segment.epsilon", 0.01}, {"segment.lambda", 2.0}, {"proxy.vipss.lambda", 0.5},
                   {"seed", 3.0}};
  write_json(sketch, dir / "p.json");
  const auto j = nlohmann::json::parse(testing::read_text(dir / "p.json"));
  EXPECT_EQ(j["params"]["segment"]["epsilon"].get<double>(), 0.01);
  EXPECT_EQ(j["params"]["segment"]["lambda"].get<double>(), 2.0);
  EXPECT_EQ(j["params"]["proxy"]["vipss"]["lambda"].get<double>(), 0.5);
  EXPECT_EQ(j["params"]["seed"].get<double>(), 3.0);
  EXPECT_EQ(read_json(dir / "p.json").params, sketch.params);

  const Sketch hand = read_text(
      document("", R"( "params": {"segment": {"epsilon": 0.02, "pearl": {"rounds": 4}}, "k": 1},)"));
  const std::map<std::string, double> expected{
      {"segment.epsilon", 0.02}, {"segment.pearl.rounds", 4.0}, {"k", 1.0}};
  EXPECT_EQ(hand.params, expected);
}

TEST(Json, WriterRefusesParamsThatCannotNest) {
  TempDir dir;
  Sketch sketch;
  sketch.params = {{"segment", 1.0}, {"segment.epsilon", 0.01}};
  expect_error([&] { write_json(sketch, dir / "p.json"); }, ErrorKind::Processing, {"segment"});
  sketch.params = {{"a..b", 1.0}};
  expect_error([&] { write_json(sketch, dir / "p.json"); }, ErrorKind::Processing, {"a..b"});
  EXPECT_TRUE(dir.files().empty());
}

TEST(Json, WriterRefusesNonFiniteValuesAndLeavesNoFile) {
  TempDir dir;
  Sketch sketch = testing::sketch_with_every_attribute(1, 300, 50);
  sketch.strokes[250].points[3].y() = std::nan("");
  expect_error([&] { write_json(sketch, dir / "bad.json"); }, ErrorKind::Processing,
               {"stroke 250 point 3", "not finite"});
  EXPECT_TRUE(dir.files().empty());
}

TEST(Json, MirrorNormalIsNormalisedWithItsOffset) {
  const Sketch s = read_text(document("", R"( "mirror": {"normal": [0, 0, 2], "offset": 1},)"));
  ASSERT_TRUE(s.mirror);
  EXPECT_EQ(s.mirror->normal, Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(s.mirror->offset, 0.5);  // 2z + 1 = 0 and z + 0.5 = 0 are the same plane
  EXPECT_FALSE(read_text(document("", R"( "mirror": null,)")).mirror);
  expect_error([] { read_text(document("", R"( "mirror": {"normal": [0, 0, 0], "offset": 1},)")); },
               ErrorKind::Input, {"t.json", "mirror", "zero"});
  expect_error([] { read_text(document("", R"( "mirror": {"normal": [0, 1], "offset": 1},)")); },
               ErrorKind::Input, {"mirror.normal", "expected 3 numbers"});
}

TEST(Json, RotationPatternRoundTripsAndBadOnesAreNamed) {
  const Sketch s = read_text(document("", R"( "rotation": {"center": [1, 2, 3], "axis": [0, 0, 2], "count": 6},)"));
  ASSERT_TRUE(s.rotation);
  EXPECT_EQ(s.rotation->center, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(s.rotation->axis, Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(s.rotation->count, 6);
  EXPECT_FALSE(read_text(document("", R"( "rotation": null,)")).rotation);
  TempDir dir;
  Sketch w = s;
  w.rotation->axis = Eigen::Vector3d(0.6, 0.0, 0.8);
  write_json(w, dir / "r.json");
  const Sketch back = read_json(dir / "r.json");
  ASSERT_TRUE(back.rotation);
  EXPECT_EQ(back.rotation->axis, w.rotation->axis);
  EXPECT_EQ(back.rotation->center, w.rotation->center);
  EXPECT_EQ(back.rotation->count, 6);
  expect_error([] { read_text(document("", R"( "rotation": {"center": [0, 0, 0], "axis": [0, 0, 0], "count": 6},)")); },
               ErrorKind::Input, {"t.json", "rotation", "axis is zero"});
  expect_error([] { read_text(document("", R"( "rotation": {"center": [0, 0, 0], "axis": [0, 1, 0], "count": 1},)")); },
               ErrorKind::Input, {"rotation.count", "from 2 to 360"});
  expect_error([] { read_text(document("", R"( "rotation": {"center": [0, 0], "axis": [0, 1, 0], "count": 3},)")); },
               ErrorKind::Input, {"rotation.center", "expected 3 numbers"});
  expect_error([] { read_text(document("", R"( "rotation": {"axis": [0, 1, 0], "count": 3},)")); },
               ErrorKind::Input, {"rotation", "no \"center\""});
}

TEST(Json, ErrorsNameTheFileThePathAndWhatWasExpected) {
  const std::string ok = R"({"points": [[0, 0, 0], [1, 1, 1], [2, 2, 2]]})";
  struct Case {
    std::string text;
    std::vector<std::string> parts;
  };
  const std::vector<Case> cases = {
      {document(ok + R"(, {"points": [[0, 0, 0], [1, 1, 1], [2, 2]]})"),
       {"strokes[1].points[2]", "expected 3 numbers, got 2"}},
      {document(R"({"points": [[0, "1", 0]]})"), {"strokes[0].points[0][1]", "expected a coordinate"}},
      {document(R"({"points": [[0, 0, 0, 0]]})"), {"strokes[0].points[0][3]", "3 coordinates"}},
      {document(R"({"points": [[0, 0, 0], [1, 1, 1]], "pressures": [0.5]})"),
       {"strokes[0].pressures", "1 entries for 2 points"}},
      {document(R"({"points": [[0, 0, 0]], "orientations": [[0, 0, 0, 1], [0, 0, 0, 1]]})"),
       {"strokes[0].orientations", "2 entries for 1 points"}},
      {document(R"({"points": [[0, 0, 0]], "timestamps_ms": [-1]})"),
       {"strokes[0].timestamps_ms[0]", "timestamp"}},
      {document(R"({"points": [[0, 0, 0]], "color": [1, 0, 0]})"), {"strokes[0].color", "expected 4"}},
      {document(R"({"points": [[0, 0, 0]], "boundary": 1})"), {"strokes[0].boundary", "true or false"}},
      {document(R"({"points": [[0, 0, 0]], "width": -1})"), {"strokes[0].width", "negative"}},
      {document(R"({"points": [[0, 0, 0]], "points": []})"), {"strokes[0].points", "duplicate key"}},
      {document(R"({"width": 1})"), {"strokes[0]", "no \"points\""}},
      {document(R"([0, 0, 0])"), {"strokes[0]", "expected a stroke object, got an array"}},
      {document(R"({"points": [[0, 0, 1e999]]})"), {"strokes[0].points[0][2]", "1e999"}},
      {R"({"format": "sketchsurf-sketch", "version": 2, "strokes": []})",
       {"version", "unsupported version 2"}},
      {R"({"format": "something-else", "version": 1})", {"format", "not a sketchsurf sketch"}},
      {R"({"version": 1, "strokes": []})", {"no \"format\""}},
      {R"({"format": "sketchsurf-sketch", "strokes": []})", {"no \"version\""}},
      {R"([1, 2, 3])", {"expected a JSON object"}},
      {document("", R"( "params": {"a": [1]},)"), {"params.a", "a number or an object"}},
      {document("", R"( "params": {"a": 1, "a": 2},)"), {"params.a", "duplicate"}},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.text);
    try {
      read_text(c.text);
      ADD_FAILURE() << "accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Input);
      const std::string what = e.what();
      EXPECT_EQ(what.rfind("t.json: ", 0), 0u) << what;
      for (const auto& p : c.parts) EXPECT_NE(what.find(p), std::string::npos) << what;
    }
  }
}

TEST(Json, SyntaxErrorsGiveTheByteOffset) {
  // The offset is that of the first byte that cannot continue the document (0-based).
  //                        01234567890
  const std::string text = R"({"format": @})";
  expect_error([&] { read_text(text); }, ErrorKind::Input,
               {"t.json: byte 11: in format: unexpected character '@'; expected a value"});
  expect_error([] { read_text(document(R"({"points": [[0, 0, 0],]})")); }, ErrorKind::Input,
               {"byte", "in strokes[0].points"});
  expect_error([] { read_json("/nonexistent/dir/s.json"); }, ErrorKind::Input,
               {"/nonexistent/dir/s.json", "no such file"});
}

TEST(Json, StringsAreUnescapedAndCheckedForUtf8) {
  const Sketch s = read_text("\xef\xbb\xbf" +  // a byte order mark is skipped
                             document(R"({"points": [[0, 0, 0]], "brush": "a\"b\\c\u00e9\ud83d\ude00\n"})"));
  EXPECT_EQ(s.strokes[0].brush, "a\"b\\c\u00e9\U0001F600\n");
  expect_error([] { read_text(document(R"({"points": [], "brush": "\ud83d"})")); }, ErrorKind::Input,
               {"strokes[0].brush", "surrogate"});
  expect_error([] { read_text(document("{\"points\": [], \"brush\": \"\xc3\x28\"}")); },
               ErrorKind::Input, {"strokes[0].brush", "invalid UTF-8"});
  expect_error([] { read_text(document("{\"points\": [], \"brush\": \"a\tb\"}")); },
               ErrorKind::Input, {"control character"});
}

TEST(Json, UnknownKeysAreIgnoredWithOneWarningEach) {
  Warnings warnings;
  const Sketch s = read_text(
      document(R"({"points": [[0, 0, 0]], "future": {"x": [1, {"y": 2}]}}, )"
               R"({"points": [[1, 1, 1]], "future": 3})",
               R"( "comment": "hi",)"),
      &warnings);
  ASSERT_EQ(s.strokes.size(), 2u);
  EXPECT_EQ(s.strokes[1].points[0], Eigen::Vector3d(1, 1, 1));
  ASSERT_EQ(warnings.size(), 2u);
  EXPECT_NE(warnings[0].find("'comment'"), std::string::npos) << warnings[0];
  EXPECT_NE(warnings[1].find("'strokes[].future'"), std::string::npos) << warnings[1];
}

TEST(Json, EveryTruncationIsAnInputError) {
  const Sketch sketch = testing::sketch_with_every_attribute(3, 2, 3);
  TempDir dir;
  write_json(sketch, dir / "s.json");
  const std::string text = testing::read_text(dir / "s.json");
  const std::size_t complete = text.rfind('}') + 1;  // what follows is a newline
  for (std::size_t n = 0; n < text.size(); ++n) {
    if (n >= complete) {
      EXPECT_NO_THROW(read_text(text.substr(0, n)));
      continue;
    }
    try {
      read_text(text.substr(0, n));
      ADD_FAILURE() << "a prefix of " << n << " bytes was accepted";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::Input) << n << ": " << e.what();
    }
  }
}

TEST(Json, RandomCorruptionsGiveAnInputErrorOrAValidSketch) {
  const Sketch sketch = testing::sketch_with_every_attribute(5, 3, 4);
  TempDir dir;
  write_json(sketch, dir / "s.json");
  const std::string text = testing::read_text(dir / "s.json");
  std::mt19937 rng(2024);
  int errors = 0, valid = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const std::string bad = testing::corrupt(text, rng);
    try {
      const Sketch s = read_text(bad);
      ++valid;
      for (const auto& st : s.strokes) EXPECT_TRUE(st.attributes_consistent());
      if (s.mirror) {
        EXPECT_NEAR(s.mirror->normal.norm(), 1.0, 1e-12);
      }
    } catch (const Error& e) {
      ++errors;
      EXPECT_EQ(e.kind(), ErrorKind::Input) << e.what();
      EXPECT_EQ(std::string(e.what()).rfind("t.json: ", 0), 0u) << e.what();
    }
  }
  EXPECT_GT(errors, 200);  // most corruptions break the document; some only change a number
  EXPECT_GT(valid, 0);
}

}  // namespace
}  // namespace sketchsurf
