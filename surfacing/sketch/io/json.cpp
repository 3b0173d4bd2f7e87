#include "surfacing/sketch/io/json.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>

#include "surfacing/error.h"
#include "surfacing/sketch/io/atomic_file.h"
#include "surfacing/sketch/io/input_limits.h"
#include "surfacing/sketch/io/text_io.h"

namespace sketchsurf {

namespace {

constexpr std::string_view kFormat = "sketchsurf-sketch";
constexpr std::int64_t kVersion = 1;

// ---------------------------------------------------------------------------------------------
// Reading: a handler of parser events that streams straight into the Sketch. A DOM of a 1M-point
// file would hold 3M+ json values (hundreds of MB); the handler keeps only a stack of where it is.

/// One JSON value as JsonParser delivers it.
struct Value {
  enum class Kind { Null, Boolean, Integer, Unsigned, Float, String, Object, Array };
  explicit Value(Kind k) : kind(k) {}

  Kind kind;
  bool boolean = false;
  std::int64_t integer = 0;
  std::uint64_t unsigned_integer = 0;
  double number = 0.0;
  std::string_view text;  // the string, or the token of a float

  bool is_number() const {
    return kind == Kind::Integer || kind == Kind::Unsigned || kind == Kind::Float;
  }
  bool is_compound() const { return kind == Kind::Object || kind == Kind::Array; }
  double as_double() const {
    switch (kind) {
      case Kind::Integer: return static_cast<double>(integer);
      case Kind::Unsigned: return static_cast<double>(unsigned_integer);
      default: return number;
    }
  }
  /// Correctly rounded from the decimal text, so that floats written by write_json come back
  /// bit-identical (going through double first could round twice).
  std::optional<float> as_float() const {
    switch (kind) {
      case Kind::Integer: return static_cast<float>(integer);
      case Kind::Unsigned: return static_cast<float>(unsigned_integer);
      case Kind::Float: return io_detail::parse_float(text);
      default: return std::nullopt;
    }
  }
  /// The value as a signed integer, if it is one (floats with a fraction are not).
  std::optional<std::int64_t> as_int64() const {
    if (kind == Kind::Integer) return integer;
    if (kind == Kind::Unsigned &&
        unsigned_integer <= static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
      return static_cast<std::int64_t>(unsigned_integer);
    return std::nullopt;
  }
  std::string describe() const {
    switch (kind) {
      case Kind::Null: return "null";
      case Kind::Boolean: return "a boolean";
      case Kind::Integer:
      case Kind::Unsigned:
      case Kind::Float: return "a number";
      case Kind::String: return "a string";
      case Kind::Object: return "an object";
      case Kind::Array: return "an array";
    }
    return "a value";
  }
};

/// Where in the document a frame of the stack is.
enum class Where {
  Document, Root, Mirror, Normal, Rotation, Center, Axis, Params, Strokes, Stroke, Points, Point, Orientations,
  Orientation, Pressures, Timestamps, Color, Skip
};

// Bits of the keys seen in one object, to refuse duplicates.
enum RootKey : std::uint32_t {
  kKeyFormat = 1, kKeyVersion = 2, kKeyUnits = 4, kKeyProvenance = 8, kKeyMirror = 16,
  kKeyParams = 32, kKeyStrokes = 64, kKeyRotation = 128
};
enum StrokeKey : std::uint32_t {
  kKeyId = 1, kKeyPoints = 2, kKeyOrientations = 4, kKeyPressures = 8, kKeyTimestamps = 16,
  kKeyWidth = 32, kKeyColor = 64, kKeyBrush = 128, kKeyLayer = 256, kKeyBoundary = 512,
  kKeyIgnored = 1024
};
enum MirrorKey : std::uint32_t { kKeyNormal = 1, kKeyOffset = 2 };
enum RotationKey : std::uint32_t { kKeyCenter = 1, kKeyAxis = 2, kKeyCount = 4 };

struct Frame {
  Frame(Where w, bool is_array) : where(w), array(is_array) {}
  Where where;
  bool array;
  std::string key;         // current key (objects)
  std::size_t index = 0;   // current element (arrays)
  std::uint32_t seen = 0;  // keys seen (objects)
  std::string prefix;      // dotted name of a params object, with a trailing '.'
};

class SketchSax {
 public:
  /// `offset` tells where the parser is, for error messages.
  SketchSax(const std::filesystem::path& name, Warnings* warnings,
            std::function<std::uint64_t()> offset)
      : name_(name), warnings_(warnings), offset_(std::move(offset)), budget_(name) {
    stack_.emplace_back(Where::Document, false);
  }

