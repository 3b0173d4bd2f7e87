#pragma once
// SketchSession: the sketch being drawn and the tools acting on it. Controller samples come in
// (apply), edits come out as a live, undoable Sketch; the Surfacer runs on a worker thread
// (surface) while the frame loop goes on; every finished edit is autosaved to a temporary file
// by a writer thread, so that a crash loses no finished stroke.
//
// No GLFW, no Vulkan: the session is driven and tested headless. Every public member is called
// from one thread (the frame loop); the surfacing and autosave threads talk to it through their
// own synchronised state.

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "engine/input/controller.h"
#include "surfacing/pipeline.h"
#include "surfacing/sketch/sketch.h"

namespace sketchsurf::session {

/// What the trigger does.
enum class Tool {
  Draw,          ///< draws a stroke from trigger down to trigger up
  Erase,         ///< erases every stroke the controller touches while the trigger is held
  MarkBoundary,  ///< toggles "boundary" (edge of an open surface) on the stroke touched at press
  MarkIgnored,   ///< toggles "ignored" (the surface must not follow it) on the stroke touched
  PlacePlane,    ///< three presses place the drawing plane through the three points (then Draw)
};

/// "draw", "erase", "boundary", "ignore", "plane".
std::string_view tool_name(Tool tool);
/// The tool named `name` (as tool_name() spells it); empty when unknown.
std::optional<Tool> parse_tool(std::string_view name);

/// How strokes are drawn and touched, and the drawing aids (each on or off). Lengths are
/// fractions of the session's reference size.
struct DrawingOptions {
  double min_spacing = 0.002;  ///< a point closer than this to the previous kept point is dropped
                               ///< (the last point of a stroke is always kept)
  double pick_radius = 0.02;   ///< how near the controller must be to a stroke to erase or mark it
  double width = 0.005;        ///< brush width stored with new strokes
  std::array<float, 4> color{0.1f, 0.1f, 0.1f, 1.0f};  ///< RGBA of new strokes

  // Drawing aids (drawing_plane.h, stroke_aids.h; patterns are the sketch's, see set_mirror).
  Plane plane{Eigen::Vector3d::UnitZ(), 0.0};  ///< the drawing plane (unit normal; the mouse's
                                               ///< cursor ray lands on it)
  bool plane_guide = false;    ///< points drawn within plane_band of the plane are projected onto it
  double plane_band = 0.03;    ///< the guide's band on each side of the plane
  bool snap = false;           ///< stroke ends within snap_radius of a stroke are moved onto it
  double snap_radius = 0.02;   ///< the mouse sets it from a radius in pixels (the studio's view)
  bool oversketch = false;     ///< a stroke drawn along part of a stroke replaces that part
  double oversketch_distance = 0.03;  ///< every point of it within this of the stroke (its ends
                                      ///< within snap_radius)
  int smoothing = 0;           ///< rounds of Kuhn's iterative smoothing of each new stroke (0: off)
  bool straight = false;       ///< each new stroke becomes the segment between its ends

  /// False (with the reason in `why`) when a length is negative or not finite, the plane's
  /// normal not unit or its offset not finite, or smoothing negative or above 1000.
  bool valid(std::string* why) const;
};

/// How a session starts.
struct SessionOptions {
  DrawingOptions drawing;
  double reference_size = 1.0;     ///< sketch units that the drawing fractions refer to; opening
                                   ///< a sketch sets it to the sketch's bounding-box diagonal
  std::filesystem::path autosave;  ///< .json file rewritten after every edit; empty = none
  Params params;                   ///< surfacing parameters
  bool background_priority = true; ///< surfacing threads run at a lower priority (nice 10) than
                                   ///< the frame loop, so that drawing stays fluid
};

/// Where the surfacing job stands.
enum class JobState { Idle, Running, Cancelling, Done, Failed, Cancelled };

struct SurfaceStatus {
  JobState state = JobState::Idle;
  std::string stage;        ///< the pipeline stage running ("proxy", "segment", ...)
  double fraction = 0.0;    ///< progress of that stage, in [0, 1]
  std::string message;      ///< for Failed: the error; for Done: a one-line summary
  double elapsed_s = 0.0;   ///< since surface() (to the end, once ended)
};

class SketchSession {
 public:
  /// Throws Error (Usage) for invalid drawing options or parameters.
  explicit SketchSession(SessionOptions options = {});
  /// Cancels a running surfacing and waits for it; writes the pending autosave.
  ~SketchSession();
  SketchSession(const SketchSession&) = delete;
  SketchSession& operator=(const SketchSession&) = delete;

