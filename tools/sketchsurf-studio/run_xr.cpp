#include <chrono>
#include <thread>

#include "engine/input/xr_controller.h"
#include "engine/render/renderer.h"
#include "engine/vk/xr_session.h"
#include "tools/sketchsurf-studio/run.h"

namespace sketchsurf::studio {

namespace {

/// The eye's camera at the frame's predicted pose. The near plane is 1 cm (a controller held
/// close to the eyes stays visible); the far plane takes in everything drawn.
render::Camera eye_camera(const XrView& view, const BoundingBox& drawn) {
  const Eigen::Vector3d eye(view.pose.position.x, view.pose.position.y, view.pose.position.z);
  const Eigen::Quaterniond orientation = input::to_quaternion(view.pose.orientation);
  double far_plane = 100.0;
  if (!drawn.empty())
    far_plane = std::max(far_plane, (0.5 * (drawn.min + drawn.max) - eye).norm() + drawn.diagonal());
  return render::eye_camera(eye, orientation,
                            {view.fov.angleLeft, view.fov.angleRight, view.fov.angleUp, view.fov.angleDown},
                            0.01, far_plane);
}

std::unique_ptr<vk::XrSystem> make_system(const Log& log) {
  vk::XrSystemOptions xo;
  xo.application = "sketchsurf-studio";
  xo.log = [&log](const std::string& line) { log.info(line); };
  return std::make_unique<vk::XrSystem>(xo);
}

}  // namespace

/// The OpenXR system, the context made through it, the session, the renderer for its eyes and
/// the controller, in that order of construction.
struct HeadsetStudio::Parts {
  Parts(const StudioOptions& options, const Log& log)
      : system(make_system(log)), context(system->create_context(context_options(options, log))) {}
  std::unique_ptr<vk::XrSystem> system;
  std::unique_ptr<vk::Context> context;
  std::unique_ptr<vk::HeadsetSession> headset;
  std::unique_ptr<render::Renderer> renderer;
  std::unique_ptr<input::XrController> controller;
};

HeadsetStudio::HeadsetStudio(const StudioOptions& options, const Log& log)
    : parts_(std::make_unique<Parts>(options, log)), log_(log) {
  Parts& p = *parts_;
  studio_ = std::make_unique<Studio>(options, *p.context, log);
  p.headset =
      std::make_unique<vk::HeadsetSession>(*p.system, *p.context, sample_count(options.msaa, *p.context),
                                           [&log](const std::string& line) { log.info(line); });
  p.renderer = std::make_unique<render::Renderer>(*p.context, p.headset->render_pass(), p.headset->samples());
  p.controller = std::make_unique<input::XrController>(p.system->instance(), p.headset->session());
  studio_->set_controller(p.controller.get());
}

HeadsetStudio::~HeadsetStudio() {
  studio_->set_controller(nullptr);
  parts_->controller.reset();
  parts_->renderer.reset();
  parts_->headset.reset();
  studio_.reset();  // its scenes live on the context
  parts_.reset();
}

const vk::Context& HeadsetStudio::context() const { return *parts_->context; }
std::size_t HeadsetStudio::haptic_ticks() const { return parts_->controller->haptic_ticks(); }
void HeadsetStudio::request_exit() { parts_->headset->request_exit(); }

bool HeadsetStudio::step() {
  Parts& p = *parts_;
  vk::HeadsetSession& headset = *p.headset;
  if (!headset.poll_events()) return false;
  if (!headset.running()) {  // waiting for the runtime (the headset put on, the session READY)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    return true;
  }
  const auto start = std::chrono::steady_clock::now();
  const vk::HeadsetFrame frame = headset.begin_frame();
  if (first_ == 0) first_ = frame.display_time;
  const double now = double(frame.display_time - first_) * 1e-9;
  p.controller->sync(headset.space(), frame.display_time, now);
  if (profile_.empty() && !(profile_ = p.controller->profile()).empty()) log_.info("controller: " + profile_);
  Studio& studio = *studio_;
  studio.input(now);
  studio.update();
  const BoundingBox drawn = studio.view().bounds();
  headset.end_frame(frame, studio.view_options().background, [&](VkCommandBuffer cmd, std::size_t eye) {
    const VkExtent2D extent = headset.eye_extent(eye);
    studio.record(cmd, *p.renderer, eye_camera(frame.views[eye], drawn),
                  double(extent.width) / double(extent.height), nullptr);
  });
  ++frames_;
  studio.frame_finished(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return true;
}

int run_xr(const StudioOptions& options, const Log& log) {
  std::unique_ptr<HeadsetStudio> headset;
  try {
    headset = std::make_unique<HeadsetStudio>(options, log);
  } catch (const vk::XrUnavailable& e) {
    log.info(std::string(e.what()) + "; starting the desktop studio");
    return options.headless ? run_headless(options, log) : run_window(options, log);
  }
  Studio& studio = headset->studio();
  catch_stop_signals();
  while (headset->step())
    if (stop_requested() || (options.frames && studio.done(headset->frames()))) headset->request_exit();
  studio.finish();
  log.info("headset: " + summary(studio.stats()) + ", " + std::to_string(headset->haptic_ticks()) +
           " haptic ticks");
  if (headset->context().validation_enabled())
    log.info("validation: " + std::to_string(headset->context().validation_messages().size()) + " messages");
  return 0;
}

}  // namespace sketchsurf::studio