  // --- events from JsonParser --------------------------------------------------------------
  void null() { value(Value(Value::Kind::Null)); }
  void boolean(bool b) {
    Value v(Value::Kind::Boolean);
    v.boolean = b;
    value(v);
  }
  void number_integer(std::int64_t i) {
    Value v(Value::Kind::Integer);
    v.integer = i;
    value(v);
  }
  void number_unsigned(std::uint64_t u) {
    Value v(Value::Kind::Unsigned);
    v.unsigned_integer = u;
    value(v);
  }
  void number_float(double d, std::string_view token) {
    Value v(Value::Kind::Float);
    v.number = d;
    v.text = token;
    value(v);
  }
  void string(std::string_view s) {
    Value v(Value::Kind::String);
    v.text = s;
    value(v);
  }
  void start_object() { value(Value(Value::Kind::Object)); }
  void start_array() { value(Value(Value::Kind::Array)); }
  void key(std::string_view k) { stack_.back().key = k; }
  void end_object() { end(); }
  void end_array() { end(); }

  /// JSON path of the value being read, e.g. "strokes[3].points[5]".
  std::string path(std::size_t frames = std::numeric_limits<std::size_t>::max()) const {
    std::string out;
    for (std::size_t i = 1; i < std::min(frames, stack_.size()); ++i) {
      const Frame& f = stack_[i];
      if (f.array) {
        out += '[';
        out += std::to_string(f.index);
        out += ']';
      } else {
        if (!out.empty()) out += ".";
        out += f.key;
      }
    }
    return out;
  }

  Sketch finish() {
    if (!done_) fail("", "the document ended early");
    return std::move(sketch_);
  }

 private:
  [[noreturn]] void fail(const std::string& at, const std::string& what) const {
    throw Error::input_at_byte(name_, offset_(), (at.empty() ? "" : at + ": ") + what);
  }
  [[noreturn]] void expected(const std::string& what, const Value& got) const {
    fail(path(), "expected " + what + ", got " + got.describe());
  }

  void warn_once(const std::string& what) {
    if (warnings_ && warned_.insert(what).second) warnings_->push_back(what);
  }

  void push(Where where, bool array) { stack_.emplace_back(where, array); }

  // A per-point attribute array holding `size` entries gets one more: it may not outgrow the
  // limit of points (its length is checked against the stroke's points only at the stroke's end).
  void check_attribute_count(std::size_t size) const {
    if (size >= budget_.limit())
      fail(path(), "more entries than the limit of " + std::to_string(budget_.limit()) +
                       " points; if the file is right, raise it with SKETCHSURF_MAX_POINTS=<count>");
  }

  // Claims key bit `bit` of the current object; a second occurrence is an error.
  void claim(std::uint32_t bit) {
    Frame& f = stack_.back();
    if (f.seen & bit) fail(path(), "duplicate key");
    f.seen |= bit;
  }

  // A key this version does not know: warned about once per pattern and skipped.
  void unknown(const Value& v, const std::string& pattern) {
    warn_once("unknown key " + io_detail::excerpt(pattern) + " ignored");
    if (v.is_compound()) push(Where::Skip, v.kind == Value::Kind::Array);
  }

  double finite_number(const Value& v, const char* what = "a number") const {
    if (!v.is_number()) expected(what, v);
    const double d = v.as_double();
    if (!std::isfinite(d)) fail(path(), "number out of range");
    return d;
  }
  float finite_float(const Value& v) const {
    if (!v.is_number()) expected("a number", v);
    const auto f = v.as_float();
    if (!f) fail(path(), "number out of range for a float");
    return *f;
  }
  std::uint32_t uint32(const Value& v, const char* what) const {
    const auto i = v.as_int64();
    if (!i || *i < 0 || *i > std::numeric_limits<std::uint32_t>::max()) expected(what, v);
    return static_cast<std::uint32_t>(*i);
  }

