// Open Brush .tilt reader and writer. Byte layout: ../shared/docs/tilt-format.md (sections cited).
//
// Decisions recorded here:
// - Zip entries are found by exact name first, then case-insensitively; with duplicate names the
//   first entry in the central directory wins (what libzip's own lookup does).
// - The zip is handed to libzip from `headerSize` on (app-written files count offsets from there,
//   section 1 "offset skew"); if that fails the whole file is tried, for zips whose offsets count
//   from the start of the file (written by generic tools appending to the header).
// - Sizes are checked before anything is allocated: stroke and point counts against the bytes left,
//   zip entries against 1 GiB and against their compressed size (Deflate cannot exceed ~1032:1).
// - The writer never writes a stroke with fewer than 2 points (section 5): zero-point strokes are
//   left out, a one-point stroke gets its point twice. Missing widths become kDefaultWidthM,
//   missing pressures 1, missing orientations identity, missing timestamps are synthesised.

#include "surfacing/sketch/io/tilt.h"

#include <zip.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "surfacing/error.h"
#include "surfacing/sketch/io/atomic_file.h"
#include "surfacing/sketch/io/input_limits.h"
#include "surfacing/sketch/io/text_io.h"

namespace sketchsurf {

namespace {

namespace fs = std::filesystem;
using Bytes = std::span<const std::uint8_t>;

constexpr std::uint32_t kMagic = 0x546C6974;     // bytes 74 69 6C 54, "tilT"
constexpr std::uint32_t kSentinel = 0xC576A5CD;  // first u32 of data.sketch
constexpr std::size_t kHeaderBytes = 16;
constexpr std::uint16_t kHeaderVersion = 1;
constexpr std::int32_t kSketchVersion = 5;
constexpr std::uint64_t kMaxDeflateRatio = 1100;  // Deflate's best case is ~1032:1
constexpr std::size_t kStrokeFixedBytes = 36;  // brush, RGBA, size, 2 masks, point count
constexpr std::size_t kPointFixedBytes = 28;   // position + orientation
constexpr double kUnitsToMetres = 0.1;         // 1 Open Brush unit = 1 decimetre (section 3)
constexpr double kDefaultWidthM = 0.01;        // written when a stroke has no width
constexpr std::uint32_t kSynthesisedStepMs = 11;  // ~90 Hz, the app's sampling rate
constexpr std::uint32_t kMaxWrittenLayers = 4096;
constexpr const char* kLightBrush = "2241cd32-8ba2-48a5-9ee7-2caef7e9ed62";
constexpr const char* kDefaultEnvironment = "ab080599-e465-4a6d-8587-43bf495af68b";

// A 256 x 256 dark grey PNG (RGB 40,40,48), made once with Python's zlib; Open Brush shows it in
// its sketch list.
constexpr std::uint8_t kThumbnailPng[] = {
    0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44,
    0x52, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x00, 0x08, 0x02, 0x00, 0x00, 0x00, 0xd3,
    0x10, 0x3f, 0x31, 0x00, 0x00, 0x01, 0xff, 0x49, 0x44, 0x41, 0x54, 0x78, 0xda, 0xed, 0xd3,
    0x31, 0x0d, 0x00, 0x00, 0x0c, 0xc3, 0xb0, 0xc2, 0xe9, 0x39, 0xfe, 0xe8, 0x76, 0x0f, 0xc3,
    0x2c, 0x19, 0x41, 0xa4, 0xa4, 0x1d, 0x78, 0x2b, 0x12, 0x60, 0x00, 0x30, 0x00, 0x18, 0x00,
    0x0c, 0x00, 0x06, 0x00, 0x03, 0x80, 0x01, 0xc0, 0x00, 0x60, 0x00, 0x30, 0x00, 0x18, 0x00,
    0x0c, 0x00, 0x06, 0x00, 0x03, 0x80, 0x01, 0xc0, 0x00, 0x60, 0x00, 0x30, 0x00, 0x18, 0x00,
    0x0c, 0x00, 0x06, 0x00, 0x03, 0x80, 0x01, 0xc0, 0x00, 0x60, 0x00, 0x30, 0x00, 0x18, 0x00,
    0x0c, 0x00, 0x06, 0x00, 0x03, 0x80, 0x01, 0xc0, 0x00, 0x60, 0x00, 0x30, 0x00, 0x18, 0x00,
    0x0c, 0x00, 0x06, 0x00, 0x03, 0x80, 0x01, 0xc0, 0x00, 0x60, 0x00, 0x30, 0x00, 0x18, 0x00,
    0x03, 0xa8, 0x80, 0x01, 0xc0, 0x00, 0x60, 0x00, 0x30, 0x00, 0x18, 0x00, 0x0c, 0x00, 0x06,
    0x00, 0x03, 0x80, 0x01, 0xc0, 0x00, 0x60, 0x00, 0x30, 0x00, 0x18, 0x00, 0x0c, 0x00, 0x06,
    0x00, 0x03, 0x80, 0x01, 0xc0, 0x00, 0x60, 0x00, 0x30, 0x00, 0x18, 0x00, 0x0c, 0x00, 0x06,
    0x00, 0x03, 0x80, 0x01, 0xc0, 0x00, 0x60, 0x00, 0x30, 0x00, 0x18, 0x00, 0x0c, 0x00, 0x06,
    0x00, 0x03, 0x80, 0x01, 0xc0, 0x00, 0x60, 0x00, 0x30, 0x00, 0x18, 0x00, 0x0c, 0x00, 0x06,
    0x00, 0x03, 0x80, 0x01, 0xc0, 0x00, 0x60, 0x00, 0x30, 0x00, 0x18, 0x00, 0x0c, 0x00, 0x06,
    0x00, 0x03, 0x80, 0x01, 0xc0, 0x00, 0x60, 0x00, 0x0c, 0x00, 0x06, 0x00, 0x03, 0x80, 0x01,
    0xc0, 0x00, 0x60, 0x00, 0x30, 0x00, 0x18, 0x00, 0x0c, 0x00, 0x06, 0x00, 0x03, 0x80, 0x01,
    0xc0, 0x00, 0x60, 0x00, 0x30, 0x00, 0x18, 0x00, 0x0c, 0x00, 0x06, 0x00, 0x03, 0x80, 0x01,
    0xc0, 0x00, 0x60, 0x00, 0x30, 0x00, 0x18, 0x00, 0x0c, 0x00, 0x06, 0x00, 0x03, 0x80, 0x01,
    0xc0, 0x00, 0x60, 0x00, 0x30, 0x00, 0x18, 0x00, 0x0c, 0x00, 0x06, 0x00, 0x03, 0x80, 0x01,
    0xc0, 0x00, 0x60, 0x00, 0x30, 0x00, 0x18, 0x00, 0x0c, 0x00, 0x06, 0x00, 0x03, 0x60, 0x00,
    0x15, 0x30, 0x00, 0x18, 0x00, 0x0c, 0x00, 0x06, 0x00, 0x03, 0x80, 0x01, 0xc0, 0x00, 0x60,
    0x00, 0x30, 0x00, 0x18, 0x00, 0x0c, 0x00, 0x06, 0x00, 0x03, 0x80, 0x01, 0xc0, 0x00, 0x60,
    0x00, 0x30, 0x00, 0x18, 0x00, 0x0c, 0x00, 0x06, 0x00, 0x03, 0x80, 0x01, 0xc0, 0x00, 0x60,
    0x00, 0x30, 0x00, 0x18, 0x00, 0x0c, 0x00, 0x06, 0x00, 0x03, 0x80, 0x01, 0xc0, 0x00, 0x60,
    0x00, 0x30, 0x00, 0x18, 0x00, 0x0c, 0x00, 0x06, 0x00, 0x03, 0x80, 0x01, 0xc0, 0x00, 0x60,
    0x00, 0x30, 0x00, 0x18, 0x00, 0x0c, 0x80, 0x01, 0xc0, 0x00, 0x60, 0x00, 0x30, 0x00, 0x18,
    0x00, 0x0c, 0x00, 0x06, 0x00, 0x03, 0x80, 0x01, 0xc0, 0x00, 0x60, 0x00, 0x30, 0x00, 0x18,
    0x00, 0x0c, 0x00, 0x06, 0x00, 0x03, 0x80, 0x01, 0xc0, 0x00, 0x60, 0x00, 0x30, 0x00, 0x18,
    0x00, 0x0c, 0x00, 0x06, 0x00, 0x03, 0x80, 0x01, 0xc0, 0x00, 0x60, 0x00, 0x30, 0x00, 0x18,
    0x00, 0x0c, 0x00, 0x06, 0x00, 0x03, 0x80, 0x01, 0xc0, 0x00, 0x60, 0x00, 0x30, 0x00, 0x18,
    0x00, 0x0c, 0x00, 0x06, 0x00, 0x03, 0x80, 0x01, 0xc0, 0x00, 0x60, 0x00, 0x30, 0x00, 0x18,
    0x00, 0x0c, 0x00, 0x06, 0x00, 0x03, 0xc0, 0xb5, 0x69, 0xb1, 0x07, 0x81, 0xa7, 0xd6, 0x62,
    0x80, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};

// ----------------------------------------------------------------------------------------------
// Little-endian primitives.

std::uint16_t load_u16(const std::uint8_t* p) {
  return static_cast<std::uint16_t>(p[0] | (p[1] << 8));
}
std::uint32_t load_u32(const std::uint8_t* p) {
  return std::uint32_t{p[0]} | (std::uint32_t{p[1]} << 8) | (std::uint32_t{p[2]} << 16) |
         (std::uint32_t{p[3]} << 24);
}
float load_f32(const std::uint8_t* p) { return std::bit_cast<float>(load_u32(p)); }

void put_u16(std::vector<std::uint8_t>& out, std::uint16_t v) {
  out.push_back(static_cast<std::uint8_t>(v));
  out.push_back(static_cast<std::uint8_t>(v >> 8));
}
void put_u32(std::vector<std::uint8_t>& out, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
}
void put_i32(std::vector<std::uint8_t>& out, std::int32_t v) {
  put_u32(out, std::bit_cast<std::uint32_t>(v));
}
void put_f32(std::vector<std::uint8_t>& out, float v) { put_u32(out, std::bit_cast<std::uint32_t>(v)); }

/// Bounds-checked cursor over data.sketch. Every failure names the byte offset, the stroke being
/// read (if any) and what was expected there.
class ByteReader {
 public:
  ByteReader(Bytes bytes, fs::path name) : bytes_(bytes), name_(std::move(name)) {}

