#include "engine/input/track.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "surfacing/error.h"
#include "surfacing/sketch/io/atomic_file.h"

namespace sketchsurf::input {

namespace {

constexpr std::string_view kFormat = "sketchsurf-track";
constexpr int kVersion = 1;

using json = nlohmann::json;

/// Byte offsets of the elements of the array that is the value of the root object's member
/// `key` (the text is valid JSON: nlohmann parsed it first). Lets errors name a line.
std::vector<std::size_t> member_array_offsets(std::string_view text, std::string_view key) {
  std::vector<std::size_t> offsets;
  int depth = 0;
  bool expect_key = false, in_target = false, expect_element = false;
  std::string last_key;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r') continue;
    if (in_target && depth == 2 && expect_element && c != ']') {
      offsets.push_back(i);
      expect_element = false;
    }
    if (c == '"') {
      const std::size_t start = i + 1;
      for (++i; i < text.size() && text[i] != '"'; ++i)
        if (text[i] == '\\') ++i;
      if (depth == 1 && expect_key) {
        last_key.assign(text.substr(start, i - start));
        expect_key = false;
      }
      continue;
    }
    switch (c) {
      case '{':
      case '[':
        ++depth;
        if (depth == 1) expect_key = c == '{';
        if (depth == 2 && c == '[' && last_key == key) in_target = expect_element = true;
        break;
      case '}':
      case ']':
        if (depth == 2) in_target = false;
        --depth;
        break;
      case ',':
        if (depth == 1) expect_key = true;
        if (depth == 2 && in_target) expect_element = true;
        break;
      default:
        break;
    }
  }
  return offsets;
}

std::size_t line_of(std::string_view text, std::size_t offset) {
  offset = std::min(offset, text.size());
  return 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + offset, '\n'));
}

std::string describe(const json& v) {
  if (v.is_null()) return "null";
  if (v.is_string()) return "the string " + v.dump();
  if (v.is_boolean()) return v.get<bool>() ? "true" : "false";
  if (v.is_number()) return v.dump();
  if (v.is_array()) return "an array";
  return "an object";
}

/// Reads the events of a parsed track, naming the line of the event at fault.
class EventReader {
 public:
  EventReader(std::string_view text, const std::filesystem::path& name)
      : name_(name), offsets_(member_array_offsets(text, "events")), text_(text) {}

  [[noreturn]] void fail(std::size_t event, const std::string& where, const std::string& what) const {
    const std::size_t line = event < offsets_.size() ? line_of(text_, offsets_[event]) : 1;
    throw Error::input_at_line(name_, line,
                               "events[" + std::to_string(event) + "]" + where + ": " + what);
  }

  double number(const json& v, std::size_t event, const std::string& where) const {
    if (!v.is_number()) fail(event, where, "expected a number, got " + describe(v));
    const double x = v.get<double>();
    if (!std::isfinite(x)) fail(event, where, "expected a finite number, got " + v.dump());
    return x;
  }

  std::vector<double> numbers(const json& v, std::size_t count, std::size_t event,
                              const std::string& where) const {
    if (!v.is_array() || v.size() != count)
      fail(event, where, "expected an array of " + std::to_string(count) + " numbers, got " +
                             (v.is_array() ? "an array of " + std::to_string(v.size()) : describe(v)));
    std::vector<double> out;
    for (std::size_t i = 0; i < count; ++i)
      out.push_back(number(v[i], event, where + "[" + std::to_string(i) + "]"));
    return out;
  }

  std::string string(const json& v, std::size_t event, const std::string& where) const {
    if (!v.is_string()) fail(event, where, "expected a string, got " + describe(v));
    return v.get<std::string>();
  }

  TrackEvent read(const json& e, std::size_t i, double previous_time) const {
    if (!e.is_object()) fail(i, "", "expected an object, got " + describe(e));
    if (!e.contains("t")) fail(i, "", "missing \"t\" (the time in seconds)");
    TrackEvent event;
    event.time_s = number(e["t"], i, ".t");
    if (event.time_s < previous_time)
      fail(i, ".t", "time " + e["t"].dump() + " is before the previous event's (" +
                        json(previous_time).dump() + "); events must be in time order");
    if (e.contains("action") == e.contains("position"))
      fail(i, "", "expected either \"position\" (a controller sample) or \"action\"");
    if (e.contains("action"))
      event.action = read_action(e, i);
    else
      event.state = read_state(e, i, event.time_s);
    return event;
  }

 private:
  void only(const json& e, std::size_t i, std::initializer_list<const char*> known) const {
    for (const auto& [key, _] : e.items())
      if (std::none_of(known.begin(), known.end(), [&](const char* k) { return key == k; })) {
        std::string list;
        for (const char* k : known) list += std::string(list.empty() ? "" : ", ") + k;
        fail(i, "", "unknown field \"" + key + "\" (expected " + list + ")");
      }
  }