  /// A value arrives in the current frame (scalars complete at once, compounds at end()).
  void value(const Value& v) {
    Frame& f = stack_.back();
    switch (f.where) {
      case Where::Document:
        if (v.kind != Value::Kind::Object) expected("a JSON object (a sketchsurf sketch)", v);
        push(Where::Root, false);
        break;
      case Where::Root: root_value(v); break;
      case Where::Mirror: mirror_value(v); break;
      case Where::Normal:
        if (f.index >= 3) fail(path(), "a normal has 3 components");
        mirror_normal_[f.index] = finite_number(v);
        break;
      case Where::Rotation: rotation_value(v); break;
      case Where::Center:
      case Where::Axis:
        if (f.index >= 3) fail(path(), "expected 3 numbers [x, y, z]");
        (f.where == Where::Center ? rotation_.center : rotation_.axis)[f.index] = finite_number(v);
        break;
      case Where::Params: params_value(v); break;
      case Where::Strokes:
        if (v.kind != Value::Kind::Object) expected("a stroke object", v);
        stroke_ = Stroke{};
        push(Where::Stroke, false);
        break;
      case Where::Stroke: stroke_value(v); break;
      case Where::Points:
        if (v.kind != Value::Kind::Array) expected("a point [x, y, z]", v);
        push(Where::Point, true);
        break;
      case Where::Point:
        if (f.index >= 3) fail(path(), "a point has 3 coordinates [x, y, z]");
        tuple_[f.index] = finite_number(v, "a coordinate (number)");
        break;
      case Where::Orientations:
        if (v.kind != Value::Kind::Array) expected("a quaternion [x, y, z, w]", v);
        check_attribute_count(stroke_.orientations.size());
        push(Where::Orientation, true);
        break;
      case Where::Orientation:
        if (f.index >= 4) fail(path(), "a quaternion has 4 components [x, y, z, w]");
        tuple_[f.index] = finite_number(v);
        break;
      case Where::Pressures:
        check_attribute_count(stroke_.pressures.size());
        stroke_.pressures.push_back(finite_float(v));
        break;
      case Where::Timestamps:
        check_attribute_count(stroke_.timestamps_ms.size());
        stroke_.timestamps_ms.push_back(uint32(v, "a timestamp (integer milliseconds >= 0)"));
        break;
      case Where::Color:
        if (f.index >= 4) fail(path(), "a colour has 4 components [r, g, b, a]");
        stroke_.color[f.index] = finite_float(v);
        break;
      case Where::Skip:
        if (v.is_compound()) push(Where::Skip, v.kind == Value::Kind::Array);
        break;
    }
    // A scalar is complete: move the enclosing array on. (Compounds do it in end().)
    if (!v.is_compound() && stack_.back().array) ++stack_.back().index;
  }

  void root_value(const Value& v) {
    const std::string& k = stack_.back().key;
    if (k == "format") {
      claim(kKeyFormat);
      if (v.kind != Value::Kind::String || v.text != kFormat)
        fail(path(), "expected \"sketchsurf-sketch\" (not a sketchsurf sketch)");
    } else if (k == "version") {
      claim(kKeyVersion);
      const auto version = v.as_int64();
      if (!version) expected("an integer version", v);
      if (*version != kVersion)
        fail(path(), "unsupported version " + std::to_string(*version) + " (this build reads version " +
                         std::to_string(kVersion) + ")");
    } else if (k == "units") {
      claim(kKeyUnits);
      if (v.kind != Value::Kind::String) expected("a string", v);
      sketch_.units = std::string(v.text);
    } else if (k == "provenance") {
      claim(kKeyProvenance);
      if (v.kind != Value::Kind::String) expected("a string", v);
      sketch_.provenance = std::string(v.text);
    } else if (k == "mirror") {
      claim(kKeyMirror);
      if (v.kind == Value::Kind::Null) return;
      if (v.kind != Value::Kind::Object) expected("null or {\"normal\": [x, y, z], \"offset\": d}", v);
      mirror_normal_.setConstant(std::numeric_limits<double>::quiet_NaN());
      push(Where::Mirror, false);
    } else if (k == "rotation") {
      claim(kKeyRotation);
      if (v.kind == Value::Kind::Null) return;
      if (v.kind != Value::Kind::Object)
        expected("null or {\"center\": [x, y, z], \"axis\": [x, y, z], \"count\": n}", v);
      rotation_ = RotationPattern{};
      push(Where::Rotation, false);
    } else if (k == "params") {
      claim(kKeyParams);
      if (v.kind != Value::Kind::Object) expected("an object of parameters", v);
      push(Where::Params, false);
    } else if (k == "strokes") {
      claim(kKeyStrokes);
      if (v.kind != Value::Kind::Array) expected("an array of strokes", v);
      push(Where::Strokes, true);
    } else {
      unknown(v, k);
    }
  }

  void mirror_value(const Value& v) {
    const std::string& k = stack_.back().key;
    if (k == "normal") {
      claim(kKeyNormal);
      if (v.kind != Value::Kind::Array) expected("a normal [x, y, z]", v);
      push(Where::Normal, true);
    } else if (k == "offset") {
      claim(kKeyOffset);
      mirror_offset_ = finite_number(v);
    } else {
      unknown(v, "mirror." + k);
    }
  }

  void rotation_value(const Value& v) {
    const std::string& k = stack_.back().key;
    if (k == "center" || k == "axis") {
      claim(k == "center" ? kKeyCenter : kKeyAxis);
      if (v.kind != Value::Kind::Array) expected("[x, y, z]", v);
      push(k == "center" ? Where::Center : Where::Axis, true);
    } else if (k == "count") {
      claim(kKeyCount);
      const auto count = v.as_int64();
      if (!count || *count < 2 || *count > 360) expected("an integer count from 2 to 360", v);
      rotation_.count = static_cast<int>(*count);
    } else {
      unknown(v, "rotation." + k);
    }
  }

