// Tracks (engine/input/track.h): round trip bit for bit, and every kind of bad input named with
// its file, line and event.

#include <gtest/gtest.h>

#include <cmath>

#include "engine/input/scripted.h"
#include "engine/input/track.h"
#include "surfacing/error.h"

namespace sketchsurf::input {
namespace {

Track sample_track() {
  Track track;
  for (int i = 0; i < 5; ++i) {
    ControllerState s;
    s.time_s = 0.1 * i + 1e-17 * i;
    s.pose.position = {0.1 + 0.2 * i, -1.0 / 3.0, 1e-9 * i};
    s.pose.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3 * i, Eigen::Vector3d(1, 2, 3).normalized()));
    s.trigger = i == 0 ? 0.0f : 0.7f / float(i);
    s.set(Button::Draw, i > 0 && i < 4);
    s.set(Button::Undo, i == 4);
    s.tracked = i != 2;
    track.events.push_back({s.time_s, s, std::nullopt});
  }
  track.events.push_back({0.5, std::nullopt, TrackAction{"tool", "erase", {}}});
  track.events.push_back({0.5, std::nullopt, TrackAction{"mirror", "", {1.0, 0.0, 0.0, 0.25}}});
  track.events.push_back({0.6, std::nullopt, TrackAction{"param", "segment.epsilon", {0.02}}});
  track.events.push_back({0.7, std::nullopt, TrackAction{"surface", "", {}}});
  return track;
}

std::string error_of(const std::string& text) {
  try {
    parse_track(text, "bad.track.json");
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input) << e.what();
    return e.what();
  }
  ADD_FAILURE() << "no error for:\n" << text;
  return "";
}

const char* kHeader = "{\"format\": \"sketchsurf-track\", \"version\": 1,\n \"events\": [\n";

TEST(Track, RoundTripsBitForBit) {
  const Track track = sample_track();
  const Track back = parse_track(track_json(track), "t.json");
  ASSERT_EQ(back.events.size(), track.events.size());
  for (std::size_t i = 0; i < track.events.size(); ++i) {
    const TrackEvent &a = track.events[i], &b = back.events[i];
    EXPECT_EQ(a.time_s, b.time_s);
    ASSERT_EQ(a.state.has_value(), b.state.has_value());
    if (a.state) {
      EXPECT_EQ(a.state->pose.position, b.state->pose.position);
      EXPECT_EQ(a.state->pose.orientation.coeffs(), b.state->pose.orientation.coeffs());
      EXPECT_EQ(a.state->trigger, b.state->trigger);
      EXPECT_EQ(a.state->buttons, b.state->buttons);
      EXPECT_EQ(a.state->tracked, b.state->tracked);
    } else {
      EXPECT_EQ(a.action->name, b.action->name);
      EXPECT_EQ(a.action->text, b.action->text);
      EXPECT_EQ(a.action->values, b.action->values);
    }
  }
  EXPECT_DOUBLE_EQ(back.duration(), 0.7);
}

TEST(Track, WritesOneEventPerLine) {
  const std::string text = track_json(sample_track());
  EXPECT_EQ(std::count(text.begin(), text.end(), '\n'), 2 + 9 + 1);
}

TEST(Track, DrawWithoutTriggerMeansFullPressure) {
  const Track t = parse_track(std::string(kHeader) +
                                  "{\"t\": 0, \"position\": [0, 0, 0], \"buttons\": [\"draw\"]},\n"
                                  "{\"t\": 1, \"position\": [1, 0, 0]}]}",
                              "t.json");
  EXPECT_EQ(t.events[0].state->trigger, 1.0f);
  EXPECT_TRUE(t.events[0].state->pressed(Button::Draw));
  EXPECT_EQ(t.events[1].state->trigger, 0.0f);
  EXPECT_TRUE(t.events[1].state->pose.orientation.isApprox(Eigen::Quaterniond::Identity()));
}