  // --- the sketch -------------------------------------------------------------------------
  const Sketch& sketch() const { return sketch_; }
  /// Changes whenever sketch() does (edit, undo, redo, open).
  std::uint64_t revision() const { return revision_; }
  /// The stroke being drawn, and its mirror image when the mirror is on; empty when not drawing.
  const std::vector<Stroke>& live_strokes() const { return live_; }
  /// Changes whenever live_strokes() does.
  std::uint64_t live_revision() const { return live_revision_; }
  double reference_size() const { return reference_size_; }
  /// Throws Error (Usage) unless positive and finite.
  void set_reference_size(double size);
  const DrawingOptions& drawing() const { return drawing_; }
  /// Throws Error (Usage) for invalid options.
  void set_drawing(const DrawingOptions& options);

  // --- controller input -------------------------------------------------------------------
  /// Applies one controller sample: the trigger (Draw button) drives the active tool, Undo and
  /// Redo act when pressed. Samples must come in time order. With the plane guide on, each point
  /// drawn within its band is projected onto the drawing plane. When the trigger is released the
  /// stroke is finished: made straight, smoothed, then either over-sketched onto the stroke it
  /// runs along (that stroke is changed, no stroke added) or its ends snapped; then it is added
  /// with its pattern images. One undo step per stroke, whatever the aids did.
  void apply(const input::ControllerState& state);
  Tool tool() const { return tool_; }
  /// Switches tools; a stroke in progress is finished first.
  void set_tool(Tool tool);
  bool drawing_in_progress() const { return live_active_; }
  /// The points placed so far by the PlacePlane tool (0 to 2).
  const std::vector<Eigen::Vector3d>& plane_points() const { return plane_points_; }

  // --- edits (each one undoable) ------------------------------------------------------------
  /// Adds a finished stroke (with its images under the mirror and the rotation, when on), giving
  /// it the next free id (the images the ids after it); returns that id. Strokes with fewer than
  /// 2 points are refused (returns -1). The aids are not applied (see finish order in apply()).
  std::int64_t add_stroke(Stroke stroke);
  /// Each returns false (and changes nothing) when no stroke has the id or nothing would change.
  bool erase_stroke(std::int64_t id);
  bool set_boundary(std::int64_t id, bool boundary);
  bool set_ignored(std::int64_t id, bool ignored);
  /// Sets (or, with none, clears) the mirror plane: strokes drawn from now on get their mirror
  /// image, and the Surfacer surfaces one half and mirrors it. Returns false when unchanged.
  bool set_mirror(const std::optional<Plane>& plane);
  /// Sets (or, with none, clears) the rotational pattern: strokes drawn from now on are repeated
  /// count times about the axis. Stored in the sketch (.json). Returns false when unchanged.
  /// Throws Error (Usage) for a zero axis or a count outside 2..360.
  bool set_rotation(const std::optional<RotationPattern>& pattern);
  /// Erases every stroke. Returns false when there is none.
  bool clear();

  /// The id of the stroke nearest to `p` within `radius` (sketch units), if any.
  std::optional<std::int64_t> nearest_stroke(const Eigen::Vector3d& p, double radius) const;
  /// Distance along the ray (origin, unit direction) to the nearest surface triangle or stroke
  /// point it passes within `radius_per_distance` times its distance; empty when none.
  std::optional<double> pick(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                             double radius_per_distance) const;

  // --- history ------------------------------------------------------------------------------
  bool can_undo() const { return !undo_.empty() || live_active_; }
  bool can_redo() const { return !redo_.empty(); }
  /// Discards the stroke in progress, if any; otherwise undoes the last edit. False when nothing.
  bool undo();
  /// Redoes the last undone edit. False when nothing.
  bool redo();
  /// Names of the edits undo() / redo() would act on ("draw", "erase", ...); empty when none.
  std::string undo_name() const;
  std::string redo_name() const;

  // --- files --------------------------------------------------------------------------------
  /// Replaces the sketch with the file's (.json, .tilt, .curves, .obj), clears the history and
  /// the surface, applies the parameters stored in it, sets the reference size to its diagonal.
  /// Throws Error (Input, Usage) naming the file; the session is unchanged then.
  void open(const std::filesystem::path& file);
  /// Writes the sketch (.json, .tilt, .obj), with the session's parameters in a .json.
  /// Throws Error.
  void save(const std::filesystem::path& file);
  /// True when the sketch changed since it was opened or saved.
  bool modified() const { return revision_ != saved_revision_; }
  /// The file last opened or saved (empty for a new sketch).
  const std::filesystem::path& file() const { return file_; }
  /// Uses the mesh (.obj, .ply) as the proxy of the next surfacings instead of VIPSS's.
  void open_proxy(const std::filesystem::path& file);
  void clear_proxy() { proxy_.reset(); }
  bool has_proxy() const { return proxy_ != nullptr; }
  /// Writes the surface (.obj, .ply with labels, .glb, .gltf). Throws Error (Usage) when there is
  /// none yet.
  void save_surface(const std::filesystem::path& file) const;

