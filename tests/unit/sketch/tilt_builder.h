#pragma once
// Hand assembly of .tilt files byte by byte (../shared/docs/tilt-format.md), for the tests of
// what our writer never produces: Deflate entries, duplicate names, extra header bytes, unknown
// extension bits, absurd counts and sizes. Also a minimal zip parser to inspect written files,
// and the comparison used by every .tilt round trip.

#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "surfacing/sketch/sketch.h"

namespace sketchsurf::testing {

using ByteVec = std::vector<std::uint8_t>;

/// Little-endian byte sink.
struct ByteWriter {
  ByteVec bytes;
  ByteWriter& u16(std::uint16_t v) {
    for (int i = 0; i < 2; ++i) bytes.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
    return *this;
  }
  ByteWriter& u32(std::uint32_t v) {
    for (int i = 0; i < 4; ++i) bytes.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
    return *this;
  }
  ByteWriter& u64(std::uint64_t v) {
    for (int i = 0; i < 8; ++i) bytes.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
    return *this;
  }
  ByteWriter& i32(std::int32_t v) { return u32(std::bit_cast<std::uint32_t>(v)); }
  ByteWriter& f32(float v) { return u32(std::bit_cast<std::uint32_t>(v)); }
  ByteWriter& raw(std::string_view s) {
    bytes.insert(bytes.end(), s.begin(), s.end());
    return *this;
  }
  ByteWriter& raw(const ByteVec& b) {
    bytes.insert(bytes.end(), b.begin(), b.end());
    return *this;
  }
};

inline std::uint32_t read_u32(const ByteVec& b, std::size_t at) {
  return std::uint32_t{b.at(at)} | (std::uint32_t{b.at(at + 1)} << 8) |
         (std::uint32_t{b.at(at + 2)} << 16) | (std::uint32_t{b.at(at + 3)} << 24);
}
inline std::uint16_t read_u16(const ByteVec& b, std::size_t at) {
  return static_cast<std::uint16_t>(b.at(at) | (b.at(at + 1) << 8));
}
inline float read_f32(const ByteVec& b, std::size_t at) { return std::bit_cast<float>(read_u32(b, at)); }

/// One control point as stored in data.sketch (Open Brush frame, decimetres).
struct RawPoint {
  float x = 0, y = 0, z = 0;
  float qx = 0, qy = 0, qz = 0, qw = 1;
  float pressure = 1;
  std::uint32_t time_ms = 0;
};

/// One stroke as stored in data.sketch. `stroke_ext` holds the 4-byte values of set bits 0..15
/// and the payloads of set bits 16..31, in ascending bit order.
struct RawStroke {
  std::int32_t brush = 0;
  float rgba[4] = {1, 0, 0, 1};
  float size = 0.5f;
  std::uint32_t stroke_mask = 0;
  std::uint32_t cp_mask = 0x3;
  std::vector<std::uint32_t> small_ext;   // one per set bit 0..15
  std::vector<std::string> large_ext;     // one per set bit 16..31
  std::vector<RawPoint> points;
};

/// data.sketch bytes: sentinel, version, reserved, `extra` header bytes, strokes.
inline ByteVec data_sketch(const std::vector<RawStroke>& strokes, std::int32_t version = 5,
                           const std::string& extra = "") {
  ByteWriter w;
  w.u32(0xC576A5CD).i32(version).u32(0).u32(static_cast<std::uint32_t>(extra.size())).raw(extra);
  w.i32(static_cast<std::int32_t>(strokes.size()));
  for (const auto& s : strokes) {
    w.i32(s.brush);
    for (float c : s.rgba) w.f32(c);
    w.f32(s.size).u32(s.stroke_mask).u32(s.cp_mask);
    std::size_t small = 0, large = 0;
    for (int bit = 0; bit < 32; ++bit) {
      if (!(s.stroke_mask & (1u << bit))) continue;
      if (bit < 16) {
        w.u32(s.small_ext.at(small++));
      } else {
        const auto& payload = s.large_ext.at(large++);
        w.u32(static_cast<std::uint32_t>(payload.size())).raw(payload);
      }
    }
    w.i32(static_cast<std::int32_t>(s.points.size()));
    for (const auto& p : s.points) {
      w.f32(p.x).f32(p.y).f32(p.z).f32(p.qx).f32(p.qy).f32(p.qz).f32(p.qw);
      for (int bit = 0; bit < 32; ++bit) {
        if (!(s.cp_mask & (1u << bit))) continue;
        if (bit == 0) w.f32(p.pressure);
        else if (bit == 1) w.u32(p.time_ms);
        else w.u32(0xDEADBEEF);
      }
    }
  }
  return w.bytes;
}

struct ZipEntry {
  std::string name;
  ByteVec data;
  bool deflate = false;
  std::optional<std::uint64_t> claimed_size;  ///< lie about the uncompressed size (Zip64 if >= 4 GiB)
};

inline ByteVec bytes_of(std::string_view s) { return ByteVec(s.begin(), s.end()); }

inline ByteVec raw_deflate(const ByteVec& in) {
  z_stream zs{};
  if (deflateInit2(&zs, Z_BEST_COMPRESSION, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY) != Z_OK)
    throw std::runtime_error("deflateInit2");
  ByteVec out(deflateBound(&zs, in.size()));
  zs.next_in = const_cast<Bytef*>(in.data());
  zs.avail_in = static_cast<uInt>(in.size());
  zs.next_out = out.data();
  zs.avail_out = static_cast<uInt>(out.size());
  const int rc = deflate(&zs, Z_FINISH);
  out.resize(zs.total_out);
  deflateEnd(&zs);
  if (rc != Z_STREAM_END) throw std::runtime_error("deflate");
  return out;
}

/// A zip archive written by hand (no data descriptors). Offsets count from the archive's first
/// byte plus `offset_base` (0 = the app's convention; 16 = counted from the start of the .tilt).
/// Duplicate names are written as given.
inline ByteVec zip_archive(const std::vector<ZipEntry>& entries, std::uint32_t offset_base = 0) {
  ByteWriter out, dir;
  for (const auto& e : entries) {
    const ByteVec body = e.deflate ? raw_deflate(e.data) : e.data;
    const auto crc = static_cast<std::uint32_t>(crc32(0, e.data.data(), static_cast<uInt>(e.data.size())));
    const std::uint64_t size = e.claimed_size.value_or(e.data.size());
    const bool zip64 = size >= 0xFFFFFFFFull;
    const auto size32 = zip64 ? 0xFFFFFFFFu : static_cast<std::uint32_t>(size);
    const auto offset = static_cast<std::uint32_t>(out.bytes.size()) + offset_base;
    const std::uint16_t method = e.deflate ? 8 : 0;
    out.u32(0x04034b50).u16(20).u16(0).u16(method).u16(0).u16(0x21).u32(crc);
    out.u32(static_cast<std::uint32_t>(body.size())).u32(size32);
    out.u16(static_cast<std::uint16_t>(e.name.size())).u16(0).raw(e.name).raw(body);
    dir.u32(0x02014b50).u16(20).u16(zip64 ? 45 : 20).u16(0).u16(method).u16(0).u16(0x21).u32(crc);
    dir.u32(static_cast<std::uint32_t>(body.size())).u32(size32);
    dir.u16(static_cast<std::uint16_t>(e.name.size())).u16(zip64 ? 12 : 0).u16(0).u16(0).u16(0);
    dir.u32(0).u32(offset).raw(e.name);
    if (zip64) dir.u16(0x0001).u16(8).u64(size);
  }
  const auto dir_offset = static_cast<std::uint32_t>(out.bytes.size()) + offset_base;
  const auto dir_size = static_cast<std::uint32_t>(dir.bytes.size());
  out.raw(dir.bytes);
  const auto n = static_cast<std::uint16_t>(entries.size());
  out.u32(0x06054b50).u16(0).u16(0).u16(n).u16(n).u32(dir_size).u32(dir_offset).u16(0);
  return out.bytes;
}

/// The .tilt header (`header_size` >= 16, padded with zeros) followed by `zip`.
inline ByteVec tilt_file(const ByteVec& zip, std::uint16_t header_size = 16, std::uint16_t version = 1) {
  ByteWriter w;
  w.u32(0x546C6974).u16(header_size).u16(version).u32(0).u32(0);
  while (w.bytes.size() < header_size) w.bytes.push_back(0);
  w.raw(zip);
  return w.bytes;
}

/// The usual three entries: data.sketch, metadata.json and a (fake) thumbnail.
inline ByteVec simple_tilt(const ByteVec& sketch, const std::string& metadata) {
  return tilt_file(zip_archive({{"thumbnail.png", bytes_of("not a png"), false, {}},
                                {"data.sketch", sketch, false, {}},
                                {"metadata.json", bytes_of(metadata), false, {}}}));
}

/// Entries of a Stored-only zip found through its central directory, with offsets counted from
/// the zip's first byte. Throws std::runtime_error if the archive does not follow that layout.
struct ParsedEntry {
  std::string name;
  std::uint16_t method = 0;
  ByteVec data;
};
inline std::vector<ParsedEntry> parse_zip(const ByteVec& zip) {
  if (zip.size() < 22) throw std::runtime_error("too short");
  const std::size_t eocd = zip.size() - 22;  // we never write a comment
  if (read_u32(zip, eocd) != 0x06054b50) throw std::runtime_error("no end of central directory");
  const std::uint16_t n = read_u16(zip, eocd + 10);
  const std::uint32_t dir_size = read_u32(zip, eocd + 12);
  std::size_t at = read_u32(zip, eocd + 16);
  if (at + dir_size != eocd) throw std::runtime_error("central directory offset not zip-relative");
  std::vector<ParsedEntry> out;
  for (std::uint16_t i = 0; i < n; ++i) {
    if (read_u32(zip, at) != 0x02014b50) throw std::runtime_error("bad central directory entry");
    ParsedEntry e;
    e.method = read_u16(zip, at + 10);
    const std::uint32_t csize = read_u32(zip, at + 20);
    const std::uint16_t name_len = read_u16(zip, at + 28), extra = read_u16(zip, at + 30),
                        comment = read_u16(zip, at + 32);
    const std::uint32_t local = read_u32(zip, at + 42);
    e.name.assign(zip.begin() + static_cast<std::ptrdiff_t>(at + 46),
                  zip.begin() + static_cast<std::ptrdiff_t>(at + 46 + name_len));
    if (read_u32(zip, local) != 0x04034b50) throw std::runtime_error("local header not at its offset");
    if (read_u16(zip, local + 6) & 0x8) throw std::runtime_error("data descriptor used");
    const std::size_t data_at = local + 30 + read_u16(zip, local + 26) + read_u16(zip, local + 28);
    e.data.assign(zip.begin() + static_cast<std::ptrdiff_t>(data_at),
                  zip.begin() + static_cast<std::ptrdiff_t>(data_at + csize));
    out.push_back(std::move(e));
    at += 46 + name_len + extra + comment;
  }
  return out;
}

/// A fresh directory for one test.
inline std::filesystem::path scratch_dir() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::filesystem::path dir = std::filesystem::path(::testing::TempDir()) /
                       (std::string("tilt_test_") + info->test_suite_name() + "_" + info->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline ByteVec read_bytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return ByteVec(std::istreambuf_iterator<char>(in), {});
}

/// Same rotation, whatever the sign of the quaternion.
inline double rotation_distance(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return std::min((a.coeffs() - b.coeffs()).norm(), (a.coeffs() + b.coeffs()).norm());
}

/// Positions to 1e-6, orientations to 1e-6, widths relative 1e-6, other attributes exact.
inline void expect_same_strokes(const Sketch& a, const Sketch& b) {
  ASSERT_EQ(a.strokes.size(), b.strokes.size());
  for (std::size_t s = 0; s < a.strokes.size(); ++s) {
    const Stroke& x = a.strokes[s];
    const Stroke& y = b.strokes[s];
    SCOPED_TRACE("stroke " + std::to_string(s));
    ASSERT_EQ(x.size(), y.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
      EXPECT_LT((x.points[i] - y.points[i]).norm(), 1e-6);
      EXPECT_LT(rotation_distance(x.orientations[i], y.orientations[i]), 1e-6);
    }
    EXPECT_EQ(x.pressures, y.pressures);
    EXPECT_EQ(x.timestamps_ms, y.timestamps_ms);
    EXPECT_EQ(x.color, y.color);
    EXPECT_EQ(x.brush, y.brush);
    EXPECT_EQ(x.layer, y.layer);
    EXPECT_NEAR(x.width, y.width, 1e-6 * x.width);
  }
  ASSERT_EQ(a.mirror.has_value(), b.mirror.has_value());
  if (a.mirror) {
    EXPECT_LT((a.mirror->normal - b.mirror->normal).norm(), 1e-6);
    EXPECT_NEAR(a.mirror->offset, b.mirror->offset, 1e-6);
  }
}

}  // namespace sketchsurf::testing
