#include "engine/session/session.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#ifdef __linux__
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

#include "engine/session/drawing_plane.h"
#include "engine/session/pattern.h"
#include "engine/session/stroke_aids.h"
#include "surfacing/error.h"
#include "surfacing/sketch/io/mesh_io.h"
#include "surfacing/sketch/io/sketch_io.h"

namespace sketchsurf::session {

namespace {

using Clock = std::chrono::steady_clock;

double seconds_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

/// Distance along the ray to the triangle (Moller-Trumbore), if it hits in front of the origin.
std::optional<double> ray_triangle(const Eigen::Vector3d& o, const Eigen::Vector3d& d,
                                   const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                   const Eigen::Vector3d& c) {
  const Eigen::Vector3d e1 = b - a, e2 = c - a;
  const Eigen::Vector3d p = d.cross(e2);
  const double det = e1.dot(p);
  if (std::abs(det) < 1e-300) return std::nullopt;
  const double inv = 1.0 / det;
  const Eigen::Vector3d s = o - a;
  const double u = s.dot(p) * inv;
  if (u < 0.0 || u > 1.0) return std::nullopt;
  const Eigen::Vector3d q = s.cross(e1);
  const double v = d.dot(q) * inv;
  if (v < 0.0 || u + v > 1.0) return std::nullopt;
  const double t = e2.dot(q) * inv;
  if (t <= 0.0) return std::nullopt;
  return t;
}

void check_non_negative(double v, const char* name, std::string* why, bool& ok) {
  if (ok && (!(v >= 0.0) || !std::isfinite(v))) {
    if (why) *why = std::string(name) + " must be >= 0 and finite";
    ok = false;
  }
}

}  // namespace

std::string_view tool_name(Tool tool) {
  switch (tool) {
    case Tool::Draw: return "draw";
    case Tool::Erase: return "erase";
    case Tool::MarkBoundary: return "boundary";
    case Tool::MarkIgnored: return "ignore";
    case Tool::PlacePlane: return "plane";
  }
  return "?";
}

std::optional<Tool> parse_tool(std::string_view name) {
  for (Tool t : {Tool::Draw, Tool::Erase, Tool::MarkBoundary, Tool::MarkIgnored, Tool::PlacePlane})
    if (tool_name(t) == name) return t;
  return std::nullopt;
}

bool DrawingOptions::valid(std::string* why) const {
  bool ok = true;
  check_non_negative(min_spacing, "min_spacing", why, ok);
  check_non_negative(pick_radius, "pick_radius", why, ok);
  check_non_negative(width, "width", why, ok);
  check_non_negative(plane_band, "plane_band", why, ok);
  check_non_negative(snap_radius, "snap_radius", why, ok);
  check_non_negative(oversketch_distance, "oversketch_distance", why, ok);
  if (ok && (!plane.normal.allFinite() || std::abs(plane.normal.norm() - 1.0) > 1e-9 ||
             !std::isfinite(plane.offset))) {
    if (why) *why = "plane must have a unit normal and a finite offset";
    ok = false;
  }
  if (ok && (smoothing < 0 || smoothing > 1000)) {
    if (why) *why = "smoothing must be from 0 to 1000 rounds";
    ok = false;
  }
  return ok;
}

// ----------------------------------------------------------------------------------------------
// The surfacing job: shared by the session and its worker thread.

struct SketchSession::Job {
  std::atomic<bool> cancel{false};
  std::atomic<bool> finished{false};
  mutable std::mutex mutex;
  std::string stage = "starting";
  double fraction = 0.0;
  std::unique_ptr<SurfaceResult> result;
  std::string error;
  bool cancelled = false;
  Clock::time_point start = Clock::now(), end;
};

SketchSession::SketchSession(SessionOptions options)
    : params_(std::move(options.params)), background_priority_(options.background_priority) {
  set_drawing(options.drawing);
  set_reference_size(options.reference_size);
  std::string why;
  if (!params_.valid(&why)) throw Error::usage("invalid parameters: " + why);
  if (!options.autosave.empty()) {
    if (options.autosave.extension() != ".json")
      throw Error::usage("the autosave file must be a .json sketch, not '" +
                         options.autosave.string() + "'");
    autosave_path_ = options.autosave;
    autosave_thread_ = std::thread([this] { autosave_loop(); });
    schedule_autosave();  // the file exists from the start
  }
}

SketchSession::~SketchSession() {
  if (job_) job_->cancel = true;
  if (worker_.joinable()) worker_.join();
  if (autosave_thread_.joinable()) {
    {
      std::lock_guard<std::mutex> lock(autosave_mutex_);
      autosave_stop_ = true;
    }
    autosave_cv_.notify_all();
    autosave_thread_.join();
  }
}

void SketchSession::set_reference_size(double size) {
  if (!(size > 0.0) || !std::isfinite(size))
    throw Error::usage("the reference size must be positive and finite");
  reference_size_ = size;
}

void SketchSession::set_drawing(const DrawingOptions& options) {
  std::string why;
  if (!options.valid(&why)) throw Error::usage("drawing options: " + why);
  drawing_ = options;
}

// ----------------------------------------------------------------------------------------------
// Controller input.

void SketchSession::apply(const input::ControllerState& state) {
  using input::Button;
  const bool was = last_.pressed(Button::Draw), down = state.pressed(Button::Draw);
  if (state.pressed(Button::Undo) && !last_.pressed(Button::Undo)) undo();
  if (state.pressed(Button::Redo) && !last_.pressed(Button::Redo)) redo();
  if (tool_ == Tool::Draw) {
    if (down && !was) {
      begin_stroke(state);
    } else if (down && live_active_) {
      add_point(state, false);
    } else if (!down && was && live_active_) {
      add_point(state, true);
      finish_stroke();
    }
  } else if (tool_ == Tool::PlacePlane) {
    if (down && !was) place_plane_point(state);
  } else if (down) {
    touch(state, !was);
  }
  last_ = state;
}

void SketchSession::place_plane_point(const input::ControllerState& state) {
  if (!state.tracked || !state.pose.position.allFinite()) return;
  plane_points_.push_back(state.pose.position);
  if (plane_points_.size() < 3) return;
  const std::vector<Eigen::Vector3d> points = std::move(plane_points_);
  plane_points_.clear();
  // Three points on a line place nothing; the user clicks again.
  Plane plane;
  try {
    plane = plane_through(points[0], points[1], points[2]);
  } catch (const Error&) {
    return;
  }
  drawing_.plane = plane;
  drawing_.plane_guide = true;
  tool_ = Tool::Draw;
}

void SketchSession::set_tool(Tool tool) {
  if (live_active_) finish_stroke();
  plane_points_.clear();
  tool_ = tool;
}

void SketchSession::begin_stroke(const input::ControllerState& state) {
  stroke_ = Stroke{};
  stroke_.width = drawing_.width * reference_size_;
  stroke_.color = drawing_.color;
  live_active_ = true;
  add_point(state, false);
  refresh_live();
}

void SketchSession::add_point(const input::ControllerState& state, bool last) {
  if (!state.tracked) return;
  Eigen::Vector3d p = state.pose.position;
  if (!p.allFinite()) return;
  if (drawing_.plane_guide) p = guide_to_plane(drawing_.plane, p, drawing_.plane_band * reference_size_);
  if (!stroke_.points.empty()) {
    const double d = (p - stroke_.points.back()).norm();
    if (last ? d == 0.0 : d < drawing_.min_spacing * reference_size_) return;
  }
  stroke_.points.push_back(p);
  stroke_.orientations.push_back(state.pose.orientation.normalized());
  stroke_.pressures.push_back(std::clamp(state.trigger, 0.0f, 1.0f));
  const double ms = std::clamp(std::round(state.time_s * 1000.0), 0.0,
                               double(std::numeric_limits<std::uint32_t>::max()));
  stroke_.timestamps_ms.push_back(static_cast<std::uint32_t>(ms));
  refresh_live();
}

void SketchSession::refresh_live() {
  live_.clear();
  if (live_active_) {
    live_.push_back(stroke_);
    for (Stroke& image : pattern_images(stroke_, sketch_.mirror, sketch_.rotation))
      live_.push_back(std::move(image));
  }
  ++live_revision_;
}

void SketchSession::finish_stroke() {
  live_active_ = false;
  refresh_live();
  if (stroke_.points.size() >= 2) commit_stroke(std::move(stroke_));
  stroke_ = Stroke{};
}

void SketchSession::commit_stroke(Stroke stroke) {
  if (drawing_.straight) straighten(stroke);
  smooth_stroke(stroke, drawing_.smoothing);
  const double radius = drawing_.snap_radius * reference_size_;
  if (drawing_.oversketch) {
    OversketchOptions options;
    options.end_radius = radius;
    options.max_distance = std::max(radius, drawing_.oversketch_distance * reference_size_);
    if (const auto target = oversketch_target(sketch_.strokes, stroke, options)) {
      // The stroke and each of its pattern images correct the stroke each runs along.
      Edit edit;
      edit.name = "over-sketch";
      std::vector<Stroke> styles{stroke};
      for (Stroke& image : pattern_images(stroke, sketch_.mirror, sketch_.rotation))
        styles.push_back(std::move(image));
      std::vector<bool> changed(sketch_.strokes.size(), false);
      for (std::size_t k = 0; k < styles.size(); ++k) {
        const auto index = k == 0 ? target : oversketch_target(sketch_.strokes, styles[k], options);
        if (!index || changed[*index]) continue;
        changed[*index] = true;
        const Stroke& old = sketch_.strokes[*index];
        edit.changes.push_back({*index, old, oversketch(old, styles[k], OversketchOptions{}.blend)});
      }
      commit(std::move(edit));
      return;
    }
  }
  if (drawing_.snap)
    snap_ends(stroke, sketch_.strokes, radius,
              drawing_.plane_guide ? std::optional<Plane>(drawing_.plane) : std::nullopt, sketch_.mirror);
  add_stroke(std::move(stroke));
}

void SketchSession::touch(const input::ControllerState& state, bool pressed_now) {
  if (!state.tracked) return;
  const auto id = nearest_stroke(state.pose.position, drawing_.pick_radius * reference_size_);
  if (!id) return;
  const Stroke& s = sketch_.strokes[*index_of(*id)];
  switch (tool_) {
    case Tool::Erase: erase_stroke(*id); break;
    case Tool::MarkBoundary:
      if (pressed_now) set_boundary(*id, !s.boundary);
      break;
    case Tool::MarkIgnored:
      if (pressed_now) set_ignored(*id, !s.ignored);
      break;
    case Tool::Draw:
    case Tool::PlacePlane: break;
  }
}

// ----------------------------------------------------------------------------------------------
// Edits and history.

std::optional<std::size_t> SketchSession::index_of(std::int64_t id) const {
  for (std::size_t i = 0; i < sketch_.strokes.size(); ++i)
    if (sketch_.strokes[i].id == id) return i;
  return std::nullopt;
}

std::int64_t SketchSession::next_id() const {
  std::int64_t next = 0;
  for (const Stroke& s : sketch_.strokes) next = std::max(next, s.id + 1);
  return next;
}

void SketchSession::changed() {
  ++revision_;
  schedule_autosave();
}

void SketchSession::play(const Edit& edit, bool forwards) {
  auto& strokes = sketch_.strokes;
  // Removals from the back, so that the indices of the others still hold; then changes in
  // place; then insertions from the front. (An edit never mixes removals and insertions.)
  std::vector<const StrokeChange*> changes;
  for (const auto& c : edit.changes) changes.push_back(&c);
  std::sort(changes.begin(), changes.end(),
            [](const StrokeChange* a, const StrokeChange* b) { return a->index < b->index; });
  for (auto it = changes.rbegin(); it != changes.rend(); ++it) {
    const auto& from = forwards ? (*it)->before : (*it)->after;
    const auto& to = forwards ? (*it)->after : (*it)->before;
    if (from && !to) strokes.erase(strokes.begin() + std::ptrdiff_t((*it)->index));
  }
  for (const StrokeChange* c : changes) {
    const auto& from = forwards ? c->before : c->after;
    const auto& to = forwards ? c->after : c->before;
    if (from && to) strokes[c->index] = *to;
    if (!from && to) strokes.insert(strokes.begin() + std::ptrdiff_t(c->index), *to);
  }
  if (edit.patterns_changed) {
    const Patterns& to = forwards ? edit.patterns_after : edit.patterns_before;
    sketch_.mirror = to.mirror;
    sketch_.rotation = to.rotation;
  }
  changed();
}

void SketchSession::commit(Edit edit) {
  play(edit, true);
  undo_.push_back(std::move(edit));
  redo_.clear();
}

bool SketchSession::undo() {
  if (live_active_) {  // "oops": the stroke in progress goes
    live_active_ = false;
    stroke_ = Stroke{};
    refresh_live();
    return true;
  }
  if (undo_.empty()) return false;
  Edit edit = std::move(undo_.back());
  undo_.pop_back();
  play(edit, false);
  redo_.push_back(std::move(edit));
  return true;
}

bool SketchSession::redo() {
  if (redo_.empty() || live_active_) return false;
  Edit edit = std::move(redo_.back());
  redo_.pop_back();
  play(edit, true);
  undo_.push_back(std::move(edit));
  return true;
}

std::string SketchSession::undo_name() const {
  if (live_active_) return "stroke in progress";
  return undo_.empty() ? "" : undo_.back().name;
}

std::string SketchSession::redo_name() const { return redo_.empty() ? "" : redo_.back().name; }

std::int64_t SketchSession::add_stroke(Stroke stroke) {
  if (stroke.points.size() < 2) return -1;
  Edit edit;
  edit.name = "draw";
  const std::int64_t id = next_id();
  stroke.id = id;
  std::vector<Stroke> images = pattern_images(stroke, sketch_.mirror, sketch_.rotation);
  const std::size_t n = sketch_.strokes.size();
  edit.changes.push_back({n, std::nullopt, std::move(stroke)});
  for (std::size_t k = 0; k < images.size(); ++k) {
    images[k].id = id + 1 + std::int64_t(k);
    edit.changes.push_back({n + 1 + k, std::nullopt, std::move(images[k])});
  }
  commit(std::move(edit));
  return id;
}

bool SketchSession::erase_stroke(std::int64_t id) {
  const auto index = index_of(id);
  if (!index) return false;
  Edit edit;
  edit.name = "erase";
  edit.changes.push_back({*index, sketch_.strokes[*index], std::nullopt});
  commit(std::move(edit));
  return true;
}

bool SketchSession::set_flag(std::int64_t id, bool Stroke::*flag, bool value, const char* name) {
  const auto index = index_of(id);
  if (!index || sketch_.strokes[*index].*flag == value) return false;
  Edit edit;
  edit.name = name;
  Stroke after = sketch_.strokes[*index];
  after.*flag = value;
  edit.changes.push_back({*index, sketch_.strokes[*index], std::move(after)});
  commit(std::move(edit));
  return true;
}

bool SketchSession::set_boundary(std::int64_t id, bool boundary) {
  return set_flag(id, &Stroke::boundary, boundary, boundary ? "mark boundary" : "unmark boundary");
}

bool SketchSession::set_ignored(std::int64_t id, bool ignored) {
  return set_flag(id, &Stroke::ignored, ignored, ignored ? "mark ignored" : "unmark ignored");
}

bool SketchSession::set_mirror(const std::optional<Plane>& plane) {
  std::optional<Plane> normalised;
  if (plane) {
    const double n = plane->normal.norm();
    if (!(n > 0.0) || !std::isfinite(n) || !std::isfinite(plane->offset))
      throw Error::usage("the mirror plane needs a finite, non-zero normal");
    normalised = Plane{plane->normal / n, plane->offset / n};
  }
  Patterns after{normalised, sketch_.rotation};
  return change_patterns(normalised ? "mirror" : "clear mirror", after);
}

bool SketchSession::set_rotation(const std::optional<RotationPattern>& pattern) {
  std::optional<RotationPattern> checked;
  if (pattern) checked = checked_rotation(*pattern);
  Patterns after{sketch_.mirror, checked};
  return change_patterns(checked ? "rotation" : "clear rotation", after);
}

bool SketchSession::change_patterns(const char* name, const Patterns& after) {
  const auto same_mirror = [](const std::optional<Plane>& x, const std::optional<Plane>& y) {
    return x.has_value() == y.has_value() && (!x || (x->normal == y->normal && x->offset == y->offset));
  };
  const auto same_rotation = [](const std::optional<RotationPattern>& x, const std::optional<RotationPattern>& y) {
    return x.has_value() == y.has_value() &&
           (!x || (x->center == y->center && x->axis == y->axis && x->count == y->count));
  };
  if (same_mirror(sketch_.mirror, after.mirror) && same_rotation(sketch_.rotation, after.rotation)) return false;
  if (live_active_) finish_stroke();
  Edit edit;
  edit.name = name;
  edit.patterns_changed = true;
  edit.patterns_before = {sketch_.mirror, sketch_.rotation};
  edit.patterns_after = after;
  commit(std::move(edit));
  return true;
}

bool SketchSession::clear() {
  if (sketch_.strokes.empty()) return false;
  if (live_active_) finish_stroke();
  Edit edit;
  edit.name = "clear";
  for (std::size_t i = 0; i < sketch_.strokes.size(); ++i)
    edit.changes.push_back({i, sketch_.strokes[i], std::nullopt});
  commit(std::move(edit));
  return true;
}

std::optional<std::int64_t> SketchSession::nearest_stroke(const Eigen::Vector3d& p,
                                                          double radius) const {
  std::optional<std::int64_t> best;
  double best_distance = radius;
  for (const Stroke& s : sketch_.strokes) {
    const double d = distance_to_stroke(p, s);
    if (d <= best_distance) {
      best_distance = d;
      best = s.id;
    }
  }
  return best;
}

std::optional<double> SketchSession::pick(const Eigen::Vector3d& origin,
                                          const Eigen::Vector3d& direction,
                                          double radius_per_distance) const {
  std::optional<double> best;
  const auto keep = [&](double t) {
    if (!best || t < *best) best = t;
  };
  if (result_) {
    const TriMesh& mesh = result_->mesh;
    for (auto f : mesh.faces()) {
      std::array<Eigen::Vector3d, 3> corner;
      int k = 0;
      for (auto v : mesh.fv_range(f))
        if (k < 3) corner[k++] = to_eigen(mesh.point(v));
      if (k < 3) continue;
      if (const auto t = ray_triangle(origin, direction, corner[0], corner[1], corner[2])) keep(*t);
    }
  }
  for (const Stroke& s : sketch_.strokes)
    for (const auto& p : s.points) {
      const double t = (p - origin).dot(direction);
      if (t <= 0.0) continue;
      if ((p - origin - t * direction).norm() <= radius_per_distance * t) keep(t);
    }
  return best;
}

// ----------------------------------------------------------------------------------------------
// Files.

void SketchSession::open(const std::filesystem::path& file) {
  Sketch loaded = read_sketch(file);
  check_extent(loaded, file);
  loaded.assign_ids();
  Params params = params_;
  try {
    params.apply(loaded.params);
  } catch (const Error& e) {
    throw Error::input(file, e.what());
  }
  if (live_active_) {
    live_active_ = false;
    stroke_ = Stroke{};
    refresh_live();
  }
  if (job_) job_->cancel = true;  // its result would be of the old sketch
  sketch_ = std::move(loaded);
  params_ = params;
  undo_.clear();
  redo_.clear();
  result_.reset();
  ++result_revision_;
  const double diagonal = sketch_.bounding_box().diagonal();
  if (diagonal > 0.0 && std::isfinite(diagonal)) reference_size_ = diagonal;
  file_ = file;
  changed();
  saved_revision_ = revision_;
}

void SketchSession::save(const std::filesystem::path& file) {
  write_sketch(sketch_, file);
  file_ = file;
  saved_revision_ = revision_;
}

void SketchSession::open_proxy(const std::filesystem::path& file) {
  proxy_ = std::make_shared<const TriMesh>(read_mesh(file));
}

void SketchSession::save_surface(const std::filesystem::path& file) const {
  if (!result_) throw Error::usage("there is no surface to save yet; surface the sketch first");
  MeshAttributes attributes;
  attributes.labels = result_->labels;
  attributes.sharp = result_->sharp;
  write_mesh(result_->mesh, file, attributes);
}

void SketchSession::set_param(const std::string& name, double value) {
  Params updated = params_;
  updated.apply({{name, value}});
  params_ = updated;
  sketch_.params[name] = value;
}

// ----------------------------------------------------------------------------------------------
// Autosave.

void SketchSession::schedule_autosave() {
  if (autosave_path_.empty()) return;
  {
    std::lock_guard<std::mutex> lock(autosave_mutex_);
    autosave_pending_.emplace(revision_, sketch_);  // a newer snapshot replaces an unwritten one
  }
  autosave_cv_.notify_all();
}

void SketchSession::autosave_loop() {
  std::unique_lock<std::mutex> lock(autosave_mutex_);
  for (;;) {
    autosave_cv_.wait(lock, [&] { return autosave_stop_ || autosave_pending_.has_value(); });
    if (!autosave_pending_) return;  // stopping, nothing left to write
    auto [revision, snapshot] = std::move(*autosave_pending_);
    autosave_pending_.reset();
    lock.unlock();
    std::string error;
    try {
      write_sketch(snapshot, autosave_path_);  // temporary file + rename: never a partial file
    } catch (const std::exception& e) {
      error = e.what();
    }
    lock.lock();
    autosave_error_ = error;
    if (error.empty()) autosaved_ = revision;
    attempted_ = revision;
    autosave_cv_.notify_all();
  }
}

std::string SketchSession::autosave_error() const {
  std::lock_guard<std::mutex> lock(autosave_mutex_);
  return autosave_error_;
}

void SketchSession::flush_autosave() {
  if (autosave_path_.empty()) return;
  std::unique_lock<std::mutex> lock(autosave_mutex_);
  const std::uint64_t wanted = revision_;
  autosave_cv_.wait(lock, [&] { return attempted_ >= wanted; });
}

// ----------------------------------------------------------------------------------------------
// Surfacing.

bool SketchSession::surface() {
  if (job_ && !job_->finished) {
    last_status_.message = "surfacing is still running";
    return false;
  }
  poll_surface();
  if (worker_.joinable()) worker_.join();
  if (live_active_) finish_stroke();
  auto job = std::make_shared<Job>();
  job_ = job;
  job_taken_ = false;
  worker_ = std::thread([job, sketch = sketch_, params = params_, proxy = proxy_,
                         lower = background_priority_] {
#ifdef __linux__
    // The nice value is per thread on Linux and inherited by the threads this one starts (the
    // Surfacer's workers), so the whole job yields to the frame loop.
    if (lower) setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), 10);
#else
    (void)lower;
#endif
    auto progress = [job](std::string_view stage, double fraction) {
      std::lock_guard<std::mutex> lock(job->mutex);
      job->stage = std::string(stage);
      job->fraction = fraction;
      return !job->cancel.load();
    };
    std::unique_ptr<SurfaceResult> result;
    std::string error;
    bool cancelled = false;
    try {
      result = std::make_unique<SurfaceResult>(Surfacer(params, progress).run(sketch, proxy.get()));
    } catch (const Error& e) {
      if (e.kind() == ErrorKind::Cancelled)
        cancelled = true;
      else
        error = e.what();
    } catch (const std::bad_alloc&) {
      error = "out of memory";
    } catch (const std::exception& e) {
      error = e.what();
    }
    std::lock_guard<std::mutex> lock(job->mutex);
    job->result = std::move(result);
    job->error = std::move(error);
    job->cancelled = cancelled;
    job->end = Clock::now();
    job->finished = true;
  });
  return true;
}

