#include "surfacing/sketch/io/json.h"

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>

#include "surfacing/error.h"
#include "surfacing/sketch/io/atomic_file.h"
#include "surfacing/sketch/io/text_io.h"

namespace sketchsurf {

namespace {

constexpr std::string_view kFormat = "sketchsurf-sketch";
constexpr std::int64_t kVersion = 1;

// ---------------------------------------------------------------------------------------------
// Reading: a SAX handler that streams straight into the Sketch. A DOM of a 1M-point file would
// hold 3M+ json values (hundreds of MB); the handler keeps only a stack of where it is.

/// One JSON value as the SAX parser delivers it.
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
  Document, Root, Mirror, Normal, Params, Strokes, Stroke, Points, Point, Orientations,
  Orientation, Pressures, Timestamps, Color, Skip
};

// Bits of the keys seen in one object, to refuse duplicates.
enum RootKey : std::uint32_t {
  kKeyFormat = 1, kKeyVersion = 2, kKeyUnits = 4, kKeyProvenance = 8, kKeyMirror = 16,
  kKeyParams = 32, kKeyStrokes = 64
};
enum StrokeKey : std::uint32_t {
  kKeyId = 1, kKeyPoints = 2, kKeyOrientations = 4, kKeyPressures = 8, kKeyTimestamps = 16,
  kKeyWidth = 32, kKeyColor = 64, kKeyBrush = 128, kKeyLayer = 256, kKeyBoundary = 512,
  kKeyIgnored = 1024
};
enum MirrorKey : std::uint32_t { kKeyNormal = 1, kKeyOffset = 2 };

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
  SketchSax(const std::filesystem::path& name, Warnings* warnings)
      : name_(name), warnings_(warnings) {
    stack_.emplace_back(Where::Document, false);
  }

  // --- nlohmann SAX interface -----------------------------------------------------------------
  bool null() { return value(Value(Value::Kind::Null)); }
  bool boolean(bool b) {
    Value v{Value::Kind::Boolean};
    v.boolean = b;
    return value(v);
  }
  bool number_integer(std::int64_t i) {
    Value v{Value::Kind::Integer};
    v.integer = i;
    return value(v);
  }
  bool number_unsigned(std::uint64_t u) {
    Value v{Value::Kind::Unsigned};
    v.unsigned_integer = u;
    return value(v);
  }
  bool number_float(double d, const std::string& token) {
    Value v{Value::Kind::Float};
    v.number = d;
    v.text = token;
    return value(v);
  }
  bool string(std::string& s) {
    Value v{Value::Kind::String};
    v.text = s;
    return value(v);
  }
  bool binary(nlohmann::json::binary_t&) { return value(Value(Value::Kind::Null)); }
  bool start_object(std::size_t) { return value(Value(Value::Kind::Object)); }
  bool start_array(std::size_t) { return value(Value(Value::Kind::Array)); }
  bool key(std::string& k) {
    Frame& f = stack_.back();
    f.key = k;
    return true;
  }
  bool end_object() { return end(); }
  bool end_array() { return end(); }
  bool parse_error(std::size_t position, const std::string&, const nlohmann::detail::exception& e) {
    std::string what = e.what();
    if (const auto p = what.find("] "); p != std::string::npos) what.erase(0, p + 2);
    const std::string at = path();
    throw Error::input_at_byte(name_, position, (at.empty() ? "" : "in " + at + ": ") + what);
  }

  Sketch finish() {
    if (!done_) fail("", "the document ended early");
    return std::move(sketch_);
  }

 private:
  [[noreturn]] void fail(const std::string& at, const std::string& what) const {
    throw Error::input(name_, (at.empty() ? "" : at + ": ") + what);
  }
  [[noreturn]] void expected(const std::string& what, const Value& got) const {
    fail(path(), "expected " + what + ", got " + got.describe());
  }

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

  void warn_once(const std::string& what) {
    if (warnings_ && warned_.insert(what).second) warnings_->push_back(what);
  }

  void push(Where where, bool array) { stack_.emplace_back(where, array); }

  // Claims key bit `bit` of the current object; a second occurrence is an error.
  void claim(std::uint32_t bit) {
    Frame& f = stack_.back();
    if (f.seen & bit) fail(path(), "duplicate key");
    f.seen |= bit;
  }

  // A key this version does not know: warned about once per pattern and skipped.
  void unknown(const Value& v, const std::string& pattern) {
    warn_once("unknown key '" + pattern + "' ignored");
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
  bool value(const Value& v) {
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
        push(Where::Orientation, true);
        break;
      case Where::Orientation:
        if (f.index >= 4) fail(path(), "a quaternion has 4 components [x, y, z, w]");
        tuple_[f.index] = finite_number(v);
        break;
      case Where::Pressures: stroke_.pressures.push_back(finite_float(v)); break;
      case Where::Timestamps:
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
    return true;
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
  bool end() {
    const Frame& f = stack_.back();
    switch (f.where) {
      case Where::Root:
        if (!(f.seen & kKeyFormat)) fail("", "no \"format\" key: not a sketchsurf sketch");
        if (!(f.seen & kKeyVersion)) fail("", "no \"version\" key");
        done_ = true;
        break;
      case Where::Mirror: end_mirror(f); break;
      case Where::Normal:
      case Where::Point:
      case Where::Orientation:
      case Where::Color: {
        const std::size_t want = f.where == Where::Normal ? 3 : f.where == Where::Point ? 3 : 4;
        if (f.index != want)
          fail(path(stack_.size() - 1), "expected " + std::to_string(want) + " numbers, got " +
                                            std::to_string(f.index));
        if (f.where == Where::Point) stroke_.points.emplace_back(tuple_[0], tuple_[1], tuple_[2]);
        if (f.where == Where::Orientation)
          stroke_.orientations.emplace_back(tuple_[3], tuple_[0], tuple_[1], tuple_[2]);
        break;
      }
      case Where::Stroke: end_stroke(f); break;
      default: break;
    }
    stack_.pop_back();
    if (stack_.back().array) ++stack_.back().index;
    return true;
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
  std::set<std::string> warned_;
  std::vector<Frame> stack_;
  Sketch sketch_;
  Stroke stroke_;
  double tuple_[4] = {0, 0, 0, 0};
  Eigen::Vector3d mirror_normal_ = Eigen::Vector3d::Zero();
  double mirror_offset_ = 0.0;
  bool done_ = false;
};

// ---------------------------------------------------------------------------------------------
// Writing: streamed, one stroke at a time.

std::string quoted(const std::string& s) { return nlohmann::json(s).dump(); }

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
  SketchSax sax(name, warnings);
  nlohmann::json::sax_parse(text.begin(), text.end(), &sax);
  return sax.finish();
}

Sketch read_json(const std::filesystem::path& file, Warnings* warnings) {
  const std::string text = io_detail::read_file(file);
  return read_json_text(text, file, warnings);
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
