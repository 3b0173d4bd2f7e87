#include "tools/sketchsurf-studio/studio.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <sstream>

#include "engine/session/actions.h"
#include "surfacing/error.h"

namespace sketchsurf::studio {

namespace {

std::filesystem::path default_autosave() {
  return std::filesystem::temp_directory_path() /
         ("sketchsurf-studio-" + std::to_string(::getpid()) + ".autosave.json");
}

BoundingBox track_bounds(const input::Track& track) {
  BoundingBox box;
  for (const auto& e : track.events)
    if (e.state && e.state->tracked) box.extend(e.state->pose.position);
  return box;
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(q * double(v.size() - 1) + 0.5))];
}

}  // namespace

void Log::info(const std::string& line) const {
  if (!quiet) std::cerr << "studio: " << line << std::endl;
}

void Log::detail(const std::string& line) const {
  if (verbose && !quiet) std::cerr << "studio: " << line << std::endl;
}

Studio::Studio(const StudioOptions& options, const vk::Context& context, const Log& log)
    : options_(options), log_(log), mouse_(options.width, options.height), view_(context) {
  session::SessionOptions session_options;
  if (!options.no_autosave)
    session_options.autosave = options.autosave.empty() ? default_autosave() : options.autosave;
  session_ = std::make_unique<session::SketchSession>(session_options);
  if (!session_->autosave_path().empty())
    log_.info("autosaving to " + session_->autosave_path().string());
  BoundingBox frame;
  if (!options.sketch.empty()) {
    session_->open(options.sketch);
    frame = session_->sketch().bounding_box();
    log_.info("opened " + options.sketch.string() + ": " + std::to_string(session_->sketch().strokes.size()) +
              " strokes, " + std::to_string(session_->sketch().point_count()) + " points");
  }
  for (const auto& [name, value] : options.params) session_->set_param(name, value);
  if (!options.proxy.empty()) session_->open_proxy(options.proxy);
  if (!options.replay.empty()) {
    scripted_.emplace(input::read_track(options.replay));
    const BoundingBox b = track_bounds(scripted_->track());
    if (!b.empty()) {
      frame.extend(b.min);
      frame.extend(b.max);
    }
    log_.detail("replaying " + options.replay.string() + ": " +
                std::to_string(scripted_->track().events.size()) + " events over " +
                std::to_string(scripted_->duration()) + " s");
  }
  if (frame.empty()) {
    frame.extend(Eigen::Vector3d::Constant(-0.5));
    frame.extend(Eigen::Vector3d::Constant(0.5));
  }
  mouse_.view().look_from(render::View::Iso);
  frame_box(frame, options.width, options.height);
  mouse_.set_pick([this](const Eigen::Vector3d& o, const Eigen::Vector3d& d, double r) {
    return session_->pick(o, d, r);
  });
  status_ = "ready";
}

Studio::~Studio() = default;

double Studio::simulated_time(std::size_t index) const {
  if (scripted_ && options_.frames && *options_.frames > 1) {
    const std::size_t n = static_cast<std::size_t>(*options_.frames);
    if (index < n) return scripted_->duration() * double(index) / double(n - 1);
    return scripted_->duration() + double(index - n + 1) / 60.0;
  }
  return double(index) / 60.0;
}

void Studio::apply_state(const input::ControllerState& state) {
  if (state.pressed(input::Button::Menu) && !last_state_.pressed(input::Button::Menu))
    panel_visible = !panel_visible;
  session_->apply(state);
  last_state_ = state;
  if (!options_.record.empty()) {
    input::ControllerState s = state;
    if (!recorded_.events.empty()) s.time_s = std::max(s.time_s, recorded_.events.back().time_s);
    recorded_.events.push_back({s.time_s, s, std::nullopt});
  }
}

