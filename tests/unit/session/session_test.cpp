// SketchSession (engine/session/session.h): drawing from controller samples, the tools, undo/redo
// of every edit (restoring the sketch exactly), files, autosave (a kill -9 keeps every finished
// stroke), surfacing on a worker thread with progress and cancel.

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <thread>

#include "engine/session/actions.h"
#include "engine/session/session.h"
#include "surfacing/sketch/io/sketch_io.h"
#include "tests/support/cli_run.h"
#include "tests/support/shapes.h"

namespace sketchsurf::session {
namespace {

using input::Button;
using input::ControllerState;

/// Every field of two sketches is equal (bit for bit).
void expect_same(const Sketch& a, const Sketch& b) {
  ASSERT_EQ(a.strokes.size(), b.strokes.size());
  for (std::size_t i = 0; i < a.strokes.size(); ++i) {
    const Stroke &s = a.strokes[i], &t = b.strokes[i];
    EXPECT_EQ(s.id, t.id);
    EXPECT_EQ(s.points, t.points) << "stroke " << i;
    ASSERT_EQ(s.orientations.size(), t.orientations.size());
    for (std::size_t k = 0; k < s.orientations.size(); ++k)
      EXPECT_EQ(s.orientations[k].coeffs(), t.orientations[k].coeffs());
    EXPECT_EQ(s.pressures, t.pressures);
    EXPECT_EQ(s.timestamps_ms, t.timestamps_ms);
    EXPECT_EQ(s.width, t.width);
    EXPECT_EQ(s.color, t.color);
    EXPECT_EQ(s.boundary, t.boundary);
    EXPECT_EQ(s.ignored, t.ignored);
  }
  ASSERT_EQ(a.mirror.has_value(), b.mirror.has_value());
  if (a.mirror) {
    EXPECT_EQ(a.mirror->normal, b.mirror->normal);
    EXPECT_EQ(a.mirror->offset, b.mirror->offset);
  }
}

ControllerState sample(double t, const Eigen::Vector3d& p, bool draw, float trigger = 1.0f) {
  ControllerState s;
  s.time_s = t;
  s.pose.position = p;
  s.pose.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(t, Eigen::Vector3d::UnitY()));
  s.set(Button::Draw, draw);
  s.trigger = draw ? trigger : 0.0f;
  return s;
}

/// Draws a straight stroke from a to b with `n` samples (plus the release).
void draw_line(SketchSession& s, const Eigen::Vector3d& a, const Eigen::Vector3d& b, int n, double& t,
               float trigger = 1.0f) {
  for (int i = 0; i < n; ++i)
    s.apply(sample(t += 0.01, a + (b - a) * (double(i) / (n - 1)), true, trigger));
  s.apply(sample(t += 0.01, b, false));
}

TEST(SketchSession, DrawsFromTriggerDownToUpKeepingSpacingPressureAndOrientation) {
  SessionOptions options;
  options.drawing.min_spacing = 0.0095;  // of the reference size 1: every tenth sample
  SketchSession s(options);
  double t = 0.0;
  // 1001 samples 0.001 apart: 1 in 10 kept, the last always.
  for (int i = 0; i <= 1000; ++i)
    s.apply(sample(t += 0.001, {0.001 * i, 0.0, 0.0}, true, 0.25f + 0.5f * float(i) / 1000));
  EXPECT_TRUE(s.drawing_in_progress());
  ASSERT_EQ(s.live_strokes().size(), 1u);
  EXPECT_TRUE(s.sketch().strokes.empty());
  s.apply(sample(t += 0.001, {1.0005, 0.0, 0.0}, false));
  EXPECT_FALSE(s.drawing_in_progress());
  EXPECT_TRUE(s.live_strokes().empty());
  ASSERT_EQ(s.sketch().strokes.size(), 1u);
  const Stroke& stroke = s.sketch().strokes[0];
  EXPECT_EQ(stroke.points.size(), 102u);  // 0, 0.01, ..., 1.0, and the release point
  for (std::size_t i = 1; i + 1 < stroke.points.size(); ++i)
    EXPECT_GE((stroke.points[i] - stroke.points[i - 1]).norm(), 0.01 - 1e-12);
  EXPECT_NEAR(stroke.length(), 1.0005, 1e-12);
  EXPECT_TRUE(stroke.attributes_consistent());
  EXPECT_EQ(stroke.pressures.size(), stroke.points.size());
  EXPECT_FLOAT_EQ(stroke.pressures.front(), 0.25f);
  EXPECT_FLOAT_EQ(stroke.pressures[100], 0.75f);
  EXPECT_EQ(stroke.orientations.size(), stroke.points.size());
  EXPECT_TRUE(stroke.orientations[100].isApprox(
      Eigen::Quaterniond(Eigen::AngleAxisd(1.001, Eigen::Vector3d::UnitY())), 1e-9));
  EXPECT_EQ(stroke.timestamps_ms.front(), 1u);
  EXPECT_EQ(stroke.timestamps_ms[100], 1001u);
  EXPECT_EQ(stroke.id, 0);
  // A click without a drag makes no stroke; untracked samples add no point.
  s.apply(sample(t += 0.01, {2, 2, 2}, true));
  s.apply(sample(t += 0.01, {2, 2, 2}, false));
  ControllerState lost = sample(t += 0.01, {5, 5, 5}, true);
  lost.tracked = false;
  s.apply(lost);
  s.apply(sample(t += 0.01, {3, 3, 3}, true));
  s.apply(sample(t += 0.01, {3, 4, 3}, false));
  ASSERT_EQ(s.sketch().strokes.size(), 2u);
  EXPECT_EQ(s.sketch().strokes[1].points.front(), Eigen::Vector3d(3, 3, 3));
}

TEST(SketchSession, UndoRedoOfEveryEditRestoresTheSketchExactly) {
  SketchSession s;
  double t = 0.0;
  std::vector<Sketch> states{s.sketch()};
  auto step = [&](auto&& edit) {
    edit();
    states.push_back(s.sketch());
  };
  step([&] { draw_line(s, {0, 0, 0}, {1, 0, 0}, 30, t); });
  step([&] { draw_line(s, {0, 1, 0}, {1, 1, 0}, 30, t, 0.4f); });
  step([&] { draw_line(s, {0, 2, 0}, {1, 2, 1}, 30, t); });
  step([&] { EXPECT_TRUE(s.set_boundary(1, true)); });
  step([&] { EXPECT_TRUE(s.set_ignored(2, true)); });
  step([&] { EXPECT_TRUE(s.erase_stroke(0)); });
  step([&] { EXPECT_TRUE(s.set_mirror(Plane{Eigen::Vector3d(2, 0, 0), -1.0})); });  // x = 0.5
  step([&] { draw_line(s, {1, 3, 0}, {2, 3, 0}, 30, t); });  // and its mirror image
  step([&] { EXPECT_TRUE(s.set_boundary(3, true)); });
  step([&] { EXPECT_TRUE(s.set_mirror(std::nullopt)); });
  step([&] { EXPECT_TRUE(s.clear()); });
  step([&] { draw_line(s, {0, 0, 5}, {0, 1, 5}, 10, t); });
  // Tools through the controller: erase and mark.
  EXPECT_EQ(s.sketch().strokes.size(), 1u);
  EXPECT_EQ(s.sketch().mirror.has_value(), false);
  ASSERT_EQ(states.size(), 13u);
  // The mirrored stroke: reflected in x = 0.5, its own id.
  const Sketch& mirrored = states[8];
  ASSERT_EQ(mirrored.strokes.size(), 4u);
  EXPECT_EQ(mirrored.strokes[3].id, mirrored.strokes[2].id + 1);
  for (std::size_t i = 0; i < mirrored.strokes[2].points.size(); ++i)
    EXPECT_NEAR(mirrored.strokes[3].points[i].x(), 1.0 - mirrored.strokes[2].points[i].x(), 1e-15);
  // Undo everything, checking each state; then redo everything.
  for (std::size_t i = states.size() - 1; i > 0; --i) {
    EXPECT_TRUE(s.can_undo());
    EXPECT_TRUE(s.undo());
    expect_same(s.sketch(), states[i - 1]);
  }
  EXPECT_FALSE(s.undo());
  for (std::size_t i = 1; i < states.size(); ++i) {
    EXPECT_TRUE(s.redo());
    expect_same(s.sketch(), states[i]);
  }
  EXPECT_FALSE(s.redo());
  // A new edit drops the redo stack.
  s.undo();
  s.undo();
  draw_line(s, {0, 0, 0}, {0, 0, 1}, 5, t);
  EXPECT_FALSE(s.can_redo());
}

TEST(SketchSession, ControllerToolsEraseAndMarkTheStrokeTouched) {
  SketchSession s;
  double t = 0.0;
  draw_line(s, {0, 0, 0}, {1, 0, 0}, 20, t);
  draw_line(s, {0, 1, 0}, {1, 1, 0}, 20, t);
  draw_line(s, {0, 2, 0}, {1, 2, 0}, 20, t);
  const Sketch before = s.sketch();
  s.set_tool(Tool::MarkBoundary);
  s.apply(sample(t += 0.01, {0.5, 1.01, 0}, true));  // within 0.02 of stroke 1
  s.apply(sample(t += 0.01, {0.5, 0.0, 0}, true));   // held: no toggle on stroke 0
  s.apply(sample(t += 0.01, {0.5, 0.0, 0}, false));
  EXPECT_TRUE(s.sketch().strokes[1].boundary);
  EXPECT_FALSE(s.sketch().strokes[0].boundary);
  s.set_tool(Tool::MarkIgnored);
  s.apply(sample(t += 0.01, {0.2, 2.0, 0.015}, true));
  s.apply(sample(t += 0.01, {0.2, 2.0, 0.015}, false));
  EXPECT_TRUE(s.sketch().strokes[2].ignored);
  s.apply(sample(t += 0.01, {0.5, 5.0, 0}, true));  // nothing there
  s.apply(sample(t += 0.01, {0.5, 5.0, 0}, false));
  s.set_tool(Tool::Erase);
  // An eraser stroke across strokes 0 and 1 erases both.
  s.apply(sample(t += 0.01, {0.3, -0.5, 0}, true));
  for (int i = 0; i <= 20; ++i) s.apply(sample(t += 0.01, {0.3, -0.5 + 0.1 * i, 0}, true));
  s.apply(sample(t += 0.01, {0.3, 1.5, 0}, false));
  ASSERT_EQ(s.sketch().strokes.size(), 1u);
  EXPECT_EQ(s.sketch().strokes[0].id, 2);
  // Undo button on the controller: four undos give the sketch back.
  for (int i = 0; i < 4; ++i) {
    ControllerState u = sample(t += 0.01, {9, 9, 9}, false);
    u.set(Button::Undo, true);
    s.apply(u);
    s.apply(sample(t += 0.01, {9, 9, 9}, false));
  }
  expect_same(s.sketch(), before);
  ControllerState r = sample(t += 0.01, {9, 9, 9}, false);
  r.set(Button::Redo, true);
  s.apply(r);
  EXPECT_TRUE(s.sketch().strokes[1].boundary);
}

TEST(SketchSession, UndoWhileDrawingDropsTheStrokeInProgress) {
  SketchSession s;
  double t = 0.0;
  draw_line(s, {0, 0, 0}, {1, 0, 0}, 20, t);
  s.apply(sample(t += 0.01, {0, 1, 0}, true));
  s.apply(sample(t += 0.01, {1, 1, 0}, true));
  EXPECT_EQ(s.undo_name(), "stroke in progress");
  EXPECT_TRUE(s.undo());
  EXPECT_FALSE(s.drawing_in_progress());
  s.apply(sample(t += 0.01, {1, 2, 0}, true));
  s.apply(sample(t += 0.01, {1, 2, 0}, false));
  EXPECT_EQ(s.sketch().strokes.size(), 1u);
  EXPECT_EQ(s.undo_name(), "draw");
}

TEST(SketchSession, ActionsAsATrackHoldsThem) {
  SketchSession s;
  double t = 0.0;
  draw_line(s, {0, 0, 0}, {1, 0, 0}, 20, t);
  EXPECT_EQ(apply_action(s, tool_action(Tool::Erase)), "tool: erase");
  EXPECT_EQ(s.tool(), Tool::Erase);
  EXPECT_EQ(apply_action(s, simple_action("undo")), "undo: draw");
  EXPECT_EQ(apply_action(s, simple_action("undo")), "nothing to undo");
  EXPECT_EQ(apply_action(s, simple_action("redo")), "redo: draw");
  EXPECT_EQ(apply_action(s, mirror_action({Eigen::Vector3d::UnitX(), 0.0})), "mirror on");
  EXPECT_TRUE(s.sketch().mirror.has_value());
  EXPECT_EQ(apply_action(s, simple_action("clear_mirror")), "mirror off");
  apply_action(s, param_action("segment.epsilon", 0.02));
  EXPECT_EQ(s.params().segment.epsilon, 0.02);
  EXPECT_THROW(apply_action(s, param_action("segment.nonsense", 1)), Error);
  EXPECT_THROW(apply_action(s, {"tool", "paint", {}}), Error);
  EXPECT_EQ(apply_action(s, simple_action("clear")), "cleared");
}

TEST(SketchSession, OpensAndSavesThroughTheReadersAndWriters) {
  const auto dir = testing::scratch_dir("session_files_");
  SketchSession s;
  s.open(std::filesystem::path(SKETCHSURF_TESTS_DIR) / "data" / "cube.json");
  EXPECT_EQ(s.sketch().strokes.size(), 18u);
  EXPECT_FALSE(s.modified());
  EXPECT_NEAR(s.reference_size(), std::sqrt(3.0), 1e-9);
  EXPECT_TRUE(s.erase_stroke(17));
  EXPECT_TRUE(s.modified());
  EXPECT_FALSE(s.can_redo());
  for (const char* ext : {".json", ".tilt", ".obj"}) {
    const auto file = dir / (std::string("saved") + ext);
    s.save(file);
    EXPECT_FALSE(s.modified());
    const Sketch back = read_sketch(file);
    ASSERT_EQ(back.strokes.size(), 17u) << ext;
    for (std::size_t i = 0; i < 17; ++i)
      for (std::size_t k = 0; k < back.strokes[i].points.size(); ++k)
        EXPECT_NEAR((back.strokes[i].points[k] - s.sketch().strokes[i].points[k]).norm(), 0.0, 1e-6);
  }
  SketchSession other;
  other.open(dir / "saved.json");
  expect_same(other.sketch(), s.sketch());
  EXPECT_FALSE(other.can_undo());
  // A file that cannot be read leaves the session as it was.
  EXPECT_THROW(other.open(dir / "missing.json"), Error);
  EXPECT_EQ(other.sketch().strokes.size(), 17u);
  EXPECT_THROW(other.save(dir / "sketch.unknown"), Error);
}

TEST(SketchSession, AutosaveHoldsEveryFinishedEditNotTheStrokeInProgress) {
  const auto dir = testing::scratch_dir("session_autosave_");
  SessionOptions options;
  options.autosave = dir / "autosave.json";
  SketchSession s(options);
  s.flush_autosave();
  EXPECT_TRUE(read_sketch(options.autosave).strokes.empty());
  double t = 0.0;
  draw_line(s, {0, 0, 0}, {1, 0, 0}, 20, t);
  draw_line(s, {0, 1, 0}, {1, 1, 0}, 20, t);
  s.apply(sample(t += 0.01, {0, 2, 0}, true));
  s.apply(sample(t += 0.01, {1, 2, 0}, true));  // in progress
  s.flush_autosave();
  EXPECT_EQ(s.autosaved_revision(), s.revision());
  EXPECT_TRUE(s.autosave_error().empty());
  Sketch saved = read_sketch(options.autosave);
  ASSERT_EQ(saved.strokes.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i)
    for (std::size_t k = 0; k < saved.strokes[i].points.size(); ++k)
      EXPECT_EQ(saved.strokes[i].points[k], s.sketch().strokes[i].points[k]);
  s.undo();  // drops the stroke in progress
  s.undo();  // and the second stroke
  s.flush_autosave();
  EXPECT_EQ(read_sketch(options.autosave).strokes.size(), 1u);
  SessionOptions tilt;
  tilt.autosave = dir / "autosave.tilt";
  EXPECT_THROW(SketchSession{tilt}, Error);
}

TEST(SketchSession, KillMinus9WhileDrawingLeavesAnAutosaveWithEveryFinishedStroke) {
  const auto dir = testing::scratch_dir("session_kill_");
  const auto autosave = dir / "autosave.json";
  int report[2];
  ASSERT_EQ(pipe(report), 0);
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {  // draws strokes forever, saying when each one is in the autosave
    close(report[0]);
    SessionOptions options;
    options.autosave = autosave;
    SketchSession s(options);
    double t = 0.0;
    for (int k = 0;; ++k) {
      for (int i = 0; i < 50; ++i) {
        s.apply(sample(t += 0.001, {0.02 * i, 0.1 * k, 0.0}, true));
        std::this_thread::sleep_for(std::chrono::microseconds(200));
      }
      s.apply(sample(t += 0.001, {1.0, 0.1 * k, 0.0}, false));
      s.flush_autosave();
      const char byte = 'k';
      if (write(report[1], &byte, 1) != 1) _exit(1);
    }
  }
  close(report[1]);
  int finished = 0;
  char byte;
  while (finished < 5 && read(report[0], &byte, 1) == 1) ++finished;
  std::this_thread::sleep_for(std::chrono::milliseconds(3));  // mid-way through the next stroke
  kill(child, SIGKILL);
  int status = 0;
  waitpid(child, &status, 0);
  while (read(report[0], &byte, 1) == 1) ++finished;
  close(report[0]);
  EXPECT_TRUE(WIFSIGNALED(status));
  const Sketch saved = read_sketch(autosave);  // complete, valid JSON: written by rename
  ASSERT_GE(int(saved.strokes.size()), finished);
  ASSERT_LE(int(saved.strokes.size()), finished + 1);
  for (std::size_t k = 0; k < saved.strokes.size(); ++k) {
    const Stroke& s = saved.strokes[k];
    ASSERT_EQ(s.points.size(), 51u) << "stroke " << k << " is not a finished stroke";
    EXPECT_EQ(s.points.back(), Eigen::Vector3d(1.0, 0.1 * double(k), 0.0));
  }
  int temporaries = 0;  // at most the one of the write the kill cut short
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    temporaries += entry.path().filename().string().find(".tmp-") != std::string::npos;
  EXPECT_LE(temporaries, 1);
}

/// The 12 edges of the unit cube, as a session would get them.
SketchSession& draw_cube(SketchSession& s) {
  double t = 0.0;
  for (const Stroke& edge : testing::cube_sketch(1.0, false).strokes)
    draw_line(s, edge.points.front(), edge.points.back(), 51, t);
  return s;
}

SessionOptions fast_surfacing() {
  SessionOptions options;
  options.params.proxy.edge = 0.03;  // a coarse proxy keeps the test quick
  options.params.segment.restarts = 2;
  return options;
}

/// Six regions, each on one face plane of the cube of side 1 (smooth vertices within 0.3% of the
/// diagonal of it), the six faces all found.
void expect_six_planar_faces(const SurfaceResult& r) {
  ASSERT_EQ(r.segmentation.models.size(), 6u);
  std::map<int, std::set<int>> faces_of_label;
  for (auto v : r.mesh.vertices()) {
    if (r.sharp[v.idx()]) continue;
    const Eigen::Vector3d p = to_eigen(r.mesh.point(v));
    int axis = 0;
    p.cwiseAbs().maxCoeff(&axis);
    EXPECT_NEAR(std::abs(p[axis]), 0.5, 0.003 * std::sqrt(3.0)) << p.transpose();
    faces_of_label[r.labels[v.idx()]].insert(2 * axis + (p[axis] < 0));
  }
  EXPECT_EQ(faces_of_label.size(), 6u);
  std::set<int> faces;
  for (const auto& [label, f] : faces_of_label) {
    EXPECT_EQ(f.size(), 1u) << "region " << label << " spans several faces";
    faces.insert(f.begin(), f.end());
  }
  EXPECT_EQ(faces.size(), 6u);
}

TEST(SketchSession, SurfacesOnAWorkerThreadWhileTheFrameLoopGoesOn) {
  SketchSession s(fast_surfacing());
  draw_cube(s);
  ASSERT_EQ(s.sketch().strokes.size(), 12u);
  ASSERT_TRUE(s.surface());
  EXPECT_FALSE(s.surface());  // one job at a time
  std::set<std::string> stages;
  double longest_frame = 0.0;
  double t = 100.0;
  int frames = 0;
  const auto start = std::chrono::steady_clock::now();
  while (s.surface_status().state == JobState::Running) {
    // A frame: draw a little, poll the job.
    const auto f0 = std::chrono::steady_clock::now();
    s.apply(sample(t += 0.01, {3.0 + 0.01 * frames, 0, 0}, frames % 20 != 19));
    s.poll_surface();
    stages.insert(s.surface_status().stage);
    longest_frame = std::max(longest_frame,
                             std::chrono::duration<double>(std::chrono::steady_clock::now() - f0).count());
    ++frames;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
    ASSERT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 120.0);
  }
  EXPECT_TRUE(s.poll_surface() || s.result());
  const SurfaceStatus status = s.surface_status();
  ASSERT_EQ(status.state, JobState::Done) << status.message;
  EXPECT_NE(status.message.find("6 regions"), std::string::npos) << status.message;
  EXPECT_GE(stages.size(), 3u) << "progress reported stage by stage";
  EXPECT_LT(longest_frame, 0.05) << "the frame loop waited for the surfacing";
  EXPECT_GT(s.sketch().strokes.size(), 12u) << "strokes drawn while surfacing";
  ASSERT_NE(s.result(), nullptr);
  expect_six_planar_faces(*s.result());
  const auto dir = testing::scratch_dir("session_surface_");
  s.save_surface(dir / "cube.ply");
  EXPECT_TRUE(std::filesystem::exists(dir / "cube.ply"));
}