  std::size_t offset() const { return pos_; }
  std::size_t remaining() const { return bytes_.size() - pos_; }
  const std::uint8_t* here() const { return bytes_.data() + pos_; }
  void set_stroke(std::int64_t stroke) { stroke_ = stroke; }

  [[noreturn]] void fail_at(std::size_t offset, const std::string& what) const {
    const std::string where = stroke_ >= 0 ? "stroke " + std::to_string(stroke_) + ": " : "";
    throw Error::input_at_byte(name_, offset, where + what);
  }
  void need(std::size_t n, const char* what) const {
    if (remaining() < n)
      fail_at(pos_, std::string("expected ") + what + " (" + std::to_string(n) +
                        " bytes), but only " + std::to_string(remaining()) + " bytes remain");
  }
  std::uint32_t u32(const char* what) {
    need(4, what);
    const auto v = load_u32(here());
    pos_ += 4;
    return v;
  }
  std::int32_t i32(const char* what) { return std::bit_cast<std::int32_t>(u32(what)); }
  float f32(const char* what) { return std::bit_cast<float>(u32(what)); }
  void skip(std::size_t n, const char* what) {
    need(n, what);
    pos_ += n;
  }

 private:
  Bytes bytes_;
  fs::path name_;
  std::size_t pos_ = 0;
  std::int64_t stroke_ = -1;
};

// ----------------------------------------------------------------------------------------------
// Transforms (section 3): p' = t + q * (s * p), in Open Brush's left-handed decimetre frame.

struct Transform {
  Eigen::Vector3d t = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  double s = 1.0;
};

/// a ∘ b: first b, then a.
Transform compose(const Transform& a, const Transform& b) {
  return {a.t + a.s * (a.q * b.t), a.q * b.q, a.s * b.s};
}

/// Open Brush's left-handed frame <-> our right-handed one: (x, y, z) -> (-x, y, z) (metres are a
/// further factor 0.1). For rotations this is conjugation by diag(-1, 1, 1), which on a
/// quaternion (x, y, z, w) gives (x, -y, -z, w). Both are their own inverse, so the writer uses
/// the same two functions.
Eigen::Vector3d flip_x(const Eigen::Vector3d& v) { return {-v.x(), v.y(), v.z()}; }
Eigen::Quaterniond flip_rotation(const Eigen::Quaterniond& q) {
  return Eigen::Quaterniond(q.w(), q.x(), -q.y(), -q.z());
}

/// A transform applied to raw data.sketch values, with the conversion to right-handed metres
/// folded in: point -> offset + linear * point, orientation -> rotation * flip(orientation).
struct PointMap {
  Eigen::Matrix3d linear;
  Eigen::Vector3d offset;
  Eigen::Quaterniond rotation;
  double width_scale = 1.0;

