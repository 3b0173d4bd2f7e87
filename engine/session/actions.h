#pragma once
// The panel's actions as data (input::TrackAction), applied to a session: what a recorded track
// replays and what the studio's panel and keys do, through one function.

#include <string>

#include "engine/input/track.h"
#include "engine/session/session.h"

namespace sketchsurf::session {

/// Applies `action` (see input::TrackAction for the names and arguments) and returns one line
/// saying what happened ("tool: erase", "undo: draw", "nothing to undo"). Throws Error (Usage)
/// for an unknown action or bad arguments, Error (Input) for a file that cannot be opened.
std::string apply_action(SketchSession& session, const input::TrackAction& action);

/// Shorthands that build the actions the panel records.
input::TrackAction tool_action(Tool tool);
input::TrackAction simple_action(const std::string& name);  ///< undo, redo, clear, surface, clear_rotation, ...
input::TrackAction mirror_action(const Plane& plane);
input::TrackAction param_action(const std::string& name, double value);
/// An aid on (1) or off (0), or its value ("smoothing" rounds, "snap_radius").
input::TrackAction aid_action(const std::string& name, double value);
input::TrackAction plane_action(const Plane& plane);
input::TrackAction rotation_action(const RotationPattern& pattern);
input::TrackAction open_action(const std::string& file);

}  // namespace sketchsurf::session
