#pragma once
// Tracks: a recorded session, as timestamped controller samples and the panel's actions in the
// order they happened (JSON, sketchsurf-track version 1; the README's "Track format"). The studio
// writes one with --record and replays one with --replay (ScriptedController, scripted.h).
//
//   {"format": "sketchsurf-track", "version": 1,
//    "events": [
//     {"t": 0.0, "position": [0, 0, 0], "orientation": [1, 0, 0, 0], "trigger": 1, "buttons": ["draw"]},
//     {"t": 0.5, "action": "tool", "value": "erase"},
//     ...]}

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "engine/input/controller.h"

namespace sketchsurf::input {

/// Something done in the panel (or by a key) rather than with the controller. The actions and
/// their arguments:
///   tool   text = "draw" | "erase" | "boundary" | "ignore" | "plane"
///   undo, redo, clear, surface, cancel, clear_mirror, clear_rotation    (no arguments)
///   mirror values = {nx, ny, nz, d}: the plane n . x + d = 0 (n is normalised when read)
///   param  text = a Params name ("segment.epsilon"), values = {value}
///   open   text = a sketch file
///   aid    text = "plane_guide" | "snap" | "oversketch" | "straight" (values = {0 or 1}),
///          "smoothing" (rounds), "snap_radius" (fraction of the reference size)
///   plane  values = {nx, ny, nz, d}: the drawing plane (n normalised when read)
///   rotation values = {cx, cy, cz, ax, ay, az, count}: the n-fold rotational pattern
struct TrackAction {
  std::string name;            ///< one of track_action_names()
  std::string text;            ///< tool name, parameter name or file, by action
  std::vector<double> values;  ///< mirror plane or parameter value, by action
};

/// One event of a track: a controller sample or an action, at time `time_s`.
struct TrackEvent {
  double time_s = 0.0;                    ///< seconds from the start, never decreasing
  std::optional<ControllerState> state;   ///< a controller sample (its time_s equals time_s)
  std::optional<TrackAction> action;      ///< or an action; exactly one of the two is set
};

/// A whole recording.
struct Track {
  std::vector<TrackEvent> events;  ///< in the order they happened

  /// Time of the last event (0 for an empty track).
  double duration() const { return events.empty() ? 0.0 : events.back().time_s; }
};

/// The action names a track may hold, in the order of the comment above.
const std::vector<std::string>& track_action_names();
/// The tool names of the "tool" action: draw, erase, boundary, ignore, plane.
const std::vector<std::string>& track_tool_names();

/// Parses the text of a track. Throws Error (Input) naming `name`, the line and the event
/// ("FILE:LINE: events[12].position[1]: ...") for JSON that does not parse, a missing or wrong
/// field, a number that is not finite (a NaN position), an unknown button, action or tool, or
/// times that go backwards.
Track parse_track(std::string_view text, const std::filesystem::path& name);
/// Reads a track file (see parse_track). Throws Error (Input) when it cannot be read.
Track read_track(const std::filesystem::path& file);
/// The track as JSON text, one event per line, every number written so that it reads back
/// bit-identical.
std::string track_json(const Track& track);
/// Writes the track atomically (temporary file + rename). Throws Error (Processing).
void write_track(const Track& track, const std::filesystem::path& file);

}  // namespace sketchsurf::input
