// The .tilt reader on broken input: every truncation, seeded random corruptions (of the file, of
// data.sketch behind a valid zip, of metadata.json), and absurd counts and sizes that must be
// refused before anything is allocated. The only acceptable outcomes are a Sketch or Error(Input).

#include <gtest/gtest.h>

#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <new>
#include <random>

#include "surfacing/error.h"
#include "surfacing/sketch/io/tilt.h"
#include "tests/unit/sketch/tilt_builder.h"

// The largest single operator-new request since the last reset: shows that an absurd count is
// refused before a buffer is sized from it. Every replaceable form is replaced, so that memory
// from any of them is released by the matching function (AddressSanitizer checks this).
namespace {
std::atomic<std::size_t> g_largest_allocation{0};

void* tracked_alloc(std::size_t n, std::size_t alignment) noexcept {
  std::size_t seen = g_largest_allocation.load(std::memory_order_relaxed);
  while (n > seen && !g_largest_allocation.compare_exchange_weak(seen, n)) {
  }
  if (alignment <= alignof(std::max_align_t)) return std::malloc(n ? n : 1);
  return std::aligned_alloc(alignment, (n + alignment - 1) / alignment * alignment);
}
void* tracked_new(std::size_t n, std::size_t alignment) {
  if (void* p = tracked_alloc(n, alignment)) return p;
  throw std::bad_alloc();
}
}  // namespace

