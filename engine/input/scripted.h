#pragma once
// ScriptedController: replays a recorded track (track.h) as a controller, frame by frame and
// deterministically: every sample and action comes out once, in the recorded order, whatever the
// frame rate, so a replay gives the same sketch as the session that recorded it.

#include <cstddef>
#include <vector>

#include "engine/input/controller.h"
#include "engine/input/track.h"

namespace sketchsurf::input {

class ScriptedController : public Controller6DoF {
 public:
  explicit ScriptedController(Track track);

  /// The controller samples with time <= now_s not returned yet (actions are skipped: use
  /// poll_events() to get both).
  std::vector<ControllerState> poll(double now_s) override;
  /// The latest sample returned (a default, untracked state before the first).
  ControllerState current() const override { return current_; }

  /// The events (samples and actions) with time <= now_s not returned yet, in track order.
  std::vector<TrackEvent> poll_events(double now_s);
  /// True once every event has been returned.
  bool finished() const { return next_ >= track_.events.size(); }
  /// The time of the track's last event.
  double duration() const { return track_.duration(); }
  const Track& track() const { return track_; }

 private:
  Track track_;
  std::size_t next_ = 0;
  ControllerState current_;
};

}  // namespace sketchsurf::input