  explicit PointMap(const Transform& room_from_canvas) {
    const Eigen::Matrix3d flip = Eigen::Vector3d(-kUnitsToMetres, kUnitsToMetres, kUnitsToMetres)
                                     .asDiagonal();
    linear = flip * room_from_canvas.q.toRotationMatrix() * room_from_canvas.s;
    offset = flip * room_from_canvas.t;
    rotation = flip_rotation(room_from_canvas.q);
    width_scale = std::abs(room_from_canvas.s) * kUnitsToMetres;
  }
};

// ----------------------------------------------------------------------------------------------
// metadata.json (section 3).

struct Metadata {
  std::vector<std::string> brushes;            // BrushIndex
  Transform scene;                             // SceneTransformInRoomSpace
  std::vector<Transform> layers;               // Layers[i].Transform
  std::optional<Transform> mirror;             // Mirror.Transform, room space
};

double json_number(const nlohmann::json& j, const fs::path& where, const std::string& field) {
  if (!j.is_number()) throw Error::input(where, "field '" + field + "': expected a number");
  const double v = j.get<double>();
  if (!std::isfinite(v)) throw Error::input(where, "field '" + field + "': not a finite number");
  return v;
}

Transform json_transform(const nlohmann::json& j, const fs::path& where, const std::string& field) {
  const std::string expected =
      "field '" + field + "': expected [[tx,ty,tz],[qx,qy,qz,qw],scale]";
  if (!j.is_array() || j.size() < 2 || j.size() > 3 || !j[0].is_array() || j[0].size() != 3 ||
      !j[1].is_array() || j[1].size() != 4)
    throw Error::input(where, expected);
  Transform xf;
  for (int i = 0; i < 3; ++i) xf.t[i] = json_number(j[0][i], where, field);
  Eigen::Vector4d q;
  for (int i = 0; i < 4; ++i) q[i] = json_number(j[1][i], where, field);
  if (q.norm() < 1e-6) throw Error::input(where, "field '" + field + "': zero rotation quaternion");
  q.normalize();
  xf.q = Eigen::Quaterniond(q[3], q[0], q[1], q[2]);
  // Open Brush writes scale 0 for layers whose transform was never set: it means 1.
  if (j.size() == 3) xf.s = json_number(j[2], where, field);
  if (xf.s == 0.0) xf.s = 1.0;
  return xf;
}

Metadata parse_metadata(std::string_view text, const fs::path& where) {
  nlohmann::json j;
  try {
    j = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error& e) {
    throw Error::input_at_byte(where, e.byte, "invalid JSON: " + io_detail::excerpt(e.what()));
  } catch (const nlohmann::json::exception& e) {  // a number too large for a double
    throw Error::input(where, "invalid JSON: " + io_detail::excerpt(e.what()));
  }
  if (!j.is_object()) throw Error::input(where, "expected a JSON object");
  Metadata meta;
  if (auto it = j.find("BrushIndex"); it != j.end()) {
    if (!it->is_array()) throw Error::input(where, "field 'BrushIndex': expected a list of GUIDs");
    for (const auto& guid : *it) {
      if (!guid.is_string()) throw Error::input(where, "field 'BrushIndex': expected GUID strings");
      meta.brushes.push_back(guid.get<std::string>());
    }
  }
  if (auto it = j.find("SceneTransformInRoomSpace"); it != j.end() && !it->is_null())
    meta.scene = json_transform(*it, where, "SceneTransformInRoomSpace");
  if (auto it = j.find("Layers"); it != j.end() && !it->is_null()) {
    if (!it->is_array()) throw Error::input(where, "field 'Layers': expected a list");
    for (std::size_t i = 0; i < it->size(); ++i) {
      const auto& layer = (*it)[i];
      const std::string field = "Layers[" + std::to_string(i) + "]";
      if (!layer.is_object()) throw Error::input(where, "field '" + field + "': expected an object");
      auto xf = layer.find("Transform");
      meta.layers.push_back(xf == layer.end() || xf->is_null()
                                ? Transform{}
                                : json_transform(*xf, where, field + ".Transform"));
    }
  }
  if (auto it = j.find("Mirror"); it != j.end() && !it->is_null()) {
    if (!it->is_object()) throw Error::input(where, "field 'Mirror': expected an object");
    if (auto xf = it->find("Transform"); xf != it->end() && !xf->is_null())
      meta.mirror = json_transform(*xf, where, "Mirror.Transform");
  }
  return meta;
}

/// The mirror widget's plane in right-handed metres. Open Brush's SymmetryWidget defines
/// `ReflectionPlane => new Plane(transform.right, transform.position)` (Assets/Scripts/Widgets/
/// SymmetryWidget.cs), so the plane normal is the widget's local +X axis and the plane passes
/// through the widget's position. The saved Mirror.Transform is in room space (format doc section
/// 3; in the real files its rotation equals the scene's, i.e. an untouched widget at the scene
/// origin), so the scene transform is not applied again.
Plane mirror_plane(const Transform& widget) {
  Plane plane;
  plane.normal = flip_x(widget.q * Eigen::Vector3d::UnitX()).normalized();
  plane.offset = -plane.normal.dot(flip_x(widget.t) * kUnitsToMetres);
  return plane;
}

// ----------------------------------------------------------------------------------------------
// data.sketch (section 2).

Sketch parse_data_sketch(Bytes data, const fs::path& where, const Metadata& meta,
                         Warnings* warnings) {
  ByteReader r(data, where);
  if (r.u32("sentinel 0xC576A5CD") != kSentinel)
    r.fail_at(0, "expected sentinel bytes CD A5 76 C5 (not a data.sketch)");
  const std::int32_t version = r.i32("version");
  if (version < kSketchVersion || version > kSketchVersion + 1)
    r.fail_at(4, "unsupported data.sketch version " + std::to_string(version) + " (expected 5 or 6)");
  r.u32("reserved word");
  const std::uint32_t extra = r.u32("extra header size");
  r.skip(extra, "extra header bytes");
  const std::size_t count_at = r.offset();
  const std::int32_t num_strokes = r.i32("stroke count");
  if (num_strokes < 0 || static_cast<std::size_t>(num_strokes) > r.remaining() / kStrokeFixedBytes)
    r.fail_at(count_at, "stroke count " + std::to_string(num_strokes) + " is impossible: " +
                            std::to_string(r.remaining()) + " bytes remain and a stroke takes at least " +
                            std::to_string(kStrokeFixedBytes));

  // Room space = Scene ∘ Layer[i] ∘ p; strokes on a layer the metadata does not list get the
  // scene transform alone.
  std::vector<PointMap> maps;
  for (const auto& layer : meta.layers) maps.emplace_back(compose(meta.scene, layer));
  const PointMap scene_only(meta.scene);

  Sketch sketch;
  sketch.strokes.reserve(static_cast<std::size_t>(num_strokes));
  std::size_t empty_strokes = 0, unknown_brushes = 0, unknown_layers = 0;
  PointBudget budget(where);
  for (std::int32_t s = 0; s < num_strokes; ++s) {
    r.set_stroke(s);
    Stroke stroke;
    const std::int32_t brush = r.i32("brush index");
    for (auto& c : stroke.color) c = r.f32("RGBA colour");
    const float brush_size = r.f32("brush size");
    const std::uint32_t stroke_mask = r.u32("stroke extension mask");
    const std::uint32_t cp_mask = r.u32("control point extension mask");
    float brush_scale = 1.0f;
    for (int bit = 0; bit < 32; ++bit) {
      if (!(stroke_mask & (std::uint32_t{1} << bit))) continue;
      if (bit < 16) {
        const std::uint32_t value = r.u32("4-byte stroke extension");
        if (bit == 1) brush_scale = std::bit_cast<float>(value);  // Scale
        if (bit == 4) stroke.layer = value;                       // Layer
      } else {
        const std::uint32_t length = r.u32("length of a variable stroke extension");
        r.skip(length, "variable stroke extension bytes");
      }
    }
    const std::size_t points_at = r.offset();
    const std::int32_t n = r.i32("control point count");
    const std::size_t point_bytes = kPointFixedBytes + 4 * std::popcount(cp_mask);
    if (n < 0 || static_cast<std::size_t>(n) > r.remaining() / point_bytes)
      r.fail_at(points_at, "control point count " + std::to_string(n) + " is impossible: " +
                               std::to_string(r.remaining()) + " bytes remain and a point takes " +
                               std::to_string(point_bytes));
    if (n == 0) {
      ++empty_strokes;
      continue;
    }

    if (brush >= 0 && static_cast<std::size_t>(brush) < meta.brushes.size())
      stroke.brush = meta.brushes[static_cast<std::size_t>(brush)];
    else
      ++unknown_brushes;
    const bool layer_known = stroke.layer < maps.size();
    if (!layer_known && stroke.layer != 0) ++unknown_layers;
    const PointMap& map = layer_known ? maps[stroke.layer] : scene_only;
    const double width = double{brush_size} * double{brush_scale} * map.width_scale;
    stroke.width = std::isfinite(width) ? std::abs(width) : 0.0;

    // Attribute slots: 4 bytes per set cpExtMask bit, in ascending bit order.
    const bool has_pressure = cp_mask & 1u;
    const bool has_time = cp_mask & 2u;
    const std::size_t time_at = kPointFixedBytes + (has_pressure ? 4 : 0);
    const auto count = static_cast<std::size_t>(n);
    budget.take(count);
    stroke.points.resize(count);
    stroke.orientations.resize(count);
    if (has_pressure) stroke.pressures.resize(count);
    if (has_time) stroke.timestamps_ms.resize(count);
    const std::uint8_t* p = r.here();
    for (std::size_t i = 0; i < count; ++i, p += point_bytes) {
      const Eigen::Vector3d raw(load_f32(p), load_f32(p + 4), load_f32(p + 8));
      stroke.points[i] = map.offset + map.linear * raw;
      const Eigen::Quaterniond q(load_f32(p + 24), load_f32(p + 12), load_f32(p + 16),
                                 load_f32(p + 20));
      stroke.orientations[i] = map.rotation * flip_rotation(q);
      if (has_pressure) stroke.pressures[i] = load_f32(p + kPointFixedBytes);
      if (has_time) stroke.timestamps_ms[i] = load_u32(p + time_at);
    }
    r.skip(count * point_bytes, "control points");
    sketch.strokes.push_back(std::move(stroke));
  }
  r.set_stroke(-1);

  if (warnings) {
    if (empty_strokes)
      warnings->push_back(where.string() + ": skipped " + std::to_string(empty_strokes) +
                          " stroke(s) with no control points");
    if (unknown_brushes)
      warnings->push_back(where.string() + ": " + std::to_string(unknown_brushes) +
                          " stroke(s) use a brush index outside BrushIndex (kept, brush unknown)");
    if (unknown_layers)
      warnings->push_back(where.string() + ": " + std::to_string(unknown_layers) +
                          " stroke(s) are on a layer metadata does not list (scene transform only)");
    if (r.remaining())
      warnings->push_back(where.string() + ": ignored " + std::to_string(r.remaining()) +
                          " byte(s) after the last stroke");
  }
  if (meta.mirror) sketch.mirror = mirror_plane(*meta.mirror);
  return sketch;
}

// ----------------------------------------------------------------------------------------------
// The zip container (section 1).

struct TiltEntries {
  std::vector<std::uint8_t> sketch;   // data.sketch
  std::string metadata;               // metadata.json, or main.json in legacy files
  std::string metadata_entry = "metadata.json";
};

struct ZipDiscard {
  void operator()(zip_t* za) const { zip_discard(za); }
};
using ZipArchive = std::unique_ptr<zip_t, ZipDiscard>;
struct ZipFileClose {
  void operator()(zip_file_t* f) const { zip_fclose(f); }
};
struct ZipSourceFree {
  void operator()(zip_source_t* s) const { zip_source_free(s); }
};
using ZipSource = std::unique_ptr<zip_source_t, ZipSourceFree>;

/// Opens a read-only zip over `bytes` (not copied); nullptr and a reason on failure.
ZipArchive open_zip(Bytes bytes, std::string* why) {
  zip_error_t error;
  zip_error_init(&error);
  ZipSource source(zip_source_buffer_create(bytes.data(), bytes.size(), 0, &error));
  zip_t* za = source ? zip_open_from_source(source.get(), ZIP_RDONLY, &error) : nullptr;
  if (za) source.release();  // the archive owns it now
  else *why = zip_error_strerror(&error);
  zip_error_fini(&error);
  return ZipArchive(za);
}

bool iequals(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) ==
                  std::tolower(static_cast<unsigned char>(y));
         });
}