void* operator new(std::size_t n) { return tracked_new(n, 0); }
void* operator new[](std::size_t n) { return tracked_new(n, 0); }
void* operator new(std::size_t n, std::align_val_t a) { return tracked_new(n, std::size_t(a)); }
void* operator new[](std::size_t n, std::align_val_t a) { return tracked_new(n, std::size_t(a)); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept { return tracked_alloc(n, 0); }
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept { return tracked_alloc(n, 0); }
// GCC 12 takes the std::free below for a mismatch with operator new; here they are one family.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { std::free(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { std::free(p); }
#pragma GCC diagnostic pop

namespace sketchsurf {
namespace {

using namespace sketchsurf::testing;

constexpr std::size_t kSmallAllocation = 1 << 20;
constexpr const char* kMetadata =
    R"({"EnvironmentPreset":"ab080599-e465-4a6d-8587-43bf495af68b","BrushIndex":["429ed64a-4e97-4466-84d3-145a861ef684"],"SchemaVersion":2,"Layers":[{"Name":"a"},{"Name":"b","Transform":[[1,2,3],[0,0.6,0,0.8],2]}],"Mirror":{"Transform":[[0,1,0],[0,0,0,1],1]}})";

/// A small project-made .tilt (a few KB): three strokes with every attribute, two layers, mirror.
ByteVec small_tilt() {
  Sketch sketch;
  for (int s = 0; s < 3; ++s) {
    Stroke stroke;
    for (int i = 0; i < 6; ++i) {
      stroke.points.emplace_back(0.1 * i, 0.5 + 0.01 * s, 0.02 * i * i);
      stroke.orientations.push_back(Eigen::Quaterniond(Eigen::AngleAxisd(0.3 * i, Eigen::Vector3d::UnitY())));
      stroke.pressures.push_back(0.1f * i);
      stroke.timestamps_ms.push_back(static_cast<std::uint32_t>(100 * s + 10 * i));
    }
    stroke.width = 0.01;
    stroke.layer = s % 2;
    sketch.strokes.push_back(stroke);
  }
  sketch.mirror = Plane{};
  const auto file = scratch_dir() / "small.tilt";
  write_tilt(sketch, file);
  return read_bytes(file);
}

ByteVec entry(const ByteVec& tilt, const std::string& name) {
  for (auto& e : parse_zip(ByteVec(tilt.begin() + 16, tilt.end())))
    if (e.name == name) return e.data;
  throw std::runtime_error("no entry " + name);
}

/// Reads `bytes`; a Sketch must be internally consistent, any failure must be Error(Input).
/// Returns true when the file was accepted.
bool read_is_safe(const ByteVec& bytes, const std::string& what) {
  try {
    const Sketch sketch = read_tilt_bytes(bytes, "fuzz.tilt");
    for (const auto& stroke : sketch.strokes) {
      EXPECT_FALSE(stroke.points.empty()) << what;
      EXPECT_TRUE(stroke.attributes_consistent()) << what;
    }
    return true;
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input) << what << ": " << e.what();
    EXPECT_NE(std::string(e.what()).find("fuzz.tilt"), std::string::npos) << e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << what << ": not a sketchsurf::Error: " << e.what();
  }
  return false;
}

/// Overwrites 1..8 random bytes with random values.
ByteVec corrupt(ByteVec bytes, std::mt19937& rng) {
  std::uniform_int_distribution<std::size_t> where(0, bytes.size() - 1);
  std::uniform_int_distribution<int> value(0, 255), count(1, 8);
  for (int k = count(rng); k > 0; --k) bytes[where(rng)] = static_cast<std::uint8_t>(value(rng));
  return bytes;
}

/// Expects Error(Input) containing `fragment`, with no allocation above 1 MiB on the way.
void expect_refused_small(const ByteVec& bytes, const std::string& fragment) {
  g_largest_allocation = 0;
  try {
    read_tilt_bytes(bytes, "absurd.tilt");
    ADD_FAILURE() << "accepted";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
  EXPECT_LT(g_largest_allocation.load(), kSmallAllocation);
}

TEST(TiltRobustness, SmallFileReads) {
  const ByteVec file = small_tilt();
  EXPECT_GT(file.size(), 500u);
  EXPECT_LT(file.size(), 8192u);
  EXPECT_EQ(read_tilt_bytes(file, "small.tilt").strokes.size(), 3u);
}

TEST(TiltRobustness, EveryTruncationIsAnInputError) {
  const ByteVec file = small_tilt();
  for (std::size_t length = 0; length < file.size(); ++length) {
    const ByteVec cut(file.begin(), file.begin() + static_cast<std::ptrdiff_t>(length));
    EXPECT_FALSE(read_is_safe(cut, "truncated to " + std::to_string(length)))
        << "truncated to " << length << " bytes was accepted";
  }
}

TEST(TiltRobustness, EveryTruncationOfDataSketchIsAnInputError) {
  // Behind a valid zip, so that the data.sketch parser (not the zip CRC) meets the cut.
  const ByteVec sketch = entry(small_tilt(), "data.sketch");
  for (std::size_t length = 0; length < sketch.size(); ++length) {
    const ByteVec cut(sketch.begin(), sketch.begin() + static_cast<std::ptrdiff_t>(length));
    EXPECT_FALSE(read_is_safe(simple_tilt(cut, kMetadata), "data.sketch cut to " + std::to_string(length)));
  }
}

TEST(TiltRobustness, RandomCorruptionsOfTheFile) {
  const ByteVec file = small_tilt();
  std::mt19937 rng(20240611);
  for (int trial = 0; trial < 300; ++trial) read_is_safe(corrupt(file, rng), "file trial " + std::to_string(trial));
}

TEST(TiltRobustness, RandomCorruptionsOfDataSketch) {
  const ByteVec sketch = entry(small_tilt(), "data.sketch");
  std::mt19937 rng(7);
  int accepted = 0;
  for (int trial = 0; trial < 300; ++trial)
    accepted += read_is_safe(simple_tilt(corrupt(sketch, rng), kMetadata),
                             "data.sketch trial " + std::to_string(trial));
  // Most bytes are coordinates, so many corruptions still give a sketch; some hit the structure.
  EXPECT_GT(accepted, 0);
  EXPECT_LT(accepted, 300);
}

TEST(TiltRobustness, RandomCorruptionsOfMetadata) {
  const ByteVec tilt = small_tilt();
  const ByteVec sketch = entry(tilt, "data.sketch");
  const ByteVec meta = bytes_of(kMetadata);
  std::mt19937 rng(11);
  for (int trial = 0; trial < 200; ++trial) {
    const ByteVec bad = corrupt(meta, rng);
    read_is_safe(simple_tilt(sketch, std::string(bad.begin(), bad.end())),
                 "metadata trial " + std::to_string(trial));
  }
}

TEST(TiltRobustness, MetadataNumbersTooLargeForADoubleAreAnInputError) {
  // Found by fuzz_tilt_dir (tools/fuzz): the JSON parser's number overflow escaped as
  // nlohmann::json::out_of_range instead of an Error naming the file.
  const ByteVec sketch = entry(small_tilt(), "data.sketch");
  const std::string number = "0.8" + std::string(5000, '1') + "e3056791760";
  EXPECT_FALSE(read_is_safe(simple_tilt(sketch, R"({"SceneTransformInRoomSpace": [)" + number + "]}"),
                            "metadata number overflow"));
  try {
    read_tilt_bytes(simple_tilt(sketch, R"({"x": 1e400})"), "fuzz.tilt");
    ADD_FAILURE() << "accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("fuzz.tilt/metadata.json: invalid JSON"), std::string::npos)
        << e.what();
  }
  try {
    read_tilt_bytes(simple_tilt(sketch, "{\"x\": " + number + "}"), "fuzz.tilt");
    ADD_FAILURE() << "accepted";
  } catch (const Error& e) {
    EXPECT_LT(std::string(e.what()).size(), 300u) << "the number is quoted cut";
  }
}

TEST(TiltRobustness, AbsurdCountsAreRefusedBeforeAllocating) {
  RawStroke stroke;
  stroke.stroke_mask = 0x1;
  stroke.small_ext = {0};
  stroke.points.resize(2);
  const ByteVec good = data_sketch({stroke});
  // Header (20 bytes), brush + RGBA + size + masks (32), Flags (4), then the point count.
  constexpr std::size_t kPointCountAt = 20 + 32 + 4;
  auto patched = [&](std::size_t at, std::uint32_t value) {
    ByteVec b = good;
    for (int i = 0; i < 4; ++i) b[at + i] = static_cast<std::uint8_t>(value >> (8 * i));
    return simple_tilt(b, kMetadata);
  };
  expect_refused_small(patched(16, 0x7FFFFFFF), "stroke count 2147483647 is impossible");
  expect_refused_small(patched(16, 0x80000000), "stroke count -2147483648 is impossible");
  expect_refused_small(patched(12, 0xFFFFFFF0), "extra header bytes");
  expect_refused_small(patched(kPointCountAt, 0x7FFFFFFF), "control point count 2147483647 is impossible");

  RawStroke big_extension = stroke;
  big_extension.stroke_mask = 0x1 | (1u << 20);
  big_extension.large_ext = {"x"};
  ByteVec b = data_sketch({big_extension});
  for (int i = 0; i < 4; ++i) b[kPointCountAt + i] = 0xFF;  // now the bit-20 extension length
  expect_refused_small(simple_tilt(b, kMetadata), "variable stroke extension");
}

TEST(TiltRobustness, ImplausibleZipEntrySizesAreRefusedBeforeReading) {
  const ByteVec sketch = data_sketch({});
  auto tilt_claiming = [&](std::uint64_t size, bool deflate) {
    return tilt_file(zip_archive({{"data.sketch", sketch, deflate, size},
                                  {"metadata.json", bytes_of(kMetadata), false, {}}}));
  };
  expect_refused_small(tilt_claiming(100'000'000'000ull, false), "refused as implausible");  // Zip64
  expect_refused_small(tilt_claiming(100'000'000'000ull, true), "refused as implausible");
  expect_refused_small(tilt_claiming(3'000'000'000ull, true), "refused as implausible");
  expect_refused_small(tilt_claiming(900'000'000ull, true), "refused as implausible");  // ratio
  expect_refused_small(tilt_claiming(sketch.size() + 1, false), "refused as implausible");  // Stored
}

}  // namespace
}  // namespace sketchsurf