void SketchSession::cancel_surface() {
  if (job_ && !job_->finished) job_->cancel = true;
}

SurfaceStatus SketchSession::surface_status() const {
  if (!job_ || job_taken_) return last_status_;
  SurfaceStatus s;
  std::lock_guard<std::mutex> lock(job_->mutex);
  s.stage = job_->stage;
  s.fraction = job_->fraction;
  if (!job_->finished) {
    s.state = job_->cancel ? JobState::Cancelling : JobState::Running;
    s.elapsed_s = seconds_between(job_->start, Clock::now());
  } else {
    s.state = job_->cancel || job_->cancelled ? JobState::Cancelled
              : job_->result                   ? JobState::Done
                                               : JobState::Failed;
    s.message = job_->error;
    s.elapsed_s = seconds_between(job_->start, job_->end);
  }
  return s;
}

bool SketchSession::poll_surface() {
  if (!job_ || job_taken_ || !job_->finished) return false;
  if (worker_.joinable()) worker_.join();
  job_taken_ = true;
  std::lock_guard<std::mutex> lock(job_->mutex);
  last_status_ = SurfaceStatus{};
  last_status_.stage = job_->stage;
  last_status_.fraction = job_->fraction;
  last_status_.elapsed_s = seconds_between(job_->start, job_->end);
  if (job_->cancel || job_->cancelled) {
    last_status_.state = JobState::Cancelled;
    last_status_.message = "surfacing cancelled";
    return false;
  }
  if (!job_->result) {
    last_status_.state = JobState::Failed;
    last_status_.message = job_->error;
    return false;
  }
  result_ = std::move(job_->result);
  ++result_revision_;
  last_status_.state = JobState::Done;
  std::ostringstream summary;
  summary.precision(3);
  summary << result_->mesh.n_faces() << " triangles, " << result_->segmentation.models.size()
          << " regions in " << last_status_.elapsed_s << " s";
  last_status_.message = summary.str();
  return true;
}

void SketchSession::set_result(SurfaceResult result) {
  result_ = std::make_unique<SurfaceResult>(std::move(result));
  ++result_revision_;
}

bool SketchSession::wait_surface(double timeout_s) {
  const auto until = Clock::now() + std::chrono::duration<double>(timeout_s);
  while (job_ && !job_taken_ && !job_->finished && Clock::now() < until)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  const bool ended = !job_ || job_taken_ || job_->finished;
  poll_surface();
  return ended;
}

}  // namespace sketchsurf::session