/// Index of the first entry called `name` (exact match preferred over a case-insensitive one).
std::optional<zip_uint64_t> find_entry(zip_t* za, std::string_view name) {
  const zip_int64_t n = zip_get_num_entries(za, 0);
  std::optional<zip_uint64_t> loose;
  for (zip_int64_t i = 0; i < n; ++i) {
    const char* entry = zip_get_name(za, static_cast<zip_uint64_t>(i), ZIP_FL_ENC_RAW);
    if (!entry) continue;
    if (name == entry) return static_cast<zip_uint64_t>(i);
    if (!loose && iequals(name, entry)) loose = static_cast<zip_uint64_t>(i);
  }
  return loose;
}

/// Reads one entry whole, after checking that its claimed size is plausible.
template <class Buffer>
Buffer read_entry(zip_t* za, zip_uint64_t index, std::uint64_t zip_bytes, const fs::path& name,
                  const std::string& entry) {
  zip_stat_t st;
  zip_stat_init(&st);
  if (zip_stat_index(za, index, 0, &st) != 0)
    throw Error::input(name, "zip entry " + entry + ": " + zip_strerror(za));
  constexpr auto kNeeded = ZIP_STAT_SIZE | ZIP_STAT_COMP_SIZE | ZIP_STAT_COMP_METHOD;
  if ((st.valid & kNeeded) != kNeeded)
    throw Error::input(name, "zip entry " + entry + ": sizes or compression method missing");
  if (st.comp_method != ZIP_CM_STORE && st.comp_method != ZIP_CM_DEFLATE)
    throw Error::input(name, "zip entry " + entry + ": compression method " +
                                 std::to_string(st.comp_method) + " (only Stored and Deflate are read)");
  const std::uint64_t ratio_limit =
      st.comp_method == ZIP_CM_STORE ? st.comp_size : st.comp_size * kMaxDeflateRatio + 1024;
  if (st.comp_size > zip_bytes || st.size > ratio_limit)
    throw Error::input(name, "zip entry " + entry + " claims " + std::to_string(st.size) +
                                 " bytes from " + std::to_string(st.comp_size) +
                                 " compressed bytes in a " + std::to_string(zip_bytes) +
                                 "-byte archive: refused as implausible");
  const std::uint64_t limit = InputLimits::from_environment().file_bytes;
  if (st.size > limit)
    throw Error::input(name, "zip entry " + entry + " inflates to " + std::to_string(st.size) +
                                 " bytes, over the input limit of " + std::to_string(limit >> 20) +
                                 " MiB; if the file is right, raise it with "
                                 "SKETCHSURF_MAX_INPUT_MB=<MiB>");
  std::unique_ptr<zip_file_t, ZipFileClose> file(zip_fopen_index(za, index, 0));
  if (!file) throw Error::input(name, "zip entry " + entry + ": " + zip_strerror(za));
  Buffer out(static_cast<std::size_t>(st.size), '\0');
  std::uint64_t got = 0;
  while (got < st.size) {
    const zip_int64_t n = zip_fread(file.get(), out.data() + got, st.size - got);
    if (n < 0) throw Error::input(name, "zip entry " + entry + ": " + zip_file_strerror(file.get()));
    if (n == 0) break;
    got += static_cast<std::uint64_t>(n);
  }
  char probe = 0;  // reading past the end makes libzip verify the CRC
  const zip_int64_t tail = zip_fread(file.get(), &probe, 1);
  if (got != st.size || tail != 0)
    throw Error::input(name, "zip entry " + entry + ": " +
                                 (tail < 0 ? std::string(zip_file_strerror(file.get()))
                                           : "data does not match its declared size " +
                                                 std::to_string(st.size)));
  return out;
}