TEST(SketchSession, CancelledSurfacingLeavesTheSessionUsable) {
  SketchSession s(fast_surfacing());
  draw_cube(s);
  const Sketch before = s.sketch();
  ASSERT_TRUE(s.surface());
  // Cancel once it is under way (past the start).
  while (s.surface_status().stage == "starting") std::this_thread::sleep_for(std::chrono::milliseconds(1));
  s.cancel_surface();
  EXPECT_EQ(s.surface_status().state, JobState::Cancelling);
  const auto asked = std::chrono::steady_clock::now();
  ASSERT_TRUE(s.wait_surface(30.0));
  const double latency = std::chrono::duration<double>(std::chrono::steady_clock::now() - asked).count();
  EXPECT_EQ(s.surface_status().state, JobState::Cancelled);
  EXPECT_LT(latency, 2.0) << "cancel took " << latency << " s";
  EXPECT_EQ(s.result(), nullptr);
  expect_same(s.sketch(), before);
  // Usable: edits, undo, and a new surfacing that completes.
  double t = 50.0;
  draw_line(s, {0, 0, 0.5}, {0.5, 0.5, 0.5}, 10, t);
  EXPECT_TRUE(s.undo());
  expect_same(s.sketch(), before);
  ASSERT_TRUE(s.surface());
  ASSERT_TRUE(s.wait_surface(120.0));
  ASSERT_EQ(s.surface_status().state, JobState::Done) << s.surface_status().message;
  expect_six_planar_faces(*s.result());
}

TEST(SketchSession, SurfacingAnEmptySketchFailsWithAMessage) {
  SketchSession s;
  ASSERT_TRUE(s.surface());
  ASSERT_TRUE(s.wait_surface(30.0));
  EXPECT_EQ(s.surface_status().state, JobState::Failed);
  EXPECT_NE(s.surface_status().message.find("no stroke"), std::string::npos) << s.surface_status().message;
  EXPECT_THROW(s.save_surface("/tmp/none.ply"), Error);
}

}  // namespace
}  // namespace sketchsurf::session