  void params_value(const Value& v) {
    const Frame& f = stack_.back();
    if (f.key.empty() || f.key.find('.') != std::string::npos)
      fail(path(), "a parameter name must be non-empty and have no '.' (nest objects instead)");
    const std::string name = f.prefix + f.key;
    if (sketch_.params.contains(name)) fail(path(), "duplicate parameter");
    const auto after = sketch_.params.lower_bound(name + ".");
    if (after != sketch_.params.end() && after->first.starts_with(name + "."))
      fail(path(), "duplicate parameter group");
    if (v.kind == Value::Kind::Object) {
      push(Where::Params, false);
      stack_.back().prefix = name + ".";
      return;
    }
    sketch_.params.emplace(name, finite_number(v, "a number or an object of parameters"));
  }

  void stroke_value(const Value& v) {
    const std::string& k = stack_.back().key;
    auto array_of = [&](std::uint32_t bit, Where where, const char* what) {
      claim(bit);
      if (v.kind != Value::Kind::Array) expected(what, v);
      push(where, true);
    };
    if (k == "points") {
      array_of(kKeyPoints, Where::Points, "an array of points");
    } else if (k == "orientations") {
      array_of(kKeyOrientations, Where::Orientations, "an array of quaternions");
    } else if (k == "pressures") {
      array_of(kKeyPressures, Where::Pressures, "an array of numbers");
    } else if (k == "timestamps_ms") {
      array_of(kKeyTimestamps, Where::Timestamps, "an array of integers");
    } else if (k == "color") {
      array_of(kKeyColor, Where::Color, "a colour [r, g, b, a]");
    } else if (k == "id") {
      claim(kKeyId);
      const auto id = v.as_int64();
      if (!id) expected("an integer id", v);
      stroke_.id = *id;
    } else if (k == "width") {
      claim(kKeyWidth);
      stroke_.width = finite_number(v);
      if (stroke_.width < 0.0) fail(path(), "a width cannot be negative");
    } else if (k == "brush") {
      claim(kKeyBrush);
      if (v.kind != Value::Kind::String) expected("a string", v);
      stroke_.brush = std::string(v.text);
    } else if (k == "layer") {
      claim(kKeyLayer);
      stroke_.layer = uint32(v, "a layer index (integer >= 0)");
    } else if (k == "boundary" || k == "ignored") {
      claim(k == "boundary" ? kKeyBoundary : kKeyIgnored);
      if (v.kind != Value::Kind::Boolean) expected("true or false", v);
      (k == "boundary" ? stroke_.boundary : stroke_.ignored) = v.boolean;
    } else {
      unknown(v, "strokes[]." + k);
    }
  }

  /// The current object or array closes.
  void end() {
    const Frame& f = stack_.back();
    switch (f.where) {
      case Where::Root:
        if (!(f.seen & kKeyFormat)) fail("", "no \"format\" key: not a sketchsurf sketch");
        if (!(f.seen & kKeyVersion)) fail("", "no \"version\" key");
        done_ = true;
        break;
      case Where::Mirror: end_mirror(f); break;
      case Where::Rotation: end_rotation(f); break;
      case Where::Normal:
      case Where::Center:
      case Where::Axis:
      case Where::Point:
      case Where::Orientation:
      case Where::Color: {
        const std::size_t want =
            f.where == Where::Orientation || f.where == Where::Color ? 4 : 3;
        if (f.index != want)
          fail(path(stack_.size() - 1), "expected " + std::to_string(want) + " numbers, got " +
                                            std::to_string(f.index));
        if (f.where == Where::Point) {
          budget_.take(1);
          stroke_.points.emplace_back(tuple_[0], tuple_[1], tuple_[2]);
        }
        if (f.where == Where::Orientation)
          stroke_.orientations.emplace_back(tuple_[3], tuple_[0], tuple_[1], tuple_[2]);
        break;
      }
      case Where::Stroke: end_stroke(f); break;
      default: break;
    }
    stack_.pop_back();
    if (stack_.back().array) ++stack_.back().index;
  }

  void end_mirror(const Frame& f) {
    const std::string at = path(stack_.size() - 1);
    if (!(f.seen & kKeyNormal)) fail(at, "no \"normal\"");
    if (!(f.seen & kKeyOffset)) fail(at, "no \"offset\"");
    const double norm = mirror_normal_.norm();
    if (!(norm > 1e-12) || !std::isfinite(norm)) fail(at, "the mirror normal is zero");
    Plane plane;
    plane.normal = mirror_normal_;
    plane.offset = mirror_offset_;
    // n . x + d = 0 keeps its meaning when both are divided by |n|. A normal that is already unit
    // (as write_json writes it) is kept bit for bit.
    if (std::abs(norm - 1.0) > 4 * std::numeric_limits<double>::epsilon()) {
      plane.normal /= norm;
      plane.offset /= norm;
    }
    sketch_.mirror = plane;
  }