void Studio::input(double now) {
  now_ = now;
  // One drawing plane: the session's. Shift+wheel moved the mouse's copy: that is a plane action.
  const Plane& mouse_plane = mouse_.drawing_plane();
  const Plane& plane = session_->drawing().plane;
  // (Beyond the last bits: the mouse renormalises the normal it is given.)
  if ((mouse_plane.normal - plane.normal).norm() > 1e-12 ||
      std::abs(mouse_plane.offset - plane.offset) > 1e-12 * (1.0 + std::abs(plane.offset)))
    act(session::plane_action(mouse_plane));
  if (replaying()) {
    for (const auto& e : scripted_->poll_events(now)) {
      if (e.state) apply_state(*e.state);
      if (e.action) act(*e.action);
    }
    mouse_.poll(now);  // the mouse waits for the replay to end
    return;
  }
  for (const auto& s : controller_ ? controller_->poll(now) : mouse_.poll(now)) apply_state(s);
}

void Studio::act(const input::TrackAction& action) {
  try {
    set_status(session::apply_action(*session_, action));
  } catch (const Error& e) {
    if (replaying()) throw;
    set_status(e.what());
    return;
  }
  if (!options_.record.empty()) {
    const double t = recorded_.events.empty() ? now_ : std::max(now_, recorded_.events.back().time_s);
    recorded_.events.push_back({t, std::nullopt, action});
  }
}

void Studio::set_status(const std::string& line) {
  status_ = line;
  log_.detail(line);
}

void Studio::update() {
  if (session_->poll_surface()) set_status("surface: " + session_->surface_status().message);
  if (options_.surface && !surface_started_ && !replaying()) {
    act(session::simple_action("surface"));
    surface_started_ = true;
  }
  log_progress();
  mouse_.set_drawing_plane(session_->drawing().plane);
  render::Overlay overlay;
  // The replayed controller until the mouse moves.
  const bool scripted = scripted_ && (replaying() || mouse_.current().time_s == 0.0);
  const input::ControllerState cursor = scripted      ? scripted_->current()
                                        : controller_ ? controller_->current()
                                                      : mouse_.current();
  if (cursor.tracked) overlay.cursor = cursor.pose;
  const bool mouse = !scripted && !controller_;
  if (mouse) update_snap_radius();
  // The grid shows the drawing plane where strokes land on it: the mouse drawing on it, or the
  // plane guide (a controller in 3D).
  if ((mouse && mouse_.depth_mode() == input::DepthMode::Plane) || session_->drawing().plane_guide)
    overlay.drawing_plane = session_->drawing().plane;
  // The grid lies around the controller (in whole cells): it shows where the strokes go.
  overlay.grid_centre = cursor.tracked ? cursor.pose.position : Eigen::Vector3d::Zero();
  view_.update(*session_, overlay, view_options_);
}

void Studio::update_snap_radius() {
  // The size of a pixel at the view's target, in the session's reference size.
  const auto& view = mouse_.view();
  const double pixel = 2.0 * std::tan(0.5 * view.fov_y * M_PI / 180.0) * view.distance / mouse_.height();
  const double radius = kSnapPixels * pixel / session_->reference_size();
  const double now = session_->drawing().snap_radius;
  if (std::isfinite(radius) && radius > 0.0 && std::abs(radius - now) > 0.01 * now)
    act(session::aid_action("snap_radius", radius));
}

void Studio::log_progress() {
  const auto& s = *session_;
  if (s.autosaved_revision() != logged_autosave_ && s.autosaved_revision() == s.revision()) {
    logged_autosave_ = s.autosaved_revision();
    log_.detail("autosaved " + std::to_string(s.sketch().strokes.size()) + " strokes");
  }
  const session::SurfaceStatus job = s.surface_status();
  if (job.state != logged_job_ || (job.state == session::JobState::Running && job.stage != logged_stage_)) {
    if (job.state == session::JobState::Running) log_.detail("surfacing: " + job.stage);
    if (job.state == session::JobState::Done) log_.info("surfaced: " + job.message);
    if (job.state == session::JobState::Failed) log_.info("surfacing failed: " + job.message);
    if (job.state == session::JobState::Cancelled) log_.info("surfacing cancelled");
    logged_job_ = job.state;
    logged_stage_ = job.stage;
  }
}

