#include "engine/session/actions.h"

#include <algorithm>
#include <cmath>

#include "surfacing/error.h"

namespace sketchsurf::session {

std::string apply_action(SketchSession& session, const input::TrackAction& a) {
  if (a.name == "tool") {
    const auto tool = parse_tool(a.text);
    if (!tool) throw Error::usage("unknown tool '" + a.text + "' (tools: draw, erase, boundary, ignore, plane)");
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
  if (a.name == "plane") {
    if (a.values.size() != 4) throw Error::usage("plane: expected the plane as 4 numbers a,b,c,d");
    const Eigen::Vector3d n(a.values[0], a.values[1], a.values[2]);
    if (!(n.norm() > 0.0) || !n.allFinite() || !std::isfinite(a.values[3]))
      throw Error::usage("plane: the drawing plane needs a finite, non-zero normal");
    DrawingOptions d = session.drawing();
    d.plane = {n.normalized(), a.values[3] / n.norm()};
    session.set_drawing(d);
    return "drawing plane moved";
  }
  if (a.name == "aid") {
    if (a.values.size() != 1) throw Error::usage("aid: expected one value");
    DrawingOptions d = session.drawing();
    const double v = a.values[0];
    const auto on_off = [&](bool& flag) {
      flag = v != 0.0;
      return a.text + (flag ? " on" : " off");
    };
    std::string said;
    if (a.text == "plane_guide") said = on_off(d.plane_guide);
    else if (a.text == "snap") said = on_off(d.snap);
    else if (a.text == "oversketch") said = on_off(d.oversketch);
    else if (a.text == "straight") said = on_off(d.straight);
    else if (a.text == "smoothing") {
      if (v != std::floor(v)) throw Error::usage("aid: smoothing is a whole number of rounds");
      d.smoothing = static_cast<int>(std::clamp(v, -1.0, 1001.0));
      said = "smoothing " + std::to_string(d.smoothing);
    } else if (a.text == "snap_radius") {
      d.snap_radius = v;
      said = "snap radius " + std::to_string(v);
    } else {
      throw Error::usage("unknown aid '" + a.text +
                         "' (aids: plane_guide, snap, oversketch, straight, smoothing, snap_radius)");
    }
    session.set_drawing(d);
    return said;
  }
  if (a.name == "rotation") {
    if (a.values.size() != 7) throw Error::usage("rotation: expected centre, axis and count (7 numbers)");
    RotationPattern r;
    r.center = {a.values[0], a.values[1], a.values[2]};
    r.axis = {a.values[3], a.values[4], a.values[5]};
    if (a.values[6] != std::floor(a.values[6])) throw Error::usage("rotation: the count is a whole number");
    r.count = static_cast<int>(std::clamp(a.values[6], 0.0, 1000.0));
    session.set_rotation(r);
    return "rotation " + std::to_string(r.count) + "-fold on";
  }
  if (a.name == "clear_rotation")
    return session.set_rotation(std::nullopt) ? "rotation off" : "rotation already off";
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

input::TrackAction aid_action(const std::string& name, double value) { return {"aid", name, {value}}; }

input::TrackAction plane_action(const Plane& plane) {
  return {"plane", "", {plane.normal.x(), plane.normal.y(), plane.normal.z(), plane.offset}};
}

input::TrackAction rotation_action(const RotationPattern& r) {
  return {"rotation", "", {r.center.x(), r.center.y(), r.center.z(), r.axis.x(), r.axis.y(), r.axis.z(),
                           double(r.count)}};
}

input::TrackAction param_action(const std::string& name, double value) {
  return {"param", name, {value}};
}

input::TrackAction open_action(const std::string& file) { return {"open", file, {}}; }

}  // namespace sketchsurf::session