  void end_rotation(const Frame& f) {
    const std::string at = path(stack_.size() - 1);
    if (!(f.seen & kKeyCenter)) fail(at, "no \"center\"");
    if (!(f.seen & kKeyAxis)) fail(at, "no \"axis\"");
    if (!(f.seen & kKeyCount)) fail(at, "no \"count\"");
    const double norm = rotation_.axis.norm();
    if (!(norm > 1e-12) || !std::isfinite(norm)) fail(at, "the rotation axis is zero");
    // A unit axis (as write_json writes it) is kept bit for bit.
    if (std::abs(norm - 1.0) > 4 * std::numeric_limits<double>::epsilon()) rotation_.axis /= norm;
    sketch_.rotation = rotation_;
  }

  void end_stroke(const Frame& f) {
    const std::string at = path(stack_.size() - 1);
    if (!(f.seen & kKeyPoints)) fail(at, "no \"points\"");
    const std::size_t n = stroke_.points.size();
    auto check = [&](std::size_t size, const char* key) {
      if (size != 0 && size != n)
        fail(at + "." + key, "has " + std::to_string(size) + " entries for " + std::to_string(n) +
                                 " points");
    };
    check(stroke_.orientations.size(), "orientations");
    check(stroke_.pressures.size(), "pressures");
    check(stroke_.timestamps_ms.size(), "timestamps_ms");
    sketch_.strokes.push_back(std::move(stroke_));
    stroke_ = Stroke{};
  }

  std::filesystem::path name_;
  Warnings* warnings_;
  std::function<std::uint64_t()> offset_;
  PointBudget budget_;
  std::set<std::string> warned_;
  std::vector<Frame> stack_;
  Sketch sketch_;
  Stroke stroke_;
  double tuple_[4] = {0, 0, 0, 0};
  Eigen::Vector3d mirror_normal_ = Eigen::Vector3d::Zero();
  double mirror_offset_ = 0.0;
  RotationPattern rotation_;
  bool done_ = false;
};

// ---------------------------------------------------------------------------------------------
// A strict JSON (RFC 8259) pull parser over a byte source that is either in memory or streamed
// from a file in chunks. Written for speed: nlohmann's lexer reads a 1M-point file (170 MB with
// orientations) in about 1.5 s; this one with std::from_chars in a fraction of that, and without
// holding the file in memory.

/// The bytes of a document: a view, or a stream read 1 MB at a time.
class Source {
 public:
  explicit Source(std::string_view text)
      : begin_(text.data()), pos_(text.data()), end_(text.data() + text.size()) {}
  explicit Source(std::istream& in) : in_(&in), buffer_(1 << 20) {}

  /// The next byte (0-255) without consuming it, or -1 at the end.
  int peek() {
    if (pos_ == end_ && !refill()) return -1;
    return static_cast<unsigned char>(*pos_);
  }
  int get() {
    const int c = peek();
    if (c >= 0) ++pos_;
    return c;
  }
  /// Offset of the next byte from the start of the document.
  std::uint64_t offset() const { return base_ + static_cast<std::uint64_t>(pos_ - begin_); }

 private:
  bool refill() {
    if (!in_) return false;
    base_ += static_cast<std::uint64_t>(end_ - begin_);
    in_->read(buffer_.data(), static_cast<std::streamsize>(buffer_.size()));
    const auto n = static_cast<std::size_t>(in_->gcount());
    begin_ = pos_ = buffer_.data();
    end_ = begin_ + n;
    return n > 0;
  }

  std::istream* in_ = nullptr;
  std::vector<char> buffer_;
  const char* begin_ = nullptr;
  const char* pos_ = nullptr;
  const char* end_ = nullptr;
  std::uint64_t base_ = 0;
};

bool valid_utf8(std::string_view s) {
  for (std::size_t i = 0; i < s.size();) {
    const auto c = static_cast<unsigned char>(s[i]);
    if (c < 0x80) {
      ++i;
      continue;
    }
    const std::size_t n = (c >> 5) == 0x6 ? 1 : (c >> 4) == 0xe ? 2 : (c >> 3) == 0x1e ? 3 : 0;
    if (n == 0 || i + n >= s.size()) return false;  // a lead byte needs n continuation bytes
    std::uint32_t cp = c & (0x3f >> n);
    for (std::size_t k = 1; k <= n; ++k) {
      const auto d = static_cast<unsigned char>(s[i + k]);
      if ((d >> 6) != 0x2) return false;
      cp = (cp << 6) | (d & 0x3f);
    }
    // No overlong forms, no surrogates, nothing above U+10FFFF.
    constexpr std::uint32_t kMin[4] = {0, 0x80, 0x800, 0x10000};
    if (cp < kMin[n] || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff)) return false;
    i += n + 1;
  }
  return true;
}

void append_utf8(std::string& out, std::uint32_t cp) {
  if (cp < 0x80) {
    out += static_cast<char>(cp);
  } else if (cp < 0x800) {
    out += static_cast<char>(0xc0 | (cp >> 6));
    out += static_cast<char>(0x80 | (cp & 0x3f));
  } else if (cp < 0x10000) {
    out += static_cast<char>(0xe0 | (cp >> 12));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3f));
    out += static_cast<char>(0x80 | (cp & 0x3f));
  } else {
    out += static_cast<char>(0xf0 | (cp >> 18));
    out += static_cast<char>(0x80 | ((cp >> 12) & 0x3f));
    out += static_cast<char>(0x80 | ((cp >> 6) & 0x3f));
    out += static_cast<char>(0x80 | (cp & 0x3f));
  }
}