render::Camera Studio::camera() const {
  render::Camera c = mouse_.camera();
  const BoundingBox box = view_.bounds();
  if (!box.empty() && box.diagonal() > 0.0) render::fit_clip_planes(c, box);
  return c;
}

void Studio::record(VkCommandBuffer cmd, const render::Renderer& renderer, int width, int height,
                    std::vector<std::shared_ptr<const void>>* in_use) const {
  record(cmd, renderer, camera(), double(width) / double(height), in_use);
}

void Studio::record(VkCommandBuffer cmd, const render::Renderer& renderer, const render::Camera& camera,
                    double aspect, std::vector<std::shared_ptr<const void>>* in_use) const {
  view_.record(cmd, renderer, camera, aspect, view_options_, in_use);
}

std::size_t Studio::frames_wanted() const {
  if (options_.frames) return static_cast<std::size_t>(std::max(1, *options_.frames));
  if (scripted_) return static_cast<std::size_t>(std::ceil(scripted_->duration() * 60.0)) + 1;
  return 1;
}

bool Studio::done(std::size_t frames) const {
  if (frames < frames_wanted() || replaying()) return false;
  if (!options_.surface) return true;
  const auto state = session_->surface_status().state;
  return surface_started_ && state != session::JobState::Running && state != session::JobState::Cancelling;
}

void Studio::frame_finished(double seconds) {
  const double ms = seconds * 1e3;
  frame_ms_.push_back(ms);
  if (frame_ms_.size() > 120) frame_ms_.pop_front();
  all_frame_ms_.push_back(ms);
}

FrameStats Studio::stats() const {
  FrameStats s;
  s.frames = all_frame_ms_.size();
  s.median_ms = percentile({frame_ms_.begin(), frame_ms_.end()}, 0.5);
  s.p95_ms = percentile(all_frame_ms_, 0.95);
  s.max_ms = all_frame_ms_.empty() ? 0.0 : *std::max_element(all_frame_ms_.begin(), all_frame_ms_.end());
  return s;
}

void Studio::frame_all(int width, int height) {
  BoundingBox box = session_->sketch().bounding_box();
  if (const auto* r = session_->result())
    for (auto v : r->mesh.vertices()) box.extend(to_eigen(r->mesh.point(v)));
  if (box.empty()) return;
  frame_box(box, width, height);
}

void Studio::frame_box(const BoundingBox& box, int width, int height) {
  // Framed in the part of the window right of the panel (when it leaves at least half of it).
  const int free = panel_visible ? std::max(width - kPanelSpace, width / 2) : width;
  mouse_.view().frame(box, double(free) / double(height));
  mouse_.view().pan(0.5 * (width - free), 0.0, height);
}

void Studio::finish() {
  // done() sees the job finished as soon as its thread ends; the frame loop takes the result on
  // its next tick, which a finishing studio does not run.
  if (session_->poll_surface()) set_status("surface: " + session_->surface_status().message);
  log_progress();  // a job that ended after the last frame's log is reported too
  if (!options_.save_surface.empty()) {
    session_->save_surface(options_.save_surface);
    log_.info("wrote the surface to " + options_.save_surface.string());
  }
  if (!options_.save.empty()) {
    session_->save(options_.save);
    log_.info("wrote the sketch to " + options_.save.string());
  }
  if (!options_.record.empty()) {
    input::write_track(recorded_, options_.record);
    log_.info("recorded " + std::to_string(recorded_.events.size()) + " events to " +
              options_.record.string());
  }
  session_->flush_autosave();
  const auto& autosave = session_->autosave_path();
  if (!autosave.empty()) {
    if (!session_->modified() || session_->sketch().strokes.empty()) {
      std::error_code ignored;
      std::filesystem::remove(autosave, ignored);
    } else {
      log_.info("unsaved strokes are in " + autosave.string());
    }
  }
}

}  // namespace sketchsurf::studio
