#pragma once
// The studio's core, shared by the window and --headless: the session, the controllers (the mouse,
// or a replayed track), the recorder, the view and the status line. The two front ends
// (run_window.cpp, run_headless.cpp) own the render target and the frame loop; they call, per
// frame: input(now) -> the panel -> update() -> record().

#include <deque>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "engine/input/mouse.h"
#include "engine/input/scripted.h"
#include "engine/render/session_view.h"
#include "engine/session/session.h"

namespace sketchsurf::studio {

/// The command line.
struct StudioOptions {
  std::filesystem::path sketch;        ///< opened at start (optional)
  std::filesystem::path record;        ///< track written at exit
  std::filesystem::path replay;        ///< track replayed from the start
  std::filesystem::path screenshot;    ///< the last frame, as PNG
  std::filesystem::path save;          ///< the sketch written at exit
  std::filesystem::path save_surface;  ///< the surface written at exit
  std::filesystem::path proxy;         ///< a proxy mesh for surfacing
  std::filesystem::path autosave;      ///< default: a file in the temporary directory
  bool no_autosave = false;
  std::optional<int> frames;           ///< run this many frames (at least), then exit
  int width = 1280, height = 720;
  bool headless = false;
  bool xr = false;                     ///< in a headset (OpenXR); the desktop when there is none
  bool surface = false;                ///< surface once the replay is over; wait for it
  std::map<std::string, double> params;
  int msaa = 0;                        ///< 1, 2 or 4; 0: 4 on a GPU, 1 on the CPU (lavapipe)
  std::string device;
  bool validation = false;
  bool vsync = true;
  bool verbose = false, quiet = false;
};

/// Lines for the user on stderr: info unless --quiet, detail with --verbose.
struct Log {
  bool verbose = false, quiet = false;
  void info(const std::string& line) const;
  void detail(const std::string& line) const;
};

/// Frame times, for the status line and the exit summary.
struct FrameStats {
  std::size_t frames = 0;
  double median_ms = 0.0, p95_ms = 0.0, max_ms = 0.0;
};

class Studio {
 public:
  /// Opens the sketch, reads the replay and the proxy, applies --param. Throws Error.
  Studio(const StudioOptions& options, const vk::Context& context, const Log& log);
  ~Studio();
  Studio(const Studio&) = delete;
  Studio& operator=(const Studio&) = delete;

  session::SketchSession& session() { return *session_; }
  const session::SketchSession& session() const { return *session_; }
  input::MouseController& mouse() { return mouse_; }
  render::SessionViewOptions& view_options() { return view_options_; }
  const render::SessionView& view() const { return view_; }
  const StudioOptions& options() const { return options_; }

  /// The time of frame `index` on the simulated clock (headless, or a window with --frames):
  /// a replay is spread over --frames frames, otherwise 60 frames a second.
  double simulated_time(std::size_t index) const;
  /// Feeds the input up to `now` (seconds) to the session: the replay's samples and actions
  /// while it lasts, then the mouse's samples. Records them with --record.
  void input(double now);
  /// Applies a panel or key action and records it. Errors go to the status line (during a replay
  /// they end the run: rethrown).
  void act(const input::TrackAction& action);
  /// Per frame, after input and panel: takes a finished surfacing, starts --surface when due,
  /// brings the view up to date.
  void update();
  /// Records the view into the render pass begun on `cmd`.
  void record(VkCommandBuffer cmd, const render::Renderer& renderer, int width, int height,
              std::vector<std::shared_ptr<const void>>* in_use) const;
  /// Records the view as seen by `camera` (a headset's eye) into the render pass begun on `cmd`.
  void record(VkCommandBuffer cmd, const render::Renderer& renderer, const render::Camera& camera,
              double aspect, std::vector<std::shared_ptr<const void>>* in_use) const;
  /// Takes the samples of `controller` (a headset's, not owned) in place of the mouse's; null
  /// gives the mouse back.
  void set_controller(input::Controller6DoF* controller) { controller_ = controller; }
  /// The view's camera, clip planes fitted to what is drawn.
  render::Camera camera() const;

  bool replaying() const { return scripted_ && !scripted_->finished(); }
  /// True once `frames` frames were rendered, the replay is over and --surface has ended.
  bool done(std::size_t frames) const;
  /// The frame count --frames asks for (or what a replay needs at 60 Hz, or 1 headless).
  std::size_t frames_wanted() const;

  /// Frame time bookkeeping.
  void frame_finished(double seconds);
  FrameStats stats() const;
  const std::string& status() const { return status_; }
  void set_status(const std::string& line);
  /// Panel visibility (Tab, the controller's menu button).
  bool panel_visible = true;
  /// Frames the view on everything drawn (F).
  void frame_all(int width, int height);
  /// Frames the view on `box`, in the part of a width x height window the panel leaves free.
  void frame_box(const BoundingBox& box, int width, int height);
  /// The panel's width, and the pixels it takes from the window's left edge (with its margins).
  static constexpr int kPanelWidth = 320, kPanelSpace = 336;
  /// The mouse's snap radius (the session's snap and over-sketch ends), pixels at the view's
  /// target; a controller in 3D uses a fraction of the sketch's diagonal instead.
  static constexpr double kSnapPixels = 12.0;

  /// At exit: --save, --save-surface, --record; the autosave is removed when nothing is unsaved.
  void finish();

 private:
  void apply_state(const input::ControllerState& state);
  /// Sets the session's snap radius to kSnapPixels at the view's target (an action: recorded).
  void update_snap_radius();
  void log_progress();

  StudioOptions options_;
  const Log& log_;
  std::unique_ptr<session::SketchSession> session_;
  input::MouseController mouse_;
  input::Controller6DoF* controller_ = nullptr;
  std::optional<input::ScriptedController> scripted_;
  input::Track recorded_;
  render::SessionView view_;
  render::SessionViewOptions view_options_;
  input::ControllerState last_state_;
  std::string status_;
  bool surface_started_ = false;
  std::uint64_t logged_autosave_ = 0;
  session::JobState logged_job_ = session::JobState::Idle;
  std::string logged_stage_;
  std::deque<double> frame_ms_;
  std::vector<double> all_frame_ms_;
  double now_ = 0.0;
};

}  // namespace sketchsurf::studio
