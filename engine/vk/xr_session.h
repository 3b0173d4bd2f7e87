#pragma once
// The headset's session: the OpenXR session on the runtime's Vulkan device, its reference space
// (stage when the runtime has one, else local), the session's life cycle (begun when the runtime
// says READY, ended when it says STOPPING) and the stereo frame: one swapchain per eye whose
// images are render targets of the same kind as the offscreen target and the window's (render
// pass of render_pass.h: the same pipelines draw into all three).
//
// Colour: the runtime's swapchains are sRGB where it offers one, so that the compositor shows the
// colours the renderer writes; they are drawn through a UNORM view (the renderer's colours are
// already sRGB-encoded, as they are for the PNG and the window).

#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "engine/vk/xr_system.h"

namespace sketchsurf::vk {

/// One frame of the headset: when it will be shown and where the eyes will be.
struct HeadsetFrame {
  XrTime display_time = 0;        ///< predicted display time
  bool render = false;            ///< the runtime wants the eyes rendered
  std::array<XrView, 2> views{};  ///< left, right: pose in the reference space and fov
  bool views_valid = false;       ///< the eye poses are known
};

class HeadsetSession {
 public:
  /// Creates the session on `context` (made by system.create_context()), the reference space and
  /// the swapchains (each eye at its recommended size, `samples` as a wish). Throws XrError.
  HeadsetSession(const XrSystem& system, const Context& context, VkSampleCountFlagBits samples,
                 std::function<void(const std::string&)> log = {});
  ~HeadsetSession();
  HeadsetSession(const HeadsetSession&) = delete;
  HeadsetSession& operator=(const HeadsetSession&) = delete;

  XrSession session() const { return session_; }
  XrSpace space() const { return space_; }
  /// "stage" or "local".
  const char* space_name() const;
  VkRenderPass render_pass() const { return render_pass_.get(); }
  VkSampleCountFlagBits samples() const { return samples_; }
  VkExtent2D eye_extent(std::size_t eye) const;

  /// Handles the runtime's pending events: begins the session when it is READY, ends it when it
  /// is STOPPING. False once the session is over (EXITING, LOSS_PENDING, or the instance lost).
  bool poll_events();
  /// Between xrBeginSession and xrEndSession: frames are due.
  bool running() const { return running_; }
  XrSessionState state() const { return state_; }
  /// Asks the runtime to end the session (it goes through STOPPING; poll_events() ends it).
  void request_exit();

  /// xrWaitFrame, xrBeginFrame and xrLocateViews. Only while running().
  HeadsetFrame begin_frame();
  /// Renders each eye when the frame asks for it: acquires its image, begins the render pass
  /// cleared to `background`, calls `record(cmd, eye)` to record the draws, ends the pass, submits
  /// and waits, releases the image; then ends the frame with a projection layer of both eyes.
  void end_frame(const HeadsetFrame& frame, const std::array<float, 4>& background,
                 const std::function<void(VkCommandBuffer, std::size_t)>& record);

 private:
  struct Eye;
  void log(const std::string& line) const;

  const XrSystem* system_;
  const Context* context_;
  std::function<void(const std::string&)> log_;
  XrSession session_ = XR_NULL_HANDLE;
  XrSpace space_ = XR_NULL_HANDLE;
  XrReferenceSpaceType space_type_ = XR_REFERENCE_SPACE_TYPE_LOCAL;
  XrSessionState state_ = XR_SESSION_STATE_UNKNOWN;
  bool running_ = false, exit_requested_ = false;
  VkSampleCountFlagBits samples_ = VK_SAMPLE_COUNT_1_BIT;
  VkFormat view_format_ = VK_FORMAT_UNDEFINED;
  UniqueRenderPass render_pass_;
  std::vector<std::unique_ptr<Eye>> eyes_;
};

}  // namespace sketchsurf::vk
