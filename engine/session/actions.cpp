#include "engine/session/actions.h"

#include "surfacing/error.h"

namespace sketchsurf::session {

std::string apply_action(SketchSession& session, const input::TrackAction& a) {
  if (a.name == "tool") {
    const auto tool = parse_tool(a.text);
    if (!tool) throw Error::usage("unknown tool '" + a.text + "' (tools: draw, erase, boundary, ignore)");
    session.set_tool(*tool);
    return "tool: " + a.text;
  }
  if (a.name == "undo") {
    const std::string name = session.undo_name();
    return session.undo() ? "undo: " + name : "nothing to undo";
  }
  if (a.name == "redo") {
    const std::string name = session.redo_name();
    return session.redo() ? "redo: " + name : "nothing to redo";
  }
  if (a.name == "clear") return session.clear() ? "cleared" : "nothing to clear";
  if (a.name == "surface") return session.surface() ? "surfacing started" : "surfacing is still running";
  if (a.name == "cancel") {
    session.cancel_surface();
    return "surfacing cancelled";
  }
  if (a.name == "clear_mirror") return session.set_mirror(std::nullopt) ? "mirror off" : "mirror already off";
  if (a.name == "mirror") {
    if (a.values.size() != 4) throw Error::usage("mirror: expected the plane as 4 numbers a,b,c,d");
    const Plane plane{Eigen::Vector3d(a.values[0], a.values[1], a.values[2]), a.values[3]};
    session.set_mirror(plane);
    return "mirror on";
  }
  if (a.name == "param") {
    if (a.values.size() != 1) throw Error::usage("param: expected one value");
    session.set_param(a.text, a.values[0]);
    return "param: " + a.text + " = " + std::to_string(a.values[0]);
  }
  if (a.name == "open") {
    session.open(a.text);
    return "opened " + a.text;
  }
  throw Error::usage("unknown action '" + a.name + "'");
}

input::TrackAction tool_action(Tool tool) { return {"tool", std::string(tool_name(tool)), {}}; }

input::TrackAction simple_action(const std::string& name) { return {name, "", {}}; }

input::TrackAction mirror_action(const Plane& plane) {
  return {"mirror", "", {plane.normal.x(), plane.normal.y(), plane.normal.z(), plane.offset}};
}

input::TrackAction param_action(const std::string& name, double value) {
  return {"param", name, {value}};
}

input::TrackAction open_action(const std::string& file) { return {"open", file, {}}; }

}  // namespace sketchsurf::session