/// Drives a SketchSax with the values of a document; throws Error (Input) at the first syntax
/// error with its byte offset and the JSON path.
class JsonParser {
 public:
  static constexpr std::size_t kMaxDepth = 256;

  JsonParser(Source& source, SketchSax& sax, const std::filesystem::path& name)
      : in_(source), sax_(sax), name_(name) {}

  void parse() {
    if (in_.peek() == 0xef) {  // a UTF-8 byte order mark, as some Windows editors write
      for (int b : {0xef, 0xbb, 0xbf})
        if (in_.get() != b) fail("unexpected byte; expected a JSON document");
    }
    skip_space();
    value();
    while (!open_.empty()) {
      skip_space();
      const bool object = open_.back().object;
      const int c = in_.peek();
      if (c == (object ? '}' : ']')) {
        in_.get();
        open_.pop_back();
        object ? sax_.end_object() : sax_.end_array();
        continue;
      }
      if (!open_.back().first) {
        if (c != ',') fail(object ? "expected ',' or '}' after an object member"
                                  : "expected ',' or ']' after an array element");
        in_.get();
        skip_space();
      }
      open_.back().first = false;
      if (object) {
        if (in_.peek() != '"') fail("expected a key (a string in double quotes)");
        read_string();
        sax_.key(text_);
        skip_space();
        if (in_.get() != ':') fail("expected ':' after a key");
        skip_space();
      }
      value();
    }
    skip_space();
    if (in_.peek() >= 0) fail("unexpected text after the end of the document");
  }

 private:
  struct Open {
    bool object;
    bool first = true;
  };

  [[noreturn]] void fail(const std::string& what) const {
    const std::string at = sax_.path();
    throw Error::input_at_byte(name_, in_.offset(), (at.empty() ? "" : "in " + at + ": ") + what);
  }

  void skip_space() {
    for (int c = in_.peek(); c == ' ' || c == '\n' || c == '\r' || c == '\t'; c = in_.peek())
      in_.get();
  }

  void open(bool object) {
    if (open_.size() >= kMaxDepth) fail("nested deeper than " + std::to_string(kMaxDepth) + " levels");
    in_.get();
    open_.push_back({object});
    object ? sax_.start_object() : sax_.start_array();
  }

  void value() {
    const int c = in_.peek();
    switch (c) {
      case '{': open(true); break;
      case '[': open(false); break;
      case '"':
        read_string();
        sax_.string(text_);
        break;
      case 't': literal("true"); sax_.boolean(true); break;
      case 'f': literal("false"); sax_.boolean(false); break;
      case 'n': literal("null"); sax_.null(); break;
      case -1: fail("unexpected end of input; expected a value");
      default:
        if (c == '-' || (c >= '0' && c <= '9')) {
          number();
        } else {
          const char byte = static_cast<char>(c);
          fail("unexpected character " + io_detail::excerpt({&byte, 1}) + "; expected a value");
        }
    }
  }

  void literal(std::string_view word) {
    for (char w : word) {
      if (in_.peek() != w) fail("invalid literal; expected '" + std::string(word) + "'");
      in_.get();
    }
  }

  std::size_t digits() {
    std::size_t n = 0;
    for (int c = in_.peek(); c >= '0' && c <= '9'; c = in_.peek(), ++n) text_ += static_cast<char>(in_.get());
    return n;
  }

  void number() {
    text_.clear();
    if (in_.peek() == '-') text_ += static_cast<char>(in_.get());
    if (in_.peek() == '0') text_ += static_cast<char>(in_.get());
    else if (digits() == 0) fail("expected a digit");
    bool integral = true;
    if (in_.peek() == '.') {
      integral = false;
      text_ += static_cast<char>(in_.get());
      if (digits() == 0) fail("expected a digit after '.'");
    }
    if (in_.peek() == 'e' || in_.peek() == 'E') {
      integral = false;
      text_ += static_cast<char>(in_.get());
      if (in_.peek() == '+' || in_.peek() == '-') text_ += static_cast<char>(in_.get());
      if (digits() == 0) fail("expected a digit in the exponent");
    }
    const char* first = text_.data();
    const char* last = first + text_.size();
    if (integral) {  // integers that do not fit 64 bits are read as doubles below
      if (text_[0] == '-') {
        std::int64_t i;
        if (const auto r = std::from_chars(first, last, i); r.ec == std::errc() && r.ptr == last)
          return sax_.number_integer(i);
      } else {
        std::uint64_t u;
        if (const auto r = std::from_chars(first, last, u); r.ec == std::errc() && r.ptr == last)
          return sax_.number_unsigned(u);
      }
    }
    double d;
    const auto r = std::from_chars(first, last, d);
    if (r.ec != std::errc() || r.ptr != last) fail("number out of range: " + text_);
    sax_.number_float(d, text_);
  }

