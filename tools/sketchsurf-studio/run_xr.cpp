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

}  // namespace

int run_xr(const StudioOptions& options, const Log& log) {
  std::unique_ptr<vk::XrSystem> system;
  try {
    vk::XrSystemOptions xo;
    xo.application = "sketchsurf-studio";
    xo.log = [&log](const std::string& line) { log.info(line); };
    system = std::make_unique<vk::XrSystem>(xo);
  } catch (const vk::XrUnavailable& e) {
    log.info(std::string(e.what()) + "; starting the desktop studio");
    return options.headless ? run_headless(options, log) : run_window(options, log);
  }
  const std::unique_ptr<vk::Context> context = system->create_context(context_options(options, log));
  Studio studio(options, *context, log);
  vk::HeadsetSession headset(*system, *context, sample_count(options.msaa, *context),
                             [&log](const std::string& line) { log.info(line); });
  const render::Renderer renderer(*context, headset.render_pass(), headset.samples());
  input::XrController controller(system->instance(), headset.session());
  studio.set_controller(&controller);

  catch_stop_signals();
  std::size_t frames = 0;
  XrTime first = 0;
  std::string profile;
  while (headset.poll_events()) {
    if (stop_requested() || (options.frames && studio.done(frames))) headset.request_exit();
    if (!headset.running()) {  // waiting for the runtime (the headset put on, the session READY)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
      continue;
    }
    const auto start = std::chrono::steady_clock::now();
    const vk::HeadsetFrame frame = headset.begin_frame();
    if (first == 0) first = frame.display_time;
    const double now = double(frame.display_time - first) * 1e-9;
    controller.sync(headset.space(), frame.display_time, now);
    if (profile.empty() && !(profile = controller.profile()).empty()) log.info("controller: " + profile);
    studio.input(now);
    studio.update();
    const BoundingBox drawn = studio.view().bounds();
    headset.end_frame(frame, studio.view_options().background, [&](VkCommandBuffer cmd, std::size_t eye) {
      const VkExtent2D extent = headset.eye_extent(eye);
      studio.record(cmd, renderer, eye_camera(frame.views[eye], drawn),
                    double(extent.width) / double(extent.height), nullptr);
    });
    ++frames;
    studio.frame_finished(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  studio.finish();
  log.info("headset: " + summary(studio.stats()) + ", " + std::to_string(controller.haptic_ticks()) +
           " haptic ticks");
  if (context->validation_enabled())
    log.info("validation: " + std::to_string(context->validation_messages().size()) + " messages");
  return 0;
}

}  // namespace sketchsurf::studio