TiltEntries entries_from_zip(zip_t* za, std::uint64_t zip_bytes, const fs::path& name) {
  TiltEntries entries;
  const auto sketch = find_entry(za, "data.sketch");
  if (!sketch) throw Error::input(name, "zip archive has no data.sketch entry");
  entries.sketch = read_entry<std::vector<std::uint8_t>>(za, *sketch, zip_bytes, name, "data.sketch");
  auto metadata = find_entry(za, "metadata.json");
  if (!metadata) {
    metadata = find_entry(za, "main.json");
    entries.metadata_entry = "main.json";
  }
  if (!metadata) throw Error::input(name, "zip archive has neither metadata.json nor main.json");
  entries.metadata = read_entry<std::string>(za, *metadata, zip_bytes, name, entries.metadata_entry);
  return entries;
}

TiltEntries entries_from_bytes(Bytes bytes, const fs::path& name) {
  if (bytes.size() < kHeaderBytes)
    throw Error::input_at_byte(name, bytes.size(), "expected the 16-byte .tilt header, but the file has only " +
                                                       std::to_string(bytes.size()) + " bytes");
  if (load_u32(bytes.data()) != kMagic)
    throw Error::input_at_byte(name, 0, "expected magic bytes 74 69 6C 54 (\"tilT\"): not a .tilt file");
  const std::uint16_t header_size = load_u16(bytes.data() + 4);
  if (header_size < kHeaderBytes)
    throw Error::input_at_byte(name, 4, "header size " + std::to_string(header_size) + " is below 16");
  const std::uint16_t header_version = load_u16(bytes.data() + 6);
  if (header_version != kHeaderVersion)
    throw Error::input_at_byte(name, 6, "header version " + std::to_string(header_version) +
                                            " is not supported (expected 1)");
  static constexpr std::uint8_t kLocalHeader[] = {0x50, 0x4B, 0x03, 0x04};
  if (bytes.size() < std::size_t{header_size} + 4 ||
      std::memcmp(bytes.data() + header_size, kLocalHeader, 4) != 0)
    throw Error::input_at_byte(name, header_size, "expected a zip local header 50 4B 03 04 (\"PK\\3\\4\")");

  const Bytes zip = bytes.subspan(header_size);
  std::string why;
  ZipArchive za = open_zip(zip, &why);
  if (za) return entries_from_zip(za.get(), zip.size(), name);
  std::string why_whole;
  za = open_zip(bytes, &why_whole);  // offsets counted from the start of the file
  if (za) return entries_from_zip(za.get(), bytes.size(), name);
  throw Error::input(name, "the zip archive after the header cannot be read: " + why);
}

