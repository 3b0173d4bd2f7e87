// Tests of surfacing/sketch/io/tilt.h: the writer's output, round trips, and hand-assembled files
// for everything the format allows that our writer never produces.

#include "surfacing/sketch/io/tilt.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "surfacing/error.h"
#include "surfacing/sketch/io/json.h"
#include "tests/unit/sketch/tilt_builder.h"

namespace sketchsurf {
namespace {

namespace fs = std::filesystem;
using namespace sketchsurf::testing;

constexpr const char* kMarker = "429ed64a-4e97-4466-84d3-145a861ef684";
constexpr const char* kLight = "2241cd32-8ba2-48a5-9ee7-2caef7e9ed62";
constexpr const char* kMinimalMetadata =
    R"({"EnvironmentPreset":"ab080599-e465-4a6d-8587-43bf495af68b","BrushIndex":["429ed64a-4e97-4466-84d3-145a861ef684"],"SchemaVersion":2})";

Error input_error(const ByteVec& bytes) {
  try {
    read_tilt_bytes(bytes, "bad.tilt");
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << "the file was accepted";
  return Error(ErrorKind::Processing, "");
}

void expect_input_error(const ByteVec& bytes, const std::string& fragment) {
  const Error e = input_error(bytes);
  EXPECT_EQ(e.kind(), ErrorKind::Input);
  EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("bad.tilt"), std::string::npos) << e.what();
}

/// Three strokes with every attribute, on three layers, with a mirror plane.
Sketch attributed_sketch() {
  Sketch sketch;
  std::uint32_t time = 1000;
  for (int s = 0; s < 3; ++s) {
    Stroke stroke;
    const int n = 5 + 3 * s;
    for (int i = 0; i < n; ++i) {
      const double t = i / double(n - 1);
      stroke.points.emplace_back(0.3 * std::cos(3 * t + s), 1.2 + 0.1 * s + 0.05 * t, 0.3 * std::sin(3 * t));
      stroke.orientations.push_back(Eigen::Quaterniond(
          Eigen::AngleAxisd(0.4 * i + s, Eigen::Vector3d(1, 2, 3 - s).normalized())));
      stroke.pressures.push_back(static_cast<float>(0.1 + 0.8 * t));
      stroke.timestamps_ms.push_back(time += 11);
    }
    stroke.width = 0.004 * (s + 1);
    stroke.color = {0.25f * s, 0.5f, 1.0f, 1.0f};
    stroke.brush = s == 1 ? kMarker : kLight;
    stroke.layer = static_cast<std::uint32_t>(s);
    sketch.strokes.push_back(stroke);
  }
  Plane mirror;
  mirror.normal = Eigen::Vector3d(0.8, 0.0, 0.6);
  mirror.offset = -0.05;
  sketch.mirror = mirror;
  return sketch;
}

RawPoint raw_point(float x, float y, float z, std::uint32_t time) {
  RawPoint p;
  p.x = x;
  p.y = y;
  p.z = z;
  p.time_ms = time;
  return p;
}

RawStroke raw_stroke(std::uint32_t stroke_mask, std::vector<std::uint32_t> small_ext, int points = 3) {
  RawStroke s;
  s.stroke_mask = stroke_mask;
  s.small_ext = std::move(small_ext);
  for (int i = 0; i < points; ++i) s.points.push_back(raw_point(float(i), 1.0f, 2.0f, 10u * i));
  return s;
}

// ---------------------------------------------------------------------------------------------
// Writer.

TEST(TiltWriter, RoundTripKeepsEveryAttribute) {
  const auto dir = scratch_dir();
  const Sketch original = attributed_sketch();
  write_tilt(original, dir / "a.tilt");
  Warnings warnings;
  const Sketch back = read_tilt(dir / "a.tilt", &warnings);
  EXPECT_TRUE(warnings.empty());
  expect_same_strokes(original, back);
  EXPECT_EQ(back.units, "m");
  EXPECT_NE(back.provenance.find("a.tilt"), std::string::npos);

  // Writing what was read gives the same data.sketch bytes: the writer is deterministic and
  // loses nothing.
  write_tilt(back, dir / "b.tilt");
  auto sketch_entry = [](const ByteVec& file) {
    for (auto& e : parse_zip(ByteVec(file.begin() + 16, file.end())))
      if (e.name == "data.sketch") return e.data;
    return ByteVec{};
  };
  const ByteVec a = sketch_entry(read_bytes(dir / "a.tilt"));
  EXPECT_FALSE(a.empty());
  EXPECT_EQ(a, sketch_entry(read_bytes(dir / "b.tilt")));
}

TEST(TiltWriter, RoundTripThroughJson) {
  // .tilt -> .json -> .tilt -> reader: the same strokes as the first read.
  const auto dir = scratch_dir();
  write_tilt(attributed_sketch(), dir / "first.tilt");
  const Sketch first = read_tilt(dir / "first.tilt");
  write_json(first, dir / "middle.json");
  write_tilt(read_json(dir / "middle.json"), dir / "last.tilt");
  expect_same_strokes(first, read_tilt(dir / "last.tilt"));
}

TEST(TiltWriter, FollowsWhatOpenBrushNeeds) {
  const auto dir = scratch_dir();
  Sketch sketch = attributed_sketch();
  sketch.strokes[0].orientations[2] = Eigen::Quaterniond(0, 0, 0, 0);  // degenerate: identity
  sketch.strokes[1].timestamps_ms.clear();                              // synthesised
  sketch.strokes[2].timestamps_ms[3] = 5;                               // goes back in time
  Stroke single;
  single.points = {{0.1, 0.2, 0.3}};
  sketch.strokes.push_back(single);
  sketch.strokes.push_back(Stroke{});  // zero points: never written
  write_tilt(sketch, dir / "rules.tilt");

  const ByteVec file = read_bytes(dir / "rules.tilt");
  ASSERT_GT(file.size(), 16u);
  EXPECT_EQ(read_u32(file, 0), 0x546C6974u);  // "tilT"
  EXPECT_EQ(read_u16(file, 4), 16);
  EXPECT_EQ(read_u16(file, 6), 1);
  EXPECT_EQ(read_u32(file, 8), 0u);
  EXPECT_EQ(read_u32(file, 12), 0u);
  // parse_zip demands offsets counted from the zip's first byte and no data descriptors.
  const auto entries = parse_zip(ByteVec(file.begin() + 16, file.end()));
  std::map<std::string, ByteVec> by_name;
  for (const auto& e : entries) {
    EXPECT_EQ(e.method, 0) << e.name << " is not Stored";
    by_name[e.name] = e.data;
  }
  ASSERT_TRUE(by_name.count("data.sketch") && by_name.count("metadata.json") &&
              by_name.count("thumbnail.png"));

  const auto meta = nlohmann::json::parse(std::string(by_name["metadata.json"].begin(),
                                                      by_name["metadata.json"].end()));
  EXPECT_TRUE(meta.at("EnvironmentPreset").is_string());
  EXPECT_EQ(meta.at("SchemaVersion"), 2);
  EXPECT_EQ(meta.at("BrushIndex"), nlohmann::json::array({kLight, kMarker}));
  EXPECT_EQ(meta.at("Layers").size(), 3u);
  EXPECT_TRUE(meta.at("Mirror").contains("Transform"));

  const ByteVec& d = by_name["data.sketch"];
  EXPECT_EQ(read_u32(d, 0), 0xC576A5CDu);
  EXPECT_EQ(read_u32(d, 4), 5u);
  EXPECT_EQ(read_u32(d, 12), 0u);
  ASSERT_EQ(read_u32(d, 16), 4u);  // the zero-point stroke is left out
  std::size_t at = 20;
  std::uint32_t previous_first_time = 0;
  std::vector<std::uint32_t> point_counts;
  for (int s = 0; s < 4; ++s) {
    const std::uint32_t brush = read_u32(d, at);
    EXPECT_LT(brush, 2u);
    EXPECT_GT(read_f32(d, at + 20), 0.0f);  // size
    EXPECT_EQ(read_u32(d, at + 24), 0x19u);  // Flags, Seed, Layer
    EXPECT_EQ(read_u32(d, at + 28), 0x3u);   // pressure, timestamp
    EXPECT_EQ(read_u32(d, at + 32), 0u);     // Flags = 0
    EXPECT_LT(read_u32(d, at + 40), 3u);     // layer index
    const std::uint32_t n = read_u32(d, at + 44);
    point_counts.push_back(n);
    EXPECT_GE(n, 2u);
    at += 48;
    std::uint32_t previous_time = 0;
    for (std::uint32_t i = 0; i < n; ++i, at += 36) {
      const Eigen::Vector4d q(read_f32(d, at + 12), read_f32(d, at + 16), read_f32(d, at + 20),
                              read_f32(d, at + 24));
      EXPECT_NEAR(q.norm(), 1.0, 1e-6);
      const std::uint32_t time = read_u32(d, at + 32);
      EXPECT_GE(time, previous_time);
      if (i == 0) {
        EXPECT_GE(time, previous_first_time) << "strokes not sorted by first timestamp";
        previous_first_time = time;
      }
      previous_time = time;
    }
  }
  EXPECT_EQ(at, d.size());
  EXPECT_EQ(std::count(point_counts.begin(), point_counts.end(), 2u), 1) << "the one-point stroke";

  // The one-point stroke reads back as its point twice, with the defaults filled in.
  const Sketch back = read_tilt(dir / "rules.tilt");
  ASSERT_EQ(back.strokes.size(), 4u);
  const auto it = std::find_if(back.strokes.begin(), back.strokes.end(),
                               [](const Stroke& s) { return s.size() == 2; });
  ASSERT_NE(it, back.strokes.end());
  EXPECT_LT((it->points[0] - Eigen::Vector3d(0.1, 0.2, 0.3)).norm(), 1e-6);
  EXPECT_LT((it->points[1] - Eigen::Vector3d(0.1, 0.2, 0.3)).norm(), 1e-6);
  EXPECT_EQ(it->brush, kLight);
  EXPECT_EQ(it->pressures, std::vector<float>(2, 1.0f));
  EXPECT_GT(it->width, 0.0);
}

TEST(TiltWriter, SortsStrokesByFirstTimestamp) {
  const auto dir = scratch_dir();
  Sketch sketch = attributed_sketch();
  std::swap(sketch.strokes[0], sketch.strokes[2]);  // now out of time order
  write_tilt(sketch, dir / "sorted.tilt");
  const Sketch back = read_tilt(dir / "sorted.tilt");
  ASSERT_EQ(back.strokes.size(), 3u);
  for (std::size_t s = 1; s < back.strokes.size(); ++s)
    EXPECT_LE(back.strokes[s - 1].timestamps_ms.front(), back.strokes[s].timestamps_ms.front());
  EXPECT_EQ(back.strokes[0].layer, 0u);  // the original first stroke is first again
}

TEST(TiltWriter, SynthesisesTimestampsInSketchOrder) {
  const auto dir = scratch_dir();
  Sketch sketch = attributed_sketch();
  for (auto& s : sketch.strokes) s.timestamps_ms.clear();
  sketch.strokes[1].orientations.clear();
  write_tilt(sketch, dir / "times.tilt");
  const Sketch back = read_tilt(dir / "times.tilt");
  ASSERT_EQ(back.strokes.size(), 3u);
  std::uint32_t previous = 0;
  for (std::size_t s = 0; s < 3; ++s) {
    EXPECT_EQ(back.strokes[s].layer, s) << "sketch order kept";
    for (auto t : back.strokes[s].timestamps_ms) {
      EXPECT_GE(t, previous);
      previous = t;
    }
    EXPECT_LT((back.strokes[s].points.back() - sketch.strokes[s].points.back()).norm(), 1e-6);
  }
  for (const auto& q : back.strokes[1].orientations)
    EXPECT_LT(rotation_distance(q, Eigen::Quaterniond::Identity()), 1e-7);
}

TEST(TiltWriter, RefusesNonFinitePointsAndLeavesNoFile) {
  const auto dir = scratch_dir();
  Sketch sketch = attributed_sketch();
  sketch.strokes[1].points[2].x() = std::nan("");
  try {
    write_tilt(sketch, dir / "nan.tilt");
    FAIL() << "written";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Processing);
    EXPECT_NE(std::string(e.what()).find("stroke 1"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::is_empty(dir));
}

TEST(TiltWriter, SingleLayerSketchUsesPlainMasks) {
  const auto dir = scratch_dir();
  Sketch sketch = attributed_sketch();
  for (auto& s : sketch.strokes) s.layer = 0;
  sketch.mirror.reset();
  write_tilt(sketch, dir / "plain.tilt");
  const ByteVec file = read_bytes(dir / "plain.tilt");
  for (const auto& e : parse_zip(ByteVec(file.begin() + 16, file.end()))) {
    if (e.name == "data.sketch") {
      EXPECT_EQ(read_u32(e.data, 44), 0x9u);
    }
    if (e.name == "metadata.json") {
      const auto meta = nlohmann::json::parse(std::string(e.data.begin(), e.data.end()));
      EXPECT_FALSE(meta.contains("Layers"));
      EXPECT_FALSE(meta.contains("Mirror"));
    }
  }
  expect_same_strokes(sketch, read_tilt(dir / "plain.tilt"));
}

// ---------------------------------------------------------------------------------------------
// Reader: hand-assembled files.

TEST(TiltReader, StrokeMasksSeenInRealFiles) {
  // 0x1 Flags; 0x3 Flags+Scale; 0xB Flags+Scale+Seed; 0xF +Group; 0x19 Flags+Seed+Layer.
  const std::vector<std::pair<std::uint32_t, std::vector<std::uint32_t>>> masks = {
      {0x1, {0}},
      {0x3, {0, std::bit_cast<std::uint32_t>(2.0f)}},
      {0xB, {0, std::bit_cast<std::uint32_t>(1.0f), 7}},
      {0xF, {0, std::bit_cast<std::uint32_t>(1.0f), 3, 7}},
      {0x19, {0, 7, 0}}};
  std::vector<RawStroke> strokes;
  for (const auto& [mask, values] : masks) strokes.push_back(raw_stroke(mask, values, 4));
  const Sketch sketch = read_tilt_bytes(simple_tilt(data_sketch(strokes), kMinimalMetadata), "m.tilt");
  ASSERT_EQ(sketch.strokes.size(), masks.size());
  for (std::size_t s = 0; s < masks.size(); ++s) {
    const Stroke& stroke = sketch.strokes[s];
    ASSERT_EQ(stroke.size(), 4u);
    // (3, 1, 2) decimetres -> (-0.3, 0.1, 0.2) metres, whatever came before the points.
    EXPECT_LT((stroke.points[3] - Eigen::Vector3d(-0.3, 0.1, 0.2)).norm(), 1e-7);
    EXPECT_EQ(stroke.timestamps_ms, (std::vector<std::uint32_t>{0, 10, 20, 30}));
    EXPECT_EQ(stroke.brush, kMarker);
  }
  EXPECT_NEAR(sketch.strokes[0].width, 0.05, 1e-9);  // size 0.5 dm
  EXPECT_NEAR(sketch.strokes[1].width, 0.10, 1e-9);  // Scale extension 2
}

TEST(TiltReader, WalksUnknownExtensionBitsGenerically) {
  // Stroke bits 5..15 carry 4 bytes, bits 16..31 a length and that many bytes; unknown control
  // point bits carry 4 bytes each and sit between the known ones.
  RawStroke s = raw_stroke(0x1 | (1u << 5) | (1u << 15) | (1u << 16) | (1u << 31), {0, 11, 22});
  s.large_ext = {"seven b", ""};
  s.cp_mask = 0x1 | 0x2 | 0x4 | 0x80;  // pressure, timestamp, two unknown
  s.points[1].pressure = 0.25f;
  RawStroke plain = raw_stroke(0x1, {0});
  const Sketch sketch =
      read_tilt_bytes(simple_tilt(data_sketch({s, plain}), kMinimalMetadata), "ext.tilt");
  ASSERT_EQ(sketch.strokes.size(), 2u);
  EXPECT_EQ(sketch.strokes[0].timestamps_ms, (std::vector<std::uint32_t>{0, 10, 20}));
  EXPECT_EQ(sketch.strokes[0].pressures[1], 0.25f);
  EXPECT_LT((sketch.strokes[1].points[2] - Eigen::Vector3d(-0.2, 0.1, 0.2)).norm(), 1e-7);
}

TEST(TiltReader, MissingControlPointAttributesStayAbsent) {
  RawStroke s = raw_stroke(0x1, {0});
  s.cp_mask = 0x2;  // timestamp only, right after the orientation
  const Sketch sketch = read_tilt_bytes(simple_tilt(data_sketch({s}), kMinimalMetadata), "t.tilt");
  ASSERT_EQ(sketch.strokes.size(), 1u);
  EXPECT_TRUE(sketch.strokes[0].pressures.empty());
  EXPECT_EQ(sketch.strokes[0].timestamps_ms, (std::vector<std::uint32_t>{0, 10, 20}));
  EXPECT_TRUE(sketch.strokes[0].attributes_consistent());
}

TEST(TiltReader, ExtraHeaderBytesInFileAndSketch) {
  const ByteVec sketch = data_sketch({raw_stroke(0x1, {0})}, 6, "future header fields");
  const ByteVec zip = zip_archive({{"data.sketch", sketch, false, {}},
                                   {"metadata.json", bytes_of(kMinimalMetadata), false, {}}});
  const Sketch s = read_tilt_bytes(tilt_file(zip, 24), "extra.tilt");
  ASSERT_EQ(s.strokes.size(), 1u);
  EXPECT_EQ(s.strokes[0].size(), 3u);
}

TEST(TiltReader, DeflateEntriesAndDuplicateNames) {
  const ByteVec one = data_sketch({raw_stroke(0x1, {0}, 5)});
  const ByteVec two = data_sketch({raw_stroke(0x1, {0}, 2), raw_stroke(0x1, {0}, 2)});
  const ByteVec zip = zip_archive({{"thumbnail.png", bytes_of("png one"), false, {}},
                                   {"thumbnail.png", bytes_of("png two"), false, {}},
                                   {"data.sketch", one, true, {}},
                                   {"data.sketch", two, true, {}},
                                   {"metadata.json", bytes_of(kMinimalMetadata), true, {}}});
  const Sketch s = read_tilt_bytes(tilt_file(zip), "deflate.tilt");
  ASSERT_EQ(s.strokes.size(), 1u) << "the first of two data.sketch entries wins";
  EXPECT_EQ(s.strokes[0].size(), 5u);
  EXPECT_EQ(s.strokes[0].brush, kMarker);
}

TEST(TiltReader, ZipOffsetsCountedFromFileStartAlsoRead) {
  const ByteVec zip = zip_archive({{"data.sketch", data_sketch({raw_stroke(0x1, {0})}), false, {}},
                                   {"metadata.json", bytes_of(kMinimalMetadata), false, {}}},
                                  16);
  EXPECT_EQ(read_tilt_bytes(tilt_file(zip), "generic.tilt").strokes.size(), 1u);
}

TEST(TiltReader, LegacyMainJson) {
  const ByteVec zip = zip_archive(
      {{"data.sketch", data_sketch({raw_stroke(0x1, {0})}), false, {}},
       {"main.json", bytes_of(R"({"BrushIndex":["429ed64a-4e97-4466-84d3-145a861ef684"]})"), false, {}}});
  const Sketch s = read_tilt_bytes(tilt_file(zip), "legacy.tilt");
  ASSERT_EQ(s.strokes.size(), 1u);
  EXPECT_EQ(s.strokes[0].brush, kMarker);
}

TEST(TiltReader, DirectoryForm) {
  const auto dir = scratch_dir() / "folder.tilt";
  fs::create_directories(dir);
  const ByteVec sketch = data_sketch({raw_stroke(0x1, {0}, 4), raw_stroke(0x3, {0, 0x3F800000}, 2)});
  std::ofstream(dir / "data.sketch", std::ios::binary)
      .write(reinterpret_cast<const char*>(sketch.data()), static_cast<std::streamsize>(sketch.size()));
  std::ofstream(dir / "metadata.json") << kMinimalMetadata;
  std::ofstream(dir / "thumbnail.png") << "png";
  const Sketch s = read_tilt(dir);
  ASSERT_EQ(s.strokes.size(), 2u);
  EXPECT_EQ(s.point_count(), 6u);
  EXPECT_EQ(s.strokes[1].brush, kMarker);

  fs::remove(dir / "data.sketch");
  try {
    read_tilt(dir);
    FAIL() << "accepted without data.sketch";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    EXPECT_NE(std::string(e.what()).find("data.sketch"), std::string::npos);
  }
}

TEST(TiltReader, ZeroPointStrokesSkippedWithWarning) {
  RawStroke empty = raw_stroke(0x1, {0}, 0);
  const ByteVec bytes = simple_tilt(data_sketch({raw_stroke(0x1, {0}), empty, raw_stroke(0x1, {0})}),
                                    kMinimalMetadata);
  Warnings warnings;
  const Sketch s = read_tilt_bytes(bytes, "empty.tilt", &warnings);
  EXPECT_EQ(s.strokes.size(), 2u);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("1 stroke(s) with no control points"), std::string::npos) << warnings[0];
}

TEST(TiltReader, UnknownBrushIndexKeepsStroke) {
  RawStroke s = raw_stroke(0x1, {0});
  s.brush = 9;
  Warnings warnings;
  const Sketch sketch =
      read_tilt_bytes(simple_tilt(data_sketch({s}), kMinimalMetadata), "brush.tilt", &warnings);
  ASSERT_EQ(sketch.strokes.size(), 1u);
  EXPECT_TRUE(sketch.strokes[0].brush.empty());
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("brush"), std::string::npos);
}

TEST(TiltReader, LayerAndSceneTransformsHaveKnownResults) {
  // Point (1, 0, 0) dm on layer 1. Layer: t = (0, 1, 0), 90 degrees about +Y, scale 2 ->
  // (0, 1, -2). Scene: t = (10, 0, 0), scale 0.5 -> (10, 0.5, -1) dm -> (-1, 0.05, -0.1) m.
  const double h = std::sqrt(0.5);
  const nlohmann::json meta = {
      {"BrushIndex", {kMarker}},
      {"SceneTransformInRoomSpace", {{10, 0, 0}, {0, 0, 0, 1}, 0.5}},
      {"Layers", {{{"Name", "Main"}, {"Visible", true}},  // no Transform: identity
                  {{"Name", "L1"}, {"Transform", {{0, 1, 0}, {0, h, 0, h}, 2}}},
                  {{"Name", "L2"}, {"Transform", {{0, 0, 3}, {0, 0, 0, 1}, 0}}}}}};  // scale 0 = 1
  RawStroke on1 = raw_stroke(0x11, {0, 1}, 1);
  on1.points[0] = raw_point(1, 0, 0, 0);
  on1.size = 0.3f;
  RawStroke on2 = raw_stroke(0x11, {0, 2}, 1);
  on2.points[0] = raw_point(1, 0, 0, 0);
  RawStroke on0 = raw_stroke(0x1, {0}, 1);
  on0.points[0] = raw_point(1, 0, 0, 0);
  const Sketch s = read_tilt_bytes(simple_tilt(data_sketch({on1, on2, on0}), meta.dump()), "xf.tilt");
  ASSERT_EQ(s.strokes.size(), 3u);
  EXPECT_LT((s.strokes[0].points[0] - Eigen::Vector3d(-1.0, 0.05, -0.1)).norm(), 1e-7)
      << s.strokes[0].points[0].transpose();
  EXPECT_EQ(s.strokes[0].layer, 1u);
  EXPECT_NEAR(s.strokes[0].width, 0.3 * 2 * 0.5 * 0.1, 1e-8);
  // The pointer's forward (0, 0, 1) turns with the layer to +X (Open Brush), i.e. -X here.
  EXPECT_LT((s.strokes[0].orientations[0] * Eigen::Vector3d::UnitZ() - Eigen::Vector3d(-1, 0, 0)).norm(),
            1e-7);
  // Layer 2: (1, 0, 3) dm, then the scene: (10.5, 0, 1.5) dm.
  EXPECT_LT((s.strokes[1].points[0] - Eigen::Vector3d(-1.05, 0.0, 0.15)).norm(), 1e-7);
  // Layer 0: scene only: (10.5, 0, 0) dm.
  EXPECT_LT((s.strokes[2].points[0] - Eigen::Vector3d(-1.05, 0.0, 0.0)).norm(), 1e-7);
}

TEST(TiltReader, OrientationsAreConvertedToRightHandedFrame) {
  // A pointer turned 90 degrees about +Y in Open Brush points its forward (0,0,1) to +X there,
  // which is -X after the x flip; its up stays +Y.
  RawStroke s = raw_stroke(0x1, {0}, 1);
  const float h = std::sqrt(0.5f);
  s.points[0].qy = h;
  s.points[0].qw = h;
  const Sketch sketch = read_tilt_bytes(simple_tilt(data_sketch({s}), kMinimalMetadata), "o.tilt");
  const Eigen::Quaterniond q = sketch.strokes.at(0).orientations.at(0);
  EXPECT_LT((q * Eigen::Vector3d::UnitZ() - Eigen::Vector3d(-1, 0, 0)).norm(), 1e-6);
  EXPECT_LT((q * Eigen::Vector3d::UnitY() - Eigen::Vector3d(0, 1, 0)).norm(), 1e-6);
}

TEST(TiltReader, MirrorWidgetBecomesMirrorPlane) {
  // The widget's local +X is the plane normal. Widget at (3, 5, 0) dm turned 90 degrees about +Y:
  // normal +X -> -Z in Open Brush, -Z here too; the plane passes through (-0.3, 0.5, 0) m.
  const double h = std::sqrt(0.5);
  const nlohmann::json meta = {{"BrushIndex", {kMarker}},
                               {"Mirror", {{"Transform", {{3, 5, 0}, {0, h, 0, h}, 1}}}}};
  const Sketch s = read_tilt_bytes(simple_tilt(data_sketch({raw_stroke(0x1, {0})}), meta.dump()), "m.tilt");
  ASSERT_TRUE(s.mirror);
  EXPECT_LT((s.mirror->normal.cwiseAbs() - Eigen::Vector3d(0, 0, 1)).norm(), 1e-9);
  EXPECT_NEAR(s.mirror->signed_distance({-0.3, 0.5, 0.0}), 0.0, 1e-9);
  EXPECT_NEAR(std::abs(s.mirror->signed_distance({0, 0, 0.25})), 0.25, 1e-9);

  // An untransformed widget at the origin mirrors x -> -x.
  const nlohmann::json plain = {{"BrushIndex", {kMarker}},
                                {"Mirror", {{"Transform", {{0, 0, 0}, {0, 0, 0, 1}, 1}}}}};
  const Sketch p = read_tilt_bytes(simple_tilt(data_sketch({raw_stroke(0x1, {0})}), plain.dump()), "m.tilt");
  ASSERT_TRUE(p.mirror);
  EXPECT_LT((p.mirror->reflect({0.2, 0.3, 0.4}) - Eigen::Vector3d(-0.2, 0.3, 0.4)).norm(), 1e-12);
}

TEST(TiltReader, HandAssembledFileRoundTripsThroughWriter) {
  const auto dir = scratch_dir();
  const double h = std::sqrt(0.5);
  const nlohmann::json meta = {
      {"BrushIndex", {kMarker, kLight}},
      {"SceneTransformInRoomSpace", {{1, 2, 3}, {0, h, 0, h}, 0.7}},
      {"Mirror", {{"Transform", {{1, 4, 3}, {0, h, 0, h}, 1}}}}};
  RawStroke a = raw_stroke(0xB, {0, std::bit_cast<std::uint32_t>(1.5f), 4}, 6);
  RawStroke b = raw_stroke(0x1, {0}, 3);
  b.brush = 1;
  for (auto& p : b.points) p.time_ms += 100;
  const Sketch first =
      read_tilt_bytes(simple_tilt(data_sketch({a, b}), meta.dump()), "hand.tilt");
  write_tilt(first, dir / "again.tilt");
  expect_same_strokes(first, read_tilt(dir / "again.tilt"));
}

// ---------------------------------------------------------------------------------------------
// Reader: errors.

TEST(TiltReaderErrors, HeaderProblemsNameTheByte) {
  const ByteVec good = simple_tilt(data_sketch({raw_stroke(0x1, {0})}), kMinimalMetadata);
  expect_input_error(ByteVec(good.begin(), good.begin() + 10), "16-byte .tilt header");
  ByteVec magic = good;
  magic[0] = 'X';
  expect_input_error(magic, "byte 0: expected magic");
  ByteVec small = good;
  small[4] = 8;
  expect_input_error(small, "byte 4: header size 8");
  ByteVec version = good;
  version[6] = 2;
  expect_input_error(version, "byte 6: header version 2");
  ByteVec not_zip = good;
  not_zip[17] = 'Q';
  expect_input_error(not_zip, "byte 16: expected a zip local header");
  expect_input_error(tilt_file(ByteVec{'P', 'K', 3, 4}), "zip archive");
}

TEST(TiltReaderErrors, MissingEntriesAndBadJson) {
  const ByteVec sketch = data_sketch({raw_stroke(0x1, {0})});
  expect_input_error(tilt_file(zip_archive({{"metadata.json", bytes_of(kMinimalMetadata), false, {}}})),
                     "no data.sketch");
  expect_input_error(tilt_file(zip_archive({{"data.sketch", sketch, false, {}}})), "metadata.json");
  expect_input_error(simple_tilt(sketch, "{\"BrushIndex\": [}"), "metadata.json: byte");
  expect_input_error(simple_tilt(sketch, "[1, 2]"), "expected a JSON object");
  expect_input_error(simple_tilt(sketch, R"({"BrushIndex": "x"})"), "'BrushIndex'");
  expect_input_error(simple_tilt(sketch, R"({"SceneTransformInRoomSpace": [[0,0],[0,0,0,1],1]})"),
                     "'SceneTransformInRoomSpace'");
  expect_input_error(simple_tilt(sketch, R"({"Layers": [{"Transform": [[0,0,0],[0,0,0,0],1]}]})"),
                     "'Layers[0].Transform': zero rotation");
}

TEST(TiltReaderErrors, DataSketchProblemsNameStrokeAndOffset) {
  auto with_sketch = [](const ByteVec& sketch) { return simple_tilt(sketch, kMinimalMetadata); };
  ByteVec sentinel = data_sketch({raw_stroke(0x1, {0})});
  sentinel[0] = 0;
  expect_input_error(with_sketch(sentinel), "data.sketch: byte 0: expected sentinel");
  expect_input_error(with_sketch(data_sketch({raw_stroke(0x1, {0})}, 4)), "byte 4: unsupported data.sketch version 4");
  ByteVec cut = data_sketch({raw_stroke(0x1, {0}), raw_stroke(0x1, {0})});
  cut.resize(cut.size() - 3);
  expect_input_error(with_sketch(cut), "stroke 1: control point count 3 is impossible");
  ByteVec negative = data_sketch({raw_stroke(0x1, {0})});
  negative[16] = 0xFF, negative[17] = 0xFF, negative[18] = 0xFF, negative[19] = 0xFF;
  expect_input_error(with_sketch(negative), "byte 16: stroke count -1 is impossible");
}

}  // namespace
}  // namespace sketchsurf