TEST(Track, InvalidJsonNamesFileLineAndColumn) {
  const std::string e = error_of(std::string(kHeader) +
                                 "{\"t\": 0, \"position\": [0, 0, 0]},\n"
                                 "{\"t\": 1, \"position\": [0, NaN, 0]}]}");
  EXPECT_NE(e.find("bad.track.json:4:"), std::string::npos) << e;
  EXPECT_NE(e.find("(column "), std::string::npos) << e;
  EXPECT_NE(e.find("not valid JSON"), std::string::npos) << e;
}

TEST(Track, NanOrInfinitePositionNamesTheEvent) {
  for (const std::string nan : {"\"NaN\"", "null", "1e999", "-1e999"}) {
    const std::string e = error_of(std::string(kHeader) +
                                   "{\"t\": 0, \"position\": [0, 0, 0]},\n"
                                   "{\"t\": 0.5, \"action\": \"undo\"},\n"
                                   "{\"t\": 1, \"position\": [0, " + nan + ", 0]}]}");
    if (nan.find("e999") != std::string::npos)  // beyond double: the parser refuses the token
      EXPECT_NE(e.find("bad.track.json:5: the number " + nan + " is out of range"), std::string::npos) << e;
    else
      EXPECT_NE(e.find("bad.track.json:5: events[2].position[1]"), std::string::npos) << e;
  }
  const std::string q = error_of(std::string(kHeader) +
                                 "{\"t\": 0, \"position\": [0, 0, 0], \"orientation\": [0, 0, 0, 0]}]}");
  EXPECT_NE(q.find("events[0].orientation"), std::string::npos) << q;
  const std::string t = error_of(std::string(kHeader) + "{\"t\": \"soon\", \"position\": [0, 0, 0]}]}");
  EXPECT_NE(t.find("events[0].t: expected a number"), std::string::npos) << t;
}

TEST(Track, UnknownButtonActionToolOrFieldIsNamed) {
  const std::string b = error_of(std::string(kHeader) +
                                 "\n\n{\"t\": 0, \"position\": [0, 0, 0], \"buttons\": [\"draw\", \"jump\"]}]}");
  EXPECT_NE(b.find("bad.track.json:5: events[0].buttons[1]: unknown button \"jump\""), std::string::npos) << b;
  EXPECT_NE(b.find("draw, grab, undo, redo, menu"), std::string::npos) << b;
  const std::string a = error_of(std::string(kHeader) + "{\"t\": 0, \"action\": \"explode\"}]}");
  EXPECT_NE(a.find("unknown action \"explode\""), std::string::npos) << a;
  const std::string tool = error_of(std::string(kHeader) + "{\"t\": 0, \"action\": \"tool\", \"value\": \"paint\"}]}");
  EXPECT_NE(tool.find("unknown tool \"paint\""), std::string::npos) << tool;
  const std::string field = error_of(std::string(kHeader) + "{\"t\": 0, \"position\": [0, 0, 0], \"pressure\": 1}]}");
  EXPECT_NE(field.find("unknown field \"pressure\""), std::string::npos) << field;
  const std::string trig = error_of(std::string(kHeader) + "{\"t\": 0, \"position\": [0, 0, 0], \"trigger\": 2}]}");
  EXPECT_NE(trig.find("events[0].trigger"), std::string::npos) << trig;
}