/// Reads a whole regular file, refusing ones over the input limit (check_input_file).
template <class Buffer>
Buffer read_file(const fs::path& file) {
  const std::uint64_t size = check_input_file(file, InputLimits::from_environment());
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error::input(file, "cannot open for reading");
  Buffer out(static_cast<std::size_t>(size), '\0');
  in.read(reinterpret_cast<char*>(out.data()), static_cast<std::streamsize>(size));
  if (in.gcount() != static_cast<std::streamsize>(size)) throw Error::input(file, "read failed");
  return out;
}

TiltEntries entries_from_directory(const fs::path& dir) {
  TiltEntries entries;
  std::error_code ec;
  if (!fs::is_regular_file(dir / "data.sketch", ec))
    throw Error::input(dir, "directory-form .tilt without a data.sketch file");
  entries.sketch = read_file<std::vector<std::uint8_t>>(dir / "data.sketch");
  if (!fs::is_regular_file(dir / "metadata.json", ec)) entries.metadata_entry = "main.json";
  if (!fs::is_regular_file(dir / entries.metadata_entry, ec))
    throw Error::input(dir, "directory-form .tilt without metadata.json or main.json");
  entries.metadata = read_file<std::string>(dir / entries.metadata_entry);
  return entries;
}

Sketch decode(const TiltEntries& entries, const fs::path& name, Warnings* warnings) {
  const Metadata meta = parse_metadata(entries.metadata, name / entries.metadata_entry);
  Sketch sketch = parse_data_sketch(entries.sketch, name / "data.sketch", meta, warnings);
  sketch.units = "m";
  sketch.provenance = "Open Brush .tilt " + name.filename().string();
  return sketch;
}

