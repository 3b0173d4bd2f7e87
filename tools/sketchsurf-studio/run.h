#pragma once
// The studio's three front ends (offscreen, window, headset): one renderer, three targets.

#include <openxr/openxr.h>

#include <functional>
#include <string>

#include "engine/render/image.h"
#include "engine/vk/context.h"

#include "tools/sketchsurf-studio/studio.h"

namespace sketchsurf::studio {

/// The studio on an offscreen target: what --headless runs, and what studio_bench measures.
class HeadlessStudio {
 public:
  /// Throws Error (the studio's), VulkanError.
  HeadlessStudio(const StudioOptions& options, const Log& log);
  ~HeadlessStudio();
  HeadlessStudio(const HeadlessStudio&) = delete;
  HeadlessStudio& operator=(const HeadlessStudio&) = delete;

  Studio& studio() { return *studio_; }
  const vk::Context& context() const { return *context_; }
  VkSampleCountFlagBits samples() const;
  /// One frame at time `now` (seconds): input, panel, update, draw, wait for it. Returns the
  /// frame's wall time in seconds (also given to Studio::frame_finished()).
  double frame(double now);
  /// The last frame's picture.
  render::RgbaImage picture() const;

 private:
  struct Parts;
  std::unique_ptr<vk::Context> context_;
  std::unique_ptr<Studio> studio_;
  std::unique_ptr<Parts> parts_;
  const Log& log_;
  double previous_ = -1.0 / 60.0;
};

/// --headless: HeadlessStudio on a simulated clock (a replay spread over --frames frames, else
/// 60 frames a second) until Studio::done(). Returns the exit code.
int run_headless(const StudioOptions& options, const Log& log);

/// A GLFW window with a Vulkan swapchain. Throws Error (Processing) with a message that suggests
/// --headless or Xvfb when there is no display. Returns the exit code.
int run_window(const StudioOptions& options, const Log& log);

/// The studio in a headset through OpenXR (--xr): the runtime's Vulkan device, one swapchain per
/// eye drawn by the same renderer as the other targets, the controller's samples in place of the
/// mouse's; no panel. What run_xr() runs, and what studio_bench measures.
class HeadsetStudio {
 public:
  /// Throws vk::XrUnavailable (no runtime or no headset: nothing else was started), Error.
  HeadsetStudio(const StudioOptions& options, const Log& log);
  ~HeadsetStudio();
  HeadsetStudio(const HeadsetStudio&) = delete;
  HeadsetStudio& operator=(const HeadsetStudio&) = delete;

  Studio& studio() { return *studio_; }
  const vk::Context& context() const;
  /// Handles the runtime's events and, while the session runs, renders one frame (wait, input,
  /// update, both eyes, end; its wall time goes to Studio::frame_finished()). False once the
  /// session is over.
  bool step();
  /// Asks the runtime to end the session; step() returns false once it has.
  void request_exit();
  /// Frames rendered so far.
  std::size_t frames() const { return frames_; }
  std::size_t haptic_ticks() const;

 private:
  struct Parts;
  std::unique_ptr<Parts> parts_;
  std::unique_ptr<Studio> studio_;
  const Log& log_;
  std::size_t frames_ = 0;
  XrTime first_ = 0;
  std::string profile_;
};

/// --xr: HeadsetStudio until the session ends. Without a runtime or a headset, says what is missing in one line and runs the desktop studio instead
/// (the window, or --headless). Ends when the runtime stops the session, on SIGINT/SIGTERM, or
/// after --frames. Returns the exit code.
int run_xr(const StudioOptions& options, const Log& log);

/// SIGINT and SIGTERM end the front end's loop as a normal exit would (with --save, --record).
void catch_stop_signals();
/// True once SIGINT or SIGTERM came.
bool stop_requested();

/// The message for a machine without a display.
std::string no_display_message(const std::string& detail);

/// --msaa as Vulkan's sample count: 1, 2 or 4; 0 chooses for the device: 4 on a GPU, 1 on the
/// CPU (lavapipe's 4x MSAA costs it about 3x the frame time with the studio's scenes).
VkSampleCountFlagBits sample_count(int msaa, const vk::Context& context);

/// "N frames: median X ms, p95 Y ms, max Z ms".
std::string summary(const FrameStats& stats);

/// The Vulkan context options of the studio (device, validation, the log).
vk::ContextOptions context_options(const StudioOptions& options, const Log& log);

}  // namespace sketchsurf::studio