  ControllerState read_state(const json& e, std::size_t i, double time) const {
    only(e, i, {"t", "position", "orientation", "trigger", "buttons", "tracked"});
    ControllerState s;
    s.time_s = time;
    const auto p = numbers(e["position"], 3, i, ".position");
    s.pose.position = {p[0], p[1], p[2]};
    if (e.contains("orientation")) {
      const auto q = numbers(e["orientation"], 4, i, ".orientation");
      Eigen::Quaterniond o(q[0], q[1], q[2], q[3]);
      if (!(o.norm() > 1e-9)) fail(i, ".orientation", "a zero quaternion is no orientation");
      // Unit quaternions as written stay bit-identical (replays are exact); others are normalised.
      s.pose.orientation = std::abs(o.norm() - 1.0) > 1e-12 ? o.normalized() : o;
    }
    if (e.contains("buttons")) {
      const json& b = e["buttons"];
      if (!b.is_array()) fail(i, ".buttons", "expected an array of button names, got " + describe(b));
      for (std::size_t k = 0; k < b.size(); ++k) {
        const std::string where = ".buttons[" + std::to_string(k) + "]";
        const std::string n = string(b[k], i, where);
        const auto button = parse_button(n);
        if (!button) {
          std::string list;
          for (Button known : all_buttons())
            list += std::string(list.empty() ? "" : ", ") + std::string(button_name(known));
          fail(i, where, "unknown button \"" + n + "\" (buttons: " + list + ")");
        }
        s.set(*button, true);
      }
    }
    if (e.contains("trigger")) {
      const double t = number(e["trigger"], i, ".trigger");
      if (t < 0.0 || t > 1.0) fail(i, ".trigger", "the trigger is in [0, 1], got " + e["trigger"].dump());
      s.trigger = static_cast<float>(t);
    } else {
      s.trigger = s.pressed(Button::Draw) ? 1.0f : 0.0f;
    }
    if (e.contains("tracked")) {
      if (!e["tracked"].is_boolean()) fail(i, ".tracked", "expected true or false, got " + describe(e["tracked"]));
      s.tracked = e["tracked"].get<bool>();
    }
    return s;
  }

  TrackAction read_action(const json& e, std::size_t i) const {
    TrackAction a;
    a.name = string(e["action"], i, ".action");
    const auto& names = track_action_names();
    if (std::find(names.begin(), names.end(), a.name) == names.end()) {
      std::string list;
      for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
      fail(i, ".action", "unknown action \"" + a.name + "\" (actions: " + list + ")");
    }
    if (a.name == "tool") {
      only(e, i, {"t", "action", "value"});
      a.text = string(e.value("value", json()), i, ".value");
      const auto& tools = track_tool_names();
      if (std::find(tools.begin(), tools.end(), a.text) == tools.end())
        fail(i, ".value", "unknown tool \"" + a.text + "\" (tools: draw, erase, boundary, ignore, plane)");
    } else if (a.name == "mirror" || a.name == "plane") {
      only(e, i, {"t", "action", "plane"});
      a.values = numbers(e.value("plane", json()), 4, i, ".plane");
      const double n = Eigen::Vector3d(a.values[0], a.values[1], a.values[2]).norm();
      if (!(n > 1e-12)) fail(i, ".plane", "the plane's normal (the first three numbers) is zero");
      for (double& v : a.values) v /= n;
    } else if (a.name == "rotation") {
      only(e, i, {"t", "action", "center", "axis", "count"});
      a.values = numbers(e.value("center", json()), 3, i, ".center");
      const auto axis = numbers(e.value("axis", json()), 3, i, ".axis");
      if (!(Eigen::Vector3d(axis[0], axis[1], axis[2]).norm() > 1e-12)) fail(i, ".axis", "the axis is zero");
      const double count = number(e.value("count", json()), i, ".count");
      if (count != std::floor(count) || count < 2 || count > 360)
        fail(i, ".count", "expected an integer from 2 to 360");
      a.values.insert(a.values.end(), axis.begin(), axis.end());
      a.values.push_back(count);
    } else if (a.name == "param" || a.name == "aid") {
      only(e, i, {"t", "action", "name", "value"});
      a.text = string(e.value("name", json()), i, ".name");
      a.values = {number(e.value("value", json()), i, ".value")};
    } else if (a.name == "open") {
      only(e, i, {"t", "action", "path"});
      a.text = string(e.value("path", json()), i, ".path");
    } else {
      only(e, i, {"t", "action"});
    }
    return a;
  }

  std::filesystem::path name_;
  std::vector<std::size_t> offsets_;
  std::string_view text_;
};