// ----------------------------------------------------------------------------------------------
// Writer (section 4).

/// Per-point timestamps for every stroke: kept when present (made non-decreasing), synthesised at
/// ~90 Hz after everything before them when absent.
std::vector<std::vector<std::uint32_t>> writable_timestamps(const Sketch& sketch) {
  std::vector<std::vector<std::uint32_t>> out(sketch.strokes.size());
  std::uint64_t cursor = 0;
  constexpr std::uint64_t kMax = std::numeric_limits<std::uint32_t>::max();
  for (std::size_t s = 0; s < sketch.strokes.size(); ++s) {
    const Stroke& stroke = sketch.strokes[s];
    auto& times = out[s];
    if (stroke.timestamps_ms.size() == stroke.size()) {
      times = stroke.timestamps_ms;
      for (std::size_t i = 1; i < times.size(); ++i) times[i] = std::max(times[i], times[i - 1]);
    } else {
      times.resize(stroke.size());
      for (std::size_t i = 0; i < times.size(); ++i)
        times[i] = static_cast<std::uint32_t>(std::min(cursor + i * kSynthesisedStepMs, kMax));
    }
    if (!times.empty()) cursor = std::max<std::uint64_t>(cursor, std::uint64_t{times.back()} + kSynthesisedStepMs);
  }
  return out;
}

struct Encoded {
  std::vector<std::uint8_t> data_sketch;
  std::vector<std::string> brushes;
  std::uint32_t layer_count = 1;
};

Encoded encode_strokes(const Sketch& sketch) {
  Encoded enc;
  const auto times = writable_timestamps(sketch);
  std::vector<std::size_t> order;
  std::size_t points = 0;
  for (std::size_t s = 0; s < sketch.strokes.size(); ++s) {
    const Stroke& stroke = sketch.strokes[s];
    if (stroke.points.empty()) continue;
    if (!stroke.attributes_consistent())
      throw Error::processing("stroke " + std::to_string(s) +
                              ": per-point attributes do not match the number of points");
    for (const auto& p : stroke.points)
      if (!p.allFinite())
        throw Error::processing("stroke " + std::to_string(s) +
                                " has a non-finite point; clean the sketch before writing .tilt");
    if (stroke.layer >= kMaxWrittenLayers)
      throw Error::processing("stroke " + std::to_string(s) + " is on layer " +
                              std::to_string(stroke.layer) + "; .tilt files hold at most " +
                              std::to_string(kMaxWrittenLayers) + " layers");
    enc.layer_count = std::max(enc.layer_count, stroke.layer + 1);
    order.push_back(s);
    points += std::max<std::size_t>(stroke.size(), 2);
  }
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return times[a].front() < times[b].front(); });

  const bool layered = enc.layer_count > 1;
  const std::uint32_t stroke_mask = layered ? 0x19u : 0x9u;  // Flags, Seed (+ Layer)
  constexpr std::uint32_t kCpMask = 0x3u;                     // pressure, timestamp
  auto& out = enc.data_sketch;
  out.reserve(20 + order.size() * (kStrokeFixedBytes + 12) + points * (kPointFixedBytes + 8));
  put_u32(out, kSentinel);
  put_i32(out, kSketchVersion);
  put_u32(out, 0);  // reserved
  put_u32(out, 0);  // no extra header bytes
  put_i32(out, static_cast<std::int32_t>(order.size()));
  for (std::size_t k = 0; k < order.size(); ++k) {
    const Stroke& stroke = sketch.strokes[order[k]];
    const std::string brush = stroke.brush.empty() ? kLightBrush : stroke.brush;
    auto it = std::find(enc.brushes.begin(), enc.brushes.end(), brush);
    if (it == enc.brushes.end()) it = enc.brushes.insert(it, brush);
    put_i32(out, static_cast<std::int32_t>(it - enc.brushes.begin()));
    for (float c : stroke.color) put_f32(out, c);
    const double width = stroke.width > 0 && std::isfinite(stroke.width) ? stroke.width : kDefaultWidthM;
    put_f32(out, static_cast<float>(width / kUnitsToMetres));
    put_u32(out, stroke_mask);
    put_u32(out, kCpMask);
    put_u32(out, 0);                                // Flags
    put_i32(out, static_cast<std::int32_t>(k));     // Seed
    if (layered) put_u32(out, stroke.layer);        // Layer
    const std::size_t n = stroke.size();
    put_i32(out, static_cast<std::int32_t>(std::max<std::size_t>(n, 2)));
    const auto& t = times[order[k]];
    for (std::size_t j = 0; j < std::max<std::size_t>(n, 2); ++j) {
      const std::size_t i = std::min(j, n - 1);  // a one-point stroke writes its point twice
      const Eigen::Vector3d p = flip_x(stroke.points[i]) / kUnitsToMetres;
      for (int a = 0; a < 3; ++a) put_f32(out, static_cast<float>(p[a]));
      Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
      if (!stroke.orientations.empty() && stroke.orientations[i].coeffs().allFinite() &&
          stroke.orientations[i].norm() > 1e-6) {
        // Quaternions already unit to float precision are written as they are, so that reading
        // and writing again reproduces the same bytes.
        const Eigen::Quaterniond& o = stroke.orientations[i];
        q = flip_rotation(std::abs(o.norm() - 1.0) < 1e-6 ? o : o.normalized());
      }
      for (double c : {q.x(), q.y(), q.z(), q.w()}) put_f32(out, static_cast<float>(c));
      put_f32(out, stroke.pressures.empty() ? 1.0f : stroke.pressures[i]);
      put_u32(out, t[i]);
    }
  }
  return enc;
}

