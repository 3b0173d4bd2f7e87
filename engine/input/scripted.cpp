#include "engine/input/scripted.h"

namespace sketchsurf::input {

ScriptedController::ScriptedController(Track track) : track_(std::move(track)) {
  current_.tracked = false;
}

std::vector<TrackEvent> ScriptedController::poll_events(double now_s) {
  std::vector<TrackEvent> out;
  while (next_ < track_.events.size() && track_.events[next_].time_s <= now_s) {
    const TrackEvent& e = track_.events[next_++];
    if (e.state) current_ = *e.state;
    out.push_back(e);
  }
  return out;
}

std::vector<ControllerState> ScriptedController::poll(double now_s) {
  std::vector<ControllerState> out;
  for (const TrackEvent& e : poll_events(now_s))
    if (e.state) out.push_back(*e.state);
  return out;
}

}  // namespace sketchsurf::input