  // --- autosave -----------------------------------------------------------------------------
  const std::filesystem::path& autosave_path() const { return autosave_path_; }
  /// The revision() last written to the autosave file (0 before the first write).
  std::uint64_t autosaved_revision() const { return autosaved_.load(); }
  /// The last autosave failure, empty when it works.
  std::string autosave_error() const;
  /// Waits until the current revision is in the autosave file (no-op without autosave).
  void flush_autosave();

  // --- surfacing ----------------------------------------------------------------------------
  const Params& params() const { return params_; }
  /// Sets one parameter by its dotted name (Params::apply); kept in the sketch's params, so that
  /// save() stores it. Throws Error (Usage) for an unknown name or invalid value.
  void set_param(const std::string& name, double value);
  /// Starts the Surfacer on a copy of the sketch, on a worker thread. Returns false (nothing
  /// started) while a previous job is still running or cancelling.
  bool surface();
  /// Asks the running job to stop (it ends at its next progress report).
  void cancel_surface();
  SurfaceStatus surface_status() const;
  /// Call once per frame: takes the result of a job that ended. True when result() changed.
  bool poll_surface();
  /// Blocks until the job ends or `timeout_s` passes, then poll_surface(). True when it ended.
  bool wait_surface(double timeout_s);
  /// The last surface computed, or nullptr.
  const SurfaceResult* result() const { return result_.get(); }
  /// Shows `result` as the surface (one computed before, read from a file).
  void set_result(SurfaceResult result);
  /// Changes whenever result() does.
  std::uint64_t result_revision() const { return result_revision_; }

 private:
  struct StrokeChange {
    std::size_t index = 0;          // position in sketch_.strokes
    std::optional<Stroke> before;   // empty: inserted
    std::optional<Stroke> after;    // empty: removed
  };
  struct Patterns {
    std::optional<Plane> mirror;
    std::optional<RotationPattern> rotation;
  };
  struct Edit {
    std::string name;
    std::vector<StrokeChange> changes;
    bool patterns_changed = false;
    Patterns patterns_before, patterns_after;
  };
  struct Job;

  /// Applies `edit` forwards (or backwards), bumps the revision, schedules the autosave.
  void play(const Edit& edit, bool forwards);
  /// Plays `edit` forwards and pushes it onto the undo stack (clearing redo).
  void commit(Edit edit);
  /// Sets the sketch's patterns as one undoable edit named `name`; false when unchanged.
  bool change_patterns(const char* name, const Patterns& after);
  std::optional<std::size_t> index_of(std::int64_t id) const;
  bool set_flag(std::int64_t id, bool Stroke::*flag, bool value, const char* name);
  std::int64_t next_id() const;
  void changed();
  // Drawing.
  void begin_stroke(const input::ControllerState& state);
  void add_point(const input::ControllerState& state, bool last);
  void finish_stroke();
  /// The finished stroke through the aids (straight, smoothing, over-sketch or snap), committed.
  void commit_stroke(Stroke stroke);
  void refresh_live();
  void place_plane_point(const input::ControllerState& state);
  void touch(const input::ControllerState& state, bool pressed_now);
  // Autosave writer.
  void schedule_autosave();
  void autosave_loop();

  Sketch sketch_;
  std::uint64_t revision_ = 1, saved_revision_ = 1, live_revision_ = 0;
  std::vector<Edit> undo_, redo_;
  DrawingOptions drawing_;
  double reference_size_ = 1.0;
  Tool tool_ = Tool::Draw;
  input::ControllerState last_;
  bool live_active_ = false;
  Stroke stroke_;              // the stroke in progress
  std::vector<Eigen::Vector3d> plane_points_;  // PlacePlane's clicks so far
  std::vector<Stroke> live_;   // it and its mirror image, for drawing
  std::filesystem::path file_;
  std::shared_ptr<const TriMesh> proxy_;
  Params params_;
  bool background_priority_ = true;

  std::shared_ptr<Job> job_;
  std::thread worker_;
  bool job_taken_ = true;
  SurfaceStatus last_status_;
  std::unique_ptr<SurfaceResult> result_;
  std::uint64_t result_revision_ = 0;

  std::filesystem::path autosave_path_;
  std::thread autosave_thread_;
  mutable std::mutex autosave_mutex_;
  std::condition_variable autosave_cv_;
  std::optional<std::pair<std::uint64_t, Sketch>> autosave_pending_;
  bool autosave_stop_ = false;
  std::atomic<std::uint64_t> autosaved_{0};
  std::uint64_t attempted_ = 0;  // revision last written or failed (guarded by autosave_mutex_)
  std::string autosave_error_;
};

}  // namespace sketchsurf::session