  unsigned hex4() {
    unsigned v = 0;
    for (int k = 0; k < 4; ++k) {
      const int c = in_.get();
      const int d = c >= '0' && c <= '9' ? c - '0' : c >= 'a' && c <= 'f' ? c - 'a' + 10
                  : c >= 'A' && c <= 'F' ? c - 'A' + 10 : -1;
      if (d < 0) fail("expected 4 hex digits after \\u");
      v = v * 16 + static_cast<unsigned>(d);
    }
    return v;
  }

  void read_string() {
    in_.get();  // the opening quote
    text_.clear();
    for (;;) {
      const int c = in_.get();
      if (c == '"') break;
      if (c < 0) fail("unexpected end of input inside a string");
      if (c < 0x20) fail("control character inside a string (escape it)");
      if (c != '\\') {
        text_ += static_cast<char>(c);
        continue;
      }
      const int e = in_.get();
      switch (e) {
        case '"': text_ += '"'; break;
        case '\\': text_ += '\\'; break;
        case '/': text_ += '/'; break;
        case 'b': text_ += '\b'; break;
        case 'f': text_ += '\f'; break;
        case 'n': text_ += '\n'; break;
        case 'r': text_ += '\r'; break;
        case 't': text_ += '\t'; break;
        case 'u': {
          std::uint32_t cp = hex4();
          if (cp >= 0xdc00 && cp <= 0xdfff) fail("unpaired low surrogate in \\u escape");
          if (cp >= 0xd800 && cp <= 0xdbff) {
            if (in_.get() != '\\' || in_.get() != 'u') fail("unpaired high surrogate in \\u escape");
            const std::uint32_t low = hex4();
            if (low < 0xdc00 || low > 0xdfff) fail("unpaired high surrogate in \\u escape");
            cp = 0x10000 + ((cp - 0xd800) << 10) + (low - 0xdc00);
          }
          append_utf8(text_, cp);
          break;
        }
        default: fail("invalid escape in a string");
      }
    }
    if (!valid_utf8(text_)) fail("invalid UTF-8 in a string");
  }

  Source& in_;
  SketchSax& sax_;
  const std::filesystem::path& name_;
  std::vector<Open> open_;
  std::string text_;  // the current string or number token
};

Sketch parse_sketch(Source& source, const std::filesystem::path& name, Warnings* warnings) {
  SketchSax sax(name, warnings, [&source] { return source.offset(); });
  JsonParser(source, sax, name).parse();
  return sax.finish();
}

// ---------------------------------------------------------------------------------------------
// Writing: streamed, one stroke at a time.