TEST(Track, DrawingAidActionsRoundTripAndBadOnesAreNamed) {
  Track track;
  track.events.push_back({0.1, std::nullopt, TrackAction{"aid", "snap", {1.0}}});
  track.events.push_back({0.2, std::nullopt, TrackAction{"plane", "", {0.0, 1.0, 0.0, -0.7}}});
  track.events.push_back({0.3, std::nullopt, TrackAction{"rotation", "", {0.5, 0.0, -1.0 / 3.0, 0.0, 1.0, 0.0, 6.0}}});
  track.events.push_back({0.4, std::nullopt, TrackAction{"clear_rotation", "", {}}});
  track.events.push_back({0.5, std::nullopt, TrackAction{"tool", "plane", {}}});
  const Track back = parse_track(track_json(track), "t.json");
  ASSERT_EQ(back.events.size(), track.events.size());
  for (std::size_t i = 0; i < track.events.size(); ++i) {
    EXPECT_EQ(back.events[i].action->name, track.events[i].action->name);
    EXPECT_EQ(back.events[i].action->text, track.events[i].action->text);
    EXPECT_EQ(back.events[i].action->values, track.events[i].action->values);
  }
  const std::string count = error_of(std::string(kHeader) +
      "{\"t\": 0, \"action\": \"rotation\", \"center\": [0, 0, 0], \"axis\": [0, 1, 0], \"count\": 2.5}]}");
  EXPECT_NE(count.find("events[0].count: expected an integer from 2 to 360"), std::string::npos) << count;
  const std::string axis = error_of(std::string(kHeader) +
      "{\"t\": 0, \"action\": \"rotation\", \"center\": [0, 0, 0], \"axis\": [0, 0, 0], \"count\": 6}]}");
  EXPECT_NE(axis.find("events[0].axis: the axis is zero"), std::string::npos) << axis;
  const std::string plane = error_of(std::string(kHeader) + "{\"t\": 1, \"action\": \"plane\", \"plane\": [0, 0, 0, 1]}]}");
  EXPECT_NE(plane.find("normal"), std::string::npos) << plane;
}

TEST(Track, StructuralErrors) {
  EXPECT_NE(error_of("[]").find("not a track"), std::string::npos);
  EXPECT_NE(error_of("{\"format\": \"sketchsurf-track\", \"version\": 9, \"events\": []}").find("version"),
            std::string::npos);
  EXPECT_NE(error_of("{\"format\": \"sketchsurf-track\", \"version\": 1}").find("events"), std::string::npos);
  const std::string back = error_of(std::string(kHeader) +
                                    "{\"t\": 1, \"position\": [0, 0, 0]},\n{\"t\": 0.5, \"position\": [0, 0, 0]}]}");
  EXPECT_NE(back.find("events[1].t: time 0.5 is before"), std::string::npos) << back;
  const std::string both = error_of(std::string(kHeader) + "{\"t\": 1}]}");
  EXPECT_NE(both.find("either \"position\""), std::string::npos) << both;
  const std::string plane = error_of(std::string(kHeader) + "{\"t\": 1, \"action\": \"mirror\", \"plane\": [0, 0, 0, 1]}]}");
  EXPECT_NE(plane.find("normal"), std::string::npos) << plane;
}

TEST(Track, MissingFileIsAnInputError) {
  try {
    read_track("/nonexistent/track.json");
    FAIL();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::Input);
    EXPECT_NE(std::string(e.what()).find("/nonexistent/track.json"), std::string::npos);
  }
}

TEST(ScriptedController, ReplaysEveryEventOnceInOrderWhateverTheFrameRate) {
  const Track track = sample_track();
  for (double frame : {0.001, 0.033, 0.25, 10.0}) {
    ScriptedController controller(track);
    EXPECT_FALSE(controller.current().tracked);
    std::vector<TrackEvent> seen;
    for (double now = 0.0; !controller.finished(); now += frame)
      for (auto& e : controller.poll_events(now)) {
        EXPECT_LE(e.time_s, now);
        seen.push_back(e);
      }
    ASSERT_EQ(seen.size(), track.events.size());
    for (std::size_t i = 0; i < seen.size(); ++i) EXPECT_EQ(seen[i].time_s, track.events[i].time_s);
    EXPECT_EQ(controller.current().pose.position, track.events[4].state->pose.position);
  }
  ScriptedController states_only(track);
  EXPECT_EQ(states_only.poll(100.0).size(), 5u);
  EXPECT_TRUE(states_only.poll(200.0).empty());
}

}  // namespace
}  // namespace sketchsurf::input
