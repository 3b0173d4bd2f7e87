#include <chrono>
#include <cstdio>
#include <thread>

#include "engine/vk/offscreen.h"
#include "tools/sketchsurf-studio/run.h"
#include "tools/sketchsurf-studio/ui.h"

namespace sketchsurf::studio {

VkSampleCountFlagBits sample_count(int msaa, const vk::Context& context) {
  if (msaa == 0) msaa = context.software() ? 1 : 4;
  return msaa >= 4 ? VK_SAMPLE_COUNT_4_BIT : msaa >= 2 ? VK_SAMPLE_COUNT_2_BIT : VK_SAMPLE_COUNT_1_BIT;
}

vk::ContextOptions context_options(const StudioOptions& options, const Log& log) {
  vk::ContextOptions co;
  co.device = options.device;
  co.validation = options.validation ? vk::Validation::On : vk::Validation::Off;
  co.log = [&log](const std::string& line) { log.info(line); };
  return co;
}

std::string summary(const FrameStats& s) {
  char text[160];
  std::snprintf(text, sizeof text, "%zu frames: median %.2f ms, p95 %.2f ms, max %.2f ms", s.frames,
                s.median_ms, s.p95_ms, s.max_ms);
  return text;
}

/// The offscreen target, the renderer and the panel, in that order of construction.
struct HeadlessStudio::Parts {
  Parts(const vk::Context& context, const StudioOptions& o)
      : target(context, {std::uint32_t(o.width), std::uint32_t(o.height)}, sample_count(o.msaa, context)),
        renderer(context, target.render_pass(), target.samples()),
        ui(context, target.render_pass(), target.samples(), 2, nullptr) {}
  vk::OffscreenTarget target;
  render::Renderer renderer;
  ImGuiLayer ui;
  PanelState panel;
};

HeadlessStudio::HeadlessStudio(const StudioOptions& options, const Log& log)
    : context_(std::make_unique<vk::Context>(context_options(options, log))), log_(log) {
  studio_ = std::make_unique<Studio>(options, *context_, log);
  parts_ = std::make_unique<Parts>(*context_, options);
}

HeadlessStudio::~HeadlessStudio() {
  parts_.reset();
  studio_.reset();
}

VkSampleCountFlagBits HeadlessStudio::samples() const { return parts_->target.samples(); }

double HeadlessStudio::frame(double now) {
  const auto start = std::chrono::steady_clock::now();
  Studio& studio = *studio_;
  const int w = studio.options().width, h = studio.options().height;
  studio.input(now);
  if (previous_ < 0.0) {  // the first frame: lay the panel out once
    parts_->ui.new_frame(w, h, 1.0 / 60.0);
    draw_panel(studio, parts_->panel, log_);
    parts_->ui.discard();
  }
  parts_->ui.new_frame(w, h, now - previous_);
  previous_ = now;
  draw_panel(studio, parts_->panel, log_);
  studio.update();
  context_->submit_and_wait([&](VkCommandBuffer cmd) {
    parts_->target.begin(cmd, studio.view_options().background);
    studio.record(cmd, parts_->renderer, w, h, nullptr);
    parts_->ui.render(cmd);
    parts_->target.end_and_copy(cmd);
  });
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  studio.frame_finished(seconds);
  return seconds;
}

render::RgbaImage HeadlessStudio::picture() const {
  return {studio_->options().width, studio_->options().height, parts_->target.read_pixels()};
}

int run_headless(const StudioOptions& options, const Log& log) {
  HeadlessStudio headless(options, log);
  Studio& studio = headless.studio();
  for (std::size_t frame = 0;; ++frame) {
    headless.frame(studio.simulated_time(frame));
    if (studio.done(frame + 1)) break;
    // Only waiting for --surface now: leave the cores to the surfacing.
    if (frame + 1 >= studio.frames_wanted() && !studio.replaying())
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  if (!options.screenshot.empty()) {
    render::write_png(headless.picture(), options.screenshot);
    log.info("wrote " + options.screenshot.string());
  }
  studio.finish();
  log.info("headless " + std::to_string(options.width) + "x" + std::to_string(options.height) +
           ", MSAA " + std::to_string(int(headless.samples())) + " on '" +
           headless.context().device_info().name + "': " + summary(studio.stats()));
  if (headless.context().validation_enabled())
    log.info("validation: " + std::to_string(headless.context().validation_messages().size()) + " messages");
  return 0;
}

}  // namespace sketchsurf::studio