nlohmann::json transform_json(const Transform& xf) {
  return nlohmann::json::array({{xf.t.x(), xf.t.y(), xf.t.z()},
                                {xf.q.x(), xf.q.y(), xf.q.z(), xf.q.w()},
                                xf.s});
}

std::string encode_metadata(const Sketch& sketch, const Encoded& enc) {
  nlohmann::json j;
  j["EnvironmentPreset"] = kDefaultEnvironment;
  j["BrushIndex"] = enc.brushes;
  j["SchemaVersion"] = 2;
  j["SceneTransformInRoomSpace"] = transform_json(Transform{});
  if (enc.layer_count > 1) {
    nlohmann::json layers = nlohmann::json::array();
    for (std::uint32_t i = 0; i < enc.layer_count; ++i)
      layers.push_back({{"Name", i == 0 ? std::string("Main Canvas") : "Layer " + std::to_string(i)},
                        {"Visible", true}});
    j["Layers"] = std::move(layers);
  }
  if (sketch.mirror) {
    const double length = sketch.mirror->normal.norm();
    if (!(length > 1e-12) || !std::isfinite(sketch.mirror->offset))
      throw Error::processing("the sketch's mirror plane has no valid normal");
    const Eigen::Vector3d n = sketch.mirror->normal / length;
    const Eigen::Vector3d on_plane = -(sketch.mirror->offset / length) * n;
    Transform widget;  // local +X is the plane normal (see mirror_plane)
    widget.t = flip_x(on_plane) / kUnitsToMetres;
    widget.q = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitX(), flip_x(n));
    j["Mirror"] = {{"Transform", transform_json(widget)}};
  }
  return j.dump();
}

struct Entry {
  const char* name;
  const void* data;
  std::size_t size;
};

/// A zip of Stored entries, offsets counted from its own first byte.
std::vector<std::uint8_t> stored_zip(const std::vector<Entry>& entries) {
  auto fail = [](const std::string& what) { return Error::processing("writing the .tilt zip: " + what); };
  zip_error_t error;
  zip_error_init(&error);
  ZipSource memory(zip_source_buffer_create(nullptr, 0, 0, &error));
  if (!memory) throw fail(zip_error_strerror(&error));
  ZipArchive za(zip_open_from_source(memory.get(), ZIP_CREATE | ZIP_TRUNCATE, &error));
  if (!za) throw fail(zip_error_strerror(&error));
  zip_source_keep(memory.get());  // stays alive after zip_close, which writes into it
  constexpr time_t kFixedTime = 1577836800;  // 2020-01-01: identical sketches give identical files
  for (const auto& e : entries) {
    zip_source_t* source = zip_source_buffer(za.get(), e.data, e.size, 0);
    if (!source) throw fail(zip_strerror(za.get()));
    const zip_int64_t index = zip_file_add(za.get(), e.name, source, 0);
    if (index < 0) {
      zip_source_free(source);
      throw fail(zip_strerror(za.get()));
    }
    const auto i = static_cast<zip_uint64_t>(index);
    if (zip_set_file_compression(za.get(), i, ZIP_CM_STORE, 0) != 0 ||
        zip_file_set_mtime(za.get(), i, kFixedTime, 0) != 0)
      throw fail(zip_strerror(za.get()));
  }
  if (zip_close(za.get()) != 0) throw fail(zip_strerror(za.get()));
  za.release();  // zip_close freed it

  zip_stat_t st;
  if (zip_source_stat(memory.get(), &st) != 0 || !(st.valid & ZIP_STAT_SIZE) ||
      zip_source_open(memory.get()) != 0)
    throw fail("cannot read back the archive");
  std::vector<std::uint8_t> out(static_cast<std::size_t>(st.size));
  const zip_int64_t n = zip_source_read(memory.get(), out.data(), st.size);
  zip_source_close(memory.get());
  if (n < 0 || static_cast<zip_uint64_t>(n) != st.size) throw fail("cannot read back the archive");
  return out;
}

}  // namespace

Sketch read_tilt_bytes(std::span<const std::uint8_t> bytes, const std::filesystem::path& name,
                       Warnings* warnings) {
  return decode(entries_from_bytes(bytes, name), name, warnings);
}

Sketch read_tilt(const std::filesystem::path& file, Warnings* warnings) {
  std::error_code ec;
  if (fs::is_directory(file, ec)) return decode(entries_from_directory(file), file, warnings);
  TiltEntries entries;
  {
    // The file's bytes are released before the strokes are decoded, to keep peak memory low.
    const auto bytes = read_file<std::vector<std::uint8_t>>(file);
    entries = entries_from_bytes(bytes, file);
  }
  return decode(entries, file, warnings);
}

void write_tilt(const Sketch& sketch, const std::filesystem::path& file) {
  const Encoded enc = encode_strokes(sketch);
  const std::string metadata = encode_metadata(sketch, enc);
  const auto zip = stored_zip({{"data.sketch", enc.data_sketch.data(), enc.data_sketch.size()},
                               {"metadata.json", metadata.data(), metadata.size()},
                               {"thumbnail.png", kThumbnailPng, sizeof(kThumbnailPng)}});
  std::vector<std::uint8_t> header;
  put_u32(header, kMagic);
  put_u16(header, static_cast<std::uint16_t>(kHeaderBytes));
  put_u16(header, kHeaderVersion);
  put_u32(header, 0);
  put_u32(header, 0);
  write_atomically(file, [&](std::ostream& out) {
    out.write(reinterpret_cast<const char*>(header.data()), static_cast<std::streamsize>(header.size()));
    out.write(reinterpret_cast<const char*>(zip.data()), static_cast<std::streamsize>(zip.size()));
  });
}

}  // namespace sketchsurf