nlohmann::ordered_json event_json(const TrackEvent& e) {
  nlohmann::ordered_json j;
  j["t"] = e.time_s;
  if (e.state) {
    const ControllerState& s = *e.state;
    const auto& p = s.pose.position;
    const auto& q = s.pose.orientation;
    j["position"] = {p.x(), p.y(), p.z()};
    j["orientation"] = {q.w(), q.x(), q.y(), q.z()};
    j["trigger"] = static_cast<double>(s.trigger);
    auto buttons = nlohmann::ordered_json::array();
    for (Button b : all_buttons())
      if (s.pressed(b)) buttons.push_back(std::string(button_name(b)));
    j["buttons"] = buttons;
    if (!s.tracked) j["tracked"] = false;
  } else if (e.action) {
    const TrackAction& a = *e.action;
    j["action"] = a.name;
    if (a.name == "tool") j["value"] = a.text;
    if (a.name == "mirror" || a.name == "plane") j["plane"] = a.values;
    if (a.name == "rotation" && a.values.size() == 7) {
      j["center"] = {a.values[0], a.values[1], a.values[2]};
      j["axis"] = {a.values[3], a.values[4], a.values[5]};
      j["count"] = static_cast<int>(a.values[6]);
    }
    if (a.name == "param" || a.name == "aid") {
      j["name"] = a.text;
      j["value"] = a.values.empty() ? 0.0 : a.values[0];
    }
    if (a.name == "open") j["path"] = a.text;
  }
  return j;
}

}  // namespace

const std::vector<Button>& all_buttons() {
  static const std::vector<Button> buttons{Button::Draw, Button::Grab, Button::Undo, Button::Redo,
                                           Button::Menu};
  return buttons;
}

std::string_view button_name(Button button) {
  switch (button) {
    case Button::Draw: return "draw";
    case Button::Grab: return "grab";
    case Button::Undo: return "undo";
    case Button::Redo: return "redo";
    case Button::Menu: return "menu";
  }
  return "?";
}

std::optional<Button> parse_button(std::string_view name) {
  for (Button b : all_buttons())
    if (button_name(b) == name) return b;
  return std::nullopt;
}

const std::vector<std::string>& track_action_names() {
  static const std::vector<std::string> names{"tool",  "undo",   "redo",         "clear",
                                              "surface", "cancel", "clear_mirror", "mirror",
                                              "param", "open", "aid", "plane", "rotation",
                                              "clear_rotation"};
  return names;
}

const std::vector<std::string>& track_tool_names() {
  static const std::vector<std::string> names{"draw", "erase", "boundary", "ignore", "plane"};
  return names;
}

Track parse_track(std::string_view text, const std::filesystem::path& name) {
  json doc;
  try {
    doc = json::parse(text.begin(), text.end());
  } catch (const json::parse_error& e) {
    const std::size_t at = e.byte > 0 ? e.byte - 1 : 0;
    const std::size_t line_start = text.rfind('\n', at == 0 ? 0 : at - 1);
    const std::size_t column = at - (line_start == std::string_view::npos ? 0 : line_start + 1) + 1;
    std::string what = e.what();
    if (const auto cut = what.find("] "); cut != std::string::npos) what = what.substr(cut + 2);
    throw Error::input_at_line(name, line_of(text, at),
                               "not valid JSON (column " + std::to_string(column) + "): " + what);
  } catch (const json::out_of_range& e) {  // a number beyond double's range ("1e999")
    std::string what = e.what();
    std::size_t at = 0;
    const auto open = what.find('\''), close = what.rfind('\'');
    if (open != std::string::npos && close > open) {
      const std::string token = what.substr(open + 1, close - open - 1);
      at = std::min(text.find(token), text.size());
      what = "the number " + token + " is out of range: not a finite number";
    }
    throw Error::input_at_line(name, line_of(text, at), what);
  }
  if (!doc.is_object() || doc.value("format", std::string()) != kFormat)
    throw Error::input(name, "not a track: expected a JSON object with \"format\": \"" +
                                 std::string(kFormat) + "\"");
  if (!doc.contains("version") || !doc["version"].is_number_integer() ||
      doc["version"].get<int>() != kVersion)
    throw Error::input(name, "unsupported track version (this studio reads version " +
                                 std::to_string(kVersion) + ")");
  if (!doc.contains("events") || !doc["events"].is_array())
    throw Error::input(name, "missing \"events\": an array of controller samples and actions");
  const EventReader reader(text, name);
  Track track;
  double previous = -std::numeric_limits<double>::infinity();
  const json& events = doc["events"];
  for (std::size_t i = 0; i < events.size(); ++i) {
    track.events.push_back(reader.read(events[i], i, previous));
    previous = track.events.back().time_s;
  }
  return track;
}

Track read_track(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error::input(file, "cannot open the track file");
  std::stringstream text;
  text << in.rdbuf();
  if (in.bad()) throw Error::input(file, "cannot read the track file");
  return parse_track(text.str(), file);
}

std::string track_json(const Track& track) {
  std::string out = "{\"format\": \"sketchsurf-track\", \"version\": 1,\n \"events\": [";
  for (std::size_t i = 0; i < track.events.size(); ++i) {
    out += i == 0 ? "\n  " : ",\n  ";
    out += event_json(track.events[i]).dump();
  }
  out += "\n ]}\n";
  return out;
}

void write_track(const Track& track, const std::filesystem::path& file) {
  const std::string text = track_json(track);
  write_atomically(file, [&](std::ostream& out) { out << text; });
}

}  // namespace sketchsurf::input