/// A JSON string literal; bytes that are not UTF-8 (a foreign brush name) become U+FFFD.
std::string quoted(const std::string& s) {
  return nlohmann::json(s).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

template <typename T>
void append(std::string& out, T value, const std::string& what) {
  if (!std::isfinite(value))
    throw Error::processing(what + " is not finite (NaN or Inf): clean the sketch first");
  io_detail::append_number(out, value);
}

/// params as nested objects: {"segment.epsilon": 0.01} -> {"segment": {"epsilon": 0.01}}.
/// (A small DOM: a sketch has a few dozen parameters. nlohmann prints doubles so that they read
/// back exactly.)
std::string params_json(const std::map<std::string, double>& params) {
  nlohmann::json root = nlohmann::json::object();
  for (const auto& [name, value] : params) {
    if (!std::isfinite(value))
      throw Error::processing("parameter '" + name + "' is not finite (NaN or Inf)");
    nlohmann::json* node = &root;
    std::size_t start = 0;
    for (std::size_t dot; (dot = name.find('.', start)) != std::string::npos; start = dot + 1) {
      const std::string part = name.substr(start, dot - start);
      if (part.empty()) throw Error::processing("parameter name '" + name + "' has an empty part");
      node = &(*node)[part];
      if (node->is_null()) *node = nlohmann::json::object();
      if (!node->is_object())
        throw Error::processing("parameter '" + name + "' is under another parameter's name");
    }
    const std::string last = name.substr(start);
    if (last.empty()) throw Error::processing("parameter name '" + name + "' has an empty part");
    if (node->contains(last))
      throw Error::processing("parameter '" + name + "' is also a group of parameters");
    (*node)[last] = value;
  }
  return root.dump();
}

void write_stroke(std::string& out, const Stroke& s, std::size_t index) {
  const std::string name = "stroke " + std::to_string(index);
  if (!s.attributes_consistent())
    throw Error::processing(name + ": per-point attributes do not match its point count");
  out += "    {\"id\": " + std::to_string(s.id) + ", \"width\": ";
  append(out, s.width, name + " width");
  out += ", \"color\": [";
  for (int c = 0; c < 4; ++c) {
    if (c) out += ", ";
    append(out, s.color[c], name + " colour");
  }
  out += "], \"brush\": " + quoted(s.brush) + ", \"layer\": " + std::to_string(s.layer) +
         ", \"boundary\": " + (s.boundary ? "true" : "false") +
         ", \"ignored\": " + (s.ignored ? "true" : "false") + ",\n     \"points\": [";
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    out += i ? ", [" : "[";
    for (int c = 0; c < 3; ++c) {
      if (c) out += ", ";
      append(out, s.points[i][c], name + " point " + std::to_string(i));
    }
    out += "]";
  }
  out += "]";
  if (!s.orientations.empty()) {
    out += ",\n     \"orientations\": [";
    for (std::size_t i = 0; i < s.orientations.size(); ++i) {
      out += i ? ", [" : "[";
      const auto& q = s.orientations[i].coeffs();  // x, y, z, w
      for (int c = 0; c < 4; ++c) {
        if (c) out += ", ";
        append(out, q[c], name + " orientation " + std::to_string(i));
      }
      out += "]";
    }
    out += "]";
  }
  if (!s.pressures.empty()) {
    out += ",\n     \"pressures\": [";
    for (std::size_t i = 0; i < s.pressures.size(); ++i) {
      if (i) out += ", ";
      append(out, s.pressures[i], name + " pressure " + std::to_string(i));
    }
    out += "]";
  }
  if (!s.timestamps_ms.empty()) {
    out += ",\n     \"timestamps_ms\": [";
    for (std::size_t i = 0; i < s.timestamps_ms.size(); ++i) {
      if (i) out += ", ";
      out += std::to_string(s.timestamps_ms[i]);
    }
    out += "]";
  }
  out += "}";
}

}  // namespace

Sketch read_json_text(std::string_view text, const std::filesystem::path& name, Warnings* warnings) {
  Source source(text);
  return parse_sketch(source, name, warnings);
}

Sketch read_json(const std::filesystem::path& file, Warnings* warnings) {
  // Streamed, so only the size is bounded (a JSON sketch may well be a single line).
  if (check_input_file(file, InputLimits::from_environment()) == 0)
    throw Error::input(file, "the file is empty");
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error::input(file, std::string("cannot open: ") + std::strerror(errno));
  Source source(in);
  Sketch sketch = parse_sketch(source, file, warnings);
  if (in.bad()) throw Error::input(file, "read error");
  return sketch;
}

void write_json(const Sketch& sketch, const std::filesystem::path& file) {
  // Streamed one stroke at a time (a 1M-point sketch never exists as one string). A non-finite
  // value throws midway; write_atomically then removes the partial temporary file.
  std::string head = "{\n  \"format\": " + quoted(std::string(kFormat)) +
                     ",\n  \"version\": " + std::to_string(kVersion) +
                     ",\n  \"units\": " + quoted(sketch.units) +
                     ",\n  \"provenance\": " + quoted(sketch.provenance) + ",\n  \"mirror\": ";
  if (sketch.mirror) {
    head += "{\"normal\": [";
    for (int c = 0; c < 3; ++c) {
      if (c) head += ", ";
      append(head, sketch.mirror->normal[c], "mirror normal");
    }
    head += "], \"offset\": ";
    append(head, sketch.mirror->offset, "mirror offset");
    head += "}";
  } else {
    head += "null";
  }
  if (sketch.rotation) {  // only when there is one: sketches without keep their bytes
    const auto triple = [&](const Eigen::Vector3d& v, const char* what) {
      head += "[";
      for (int c = 0; c < 3; ++c) {
        if (c) head += ", ";
        append(head, v[c], what);
      }
      head += "]";
    };
    head += ",\n  \"rotation\": {\"center\": ";
    triple(sketch.rotation->center, "rotation center");
    head += ", \"axis\": ";
    triple(sketch.rotation->axis, "rotation axis");
    head += ", \"count\": " + std::to_string(sketch.rotation->count) + "}";
  }
  head += ",\n  \"params\": " + params_json(sketch.params) + ",\n  \"strokes\": [";
  write_atomically(file, [&](std::ostream& out) {
    out << head;
    std::string text;
    for (std::size_t i = 0; i < sketch.strokes.size(); ++i) {
      text.assign(i ? ",\n" : "\n");
      write_stroke(text, sketch.strokes[i], i);
      out.write(text.data(), static_cast<std::streamsize>(text.size()));
    }
    out << (sketch.strokes.empty() ? "]\n}\n" : "\n  ]\n}\n");
  });
}

}  // namespace sketchsurf
