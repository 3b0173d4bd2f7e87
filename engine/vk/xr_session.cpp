#include "engine/vk/xr_session.h"

#include <algorithm>

#include "engine/vk/check.h"
#include "engine/vk/image.h"
#include "engine/vk/render_pass.h"
#include "engine/vk/xr_check.h"

namespace sketchsurf::vk {

namespace {

constexpr XrViewConfigurationType kStereo = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;

/// A swapchain format and the format of the views drawn through.
struct FormatChoice {
  VkFormat image, view;
};

/// sRGB images drawn through a UNORM view first (see the header), then plain UNORM images.
FormatChoice choose_format(XrSession session) {
  std::uint32_t count = 0;
  XR_CHECK(xrEnumerateSwapchainFormats(session, 0, &count, nullptr));
  std::vector<std::int64_t> formats(count);
  XR_CHECK(xrEnumerateSwapchainFormats(session, count, &count, formats.data()));
  for (const FormatChoice c : {FormatChoice{VK_FORMAT_R8G8B8A8_SRGB, VK_FORMAT_R8G8B8A8_UNORM},
                               FormatChoice{VK_FORMAT_B8G8R8A8_SRGB, VK_FORMAT_B8G8R8A8_UNORM},
                               FormatChoice{VK_FORMAT_R8G8B8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM},
                               FormatChoice{VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_B8G8R8A8_UNORM}})
    if (std::find(formats.begin(), formats.end(), std::int64_t(c.image)) != formats.end()) return c;
  throw Error::processing("the OpenXR runtime offers no 8-bit RGBA swapchain format");
}

}  // namespace

/// One eye's swapchain with a framebuffer per image.
struct HeadsetSession::Eye {
  XrSwapchain swapchain = XR_NULL_HANDLE;
  VkExtent2D extent{};
  std::vector<XrSwapchainImageVulkan2KHR> images;
  std::vector<UniqueImageView> views;
  Image color_msaa, depth;
  std::vector<UniqueFramebuffer> framebuffers;
  Eye() = default;
  Eye(const Eye&) = delete;
  Eye& operator=(const Eye&) = delete;
  ~Eye() {
    framebuffers.clear();
    views.clear();
    if (swapchain != XR_NULL_HANDLE) xrDestroySwapchain(swapchain);
  }
};

HeadsetSession::HeadsetSession(const XrSystem& system, const Context& context, VkSampleCountFlagBits samples,
                               std::function<void(const std::string&)> log)
    : system_(&system),
      context_(&context),
      log_(std::move(log)),
      samples_(context.supported_samples(samples)) {
  XrGraphicsBindingVulkan2KHR binding{XR_TYPE_GRAPHICS_BINDING_VULKAN2_KHR};
  binding.instance = context.instance();
  binding.physicalDevice = context.physical_device();
  binding.device = context.device();
  binding.queueFamilyIndex = context.queue_family();
  binding.queueIndex = 0;
  XrSessionCreateInfo info{XR_TYPE_SESSION_CREATE_INFO};
  info.next = &binding;
  info.systemId = system.system();
  XR_CHECK(xrCreateSession(system.instance(), &info, &session_));
  try {
    std::uint32_t count = 0;
    XR_CHECK(xrEnumerateReferenceSpaces(session_, 0, &count, nullptr));
    std::vector<XrReferenceSpaceType> spaces(count);
    XR_CHECK(xrEnumerateReferenceSpaces(session_, count, &count, spaces.data()));
    if (std::find(spaces.begin(), spaces.end(), XR_REFERENCE_SPACE_TYPE_STAGE) != spaces.end())
      space_type_ = XR_REFERENCE_SPACE_TYPE_STAGE;
    XrReferenceSpaceCreateInfo space{XR_TYPE_REFERENCE_SPACE_CREATE_INFO};
    space.referenceSpaceType = space_type_;
    space.poseInReferenceSpace.orientation.w = 1.0f;
    XR_CHECK(xrCreateReferenceSpace(session_, &space, &space_));

    const FormatChoice format = choose_format(session_);
    view_format_ = format.view;
    const VkFormat depth_format = choose_depth_format(context);
    VkSubpassDependency dep{};
    dep.srcSubpass = VK_SUBPASS_EXTERNAL;
    dep.dstSubpass = 0;
    dep.srcStageMask =
        VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    dep.dstStageMask =
        VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT;
    dep.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    dep.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    // OpenXR hands swapchain images back to the runtime in COLOR_ATTACHMENT_OPTIMAL.
    render_pass_ = create_render_pass(context, view_format_, depth_format, samples_,
                                      VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, {dep});
    const bool msaa = samples_ != VK_SAMPLE_COUNT_1_BIT;
    for (const XrViewConfigurationView& v : system.eye_views()) {
      auto eye = std::make_unique<Eye>();
      eye->extent = {v.recommendedImageRectWidth, v.recommendedImageRectHeight};
      XrSwapchainCreateInfo sc{XR_TYPE_SWAPCHAIN_CREATE_INFO};
      sc.usageFlags = XR_SWAPCHAIN_USAGE_COLOR_ATTACHMENT_BIT |
                      (format.image != format.view ? XR_SWAPCHAIN_USAGE_MUTABLE_FORMAT_BIT : 0);
      sc.format = format.image;
      sc.sampleCount = 1;
      sc.width = eye->extent.width;
      sc.height = eye->extent.height;
      sc.faceCount = 1;
      sc.arraySize = 1;
      sc.mipCount = 1;
      XR_CHECK(xrCreateSwapchain(session_, &sc, &eye->swapchain));
      std::uint32_t n = 0;
      XR_CHECK(xrEnumerateSwapchainImages(eye->swapchain, 0, &n, nullptr));
      eye->images.assign(n, {XR_TYPE_SWAPCHAIN_IMAGE_VULKAN2_KHR});
      XR_CHECK(xrEnumerateSwapchainImages(eye->swapchain, n, &n,
                                          reinterpret_cast<XrSwapchainImageBaseHeader*>(eye->images.data())));
      if (msaa)
        eye->color_msaa =
            Image(context,
                  {eye->extent, view_format_,
                   VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT, samples_,
                   VK_IMAGE_TILING_OPTIMAL, VK_IMAGE_ASPECT_COLOR_BIT, false},
                  "headset colour (msaa)");
      eye->depth =
          Image(context,
                {eye->extent, depth_format,
                 VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT,
                 samples_, VK_IMAGE_TILING_OPTIMAL, VK_IMAGE_ASPECT_DEPTH_BIT, false},
                "headset depth");
      for (const auto& image : eye->images) {
        VkImageViewCreateInfo view_info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
        view_info.image = image.image;
        view_info.viewType = VK_IMAGE_VIEW_TYPE_2D;
        view_info.format = view_format_;
        view_info.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        VkImageView view = VK_NULL_HANDLE;
        VK_CHECK(vkCreateImageView(context.device(), &view_info, nullptr, &view));
        eye->views.emplace_back(context.device(), view);
        std::vector<VkImageView> attachments;
        attachments.push_back(msaa ? eye->color_msaa.view() : view);
        attachments.push_back(eye->depth.view());
        if (msaa) attachments.push_back(view);
        eye->framebuffers.push_back(
            create_framebuffer(context, render_pass_.get(), eye->extent, attachments));
      }
      eyes_.push_back(std::move(eye));
    }
  } catch (...) {
    eyes_.clear();
    if (space_ != XR_NULL_HANDLE) xrDestroySpace(space_);
    xrDestroySession(session_);
    throw;
  }
  this->log(std::string("headset session: ") + space_name() + " space, " +
            std::to_string(eyes_[0]->extent.width) + "x" + std::to_string(eyes_[0]->extent.height) +
            " per eye, " + std::to_string(eyes_[0]->images.size()) + " images, MSAA " +
            std::to_string(int(samples_)));
}

HeadsetSession::~HeadsetSession() {
  vkDeviceWaitIdle(context_->device());
  eyes_.clear();
  if (space_ != XR_NULL_HANDLE) xrDestroySpace(space_);
  if (session_ != XR_NULL_HANDLE) xrDestroySession(session_);
}

const char* HeadsetSession::space_name() const {
  return space_type_ == XR_REFERENCE_SPACE_TYPE_STAGE ? "stage" : "local";
}

VkExtent2D HeadsetSession::eye_extent(std::size_t eye) const { return eyes_.at(eye)->extent; }

void HeadsetSession::log(const std::string& line) const {
  if (log_) log_(line);
}

bool HeadsetSession::poll_events() {
  if (exit_requested_ && !running_) return false;
  for (;;) {
    XrEventDataBuffer event{XR_TYPE_EVENT_DATA_BUFFER};
    const XrResult polled = xrPollEvent(system_->instance(), &event);
    XR_CHECK(polled);
    if (polled == XR_EVENT_UNAVAILABLE) return true;
    if (event.type == XR_TYPE_EVENT_DATA_INSTANCE_LOSS_PENDING) {
      log("the OpenXR runtime is going away");
      return false;
    }
    if (event.type != XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED) continue;
    const auto& changed = reinterpret_cast<const XrEventDataSessionStateChanged&>(event);
    state_ = changed.state;
    log("headset session " + xr_state_name(state_));
    switch (state_) {
      case XR_SESSION_STATE_READY: {
        XrSessionBeginInfo begin{XR_TYPE_SESSION_BEGIN_INFO};
        begin.primaryViewConfigurationType = kStereo;
        XR_CHECK(xrBeginSession(session_, &begin));
        running_ = true;
        break;
      }
      case XR_SESSION_STATE_STOPPING:
        XR_CHECK(xrEndSession(session_));
        running_ = false;
        if (exit_requested_) return false;
        break;
      case XR_SESSION_STATE_EXITING:
      case XR_SESSION_STATE_LOSS_PENDING:
        return false;
      default:
        break;
    }
  }
}

void HeadsetSession::request_exit() {
  if (exit_requested_) return;
  exit_requested_ = true;
  if (running_) XR_CHECK(xrRequestExitSession(session_));
}

HeadsetFrame HeadsetSession::begin_frame() {
  XrFrameWaitInfo wait{XR_TYPE_FRAME_WAIT_INFO};
  XrFrameState state{XR_TYPE_FRAME_STATE};
  XR_CHECK(xrWaitFrame(session_, &wait, &state));
  XrFrameBeginInfo begin{XR_TYPE_FRAME_BEGIN_INFO};
  XR_CHECK(xrBeginFrame(session_, &begin));
  HeadsetFrame frame;
  frame.display_time = state.predictedDisplayTime;
  frame.render = state.shouldRender == XR_TRUE;
  XrViewLocateInfo locate{XR_TYPE_VIEW_LOCATE_INFO};
  locate.viewConfigurationType = kStereo;
  locate.displayTime = state.predictedDisplayTime;
  locate.space = space_;
  XrViewState view_state{XR_TYPE_VIEW_STATE};
  for (auto& v : frame.views) v = {XR_TYPE_VIEW};
  std::uint32_t count = 0;
  XR_CHECK(xrLocateViews(session_, &locate, &view_state, 2, &count, frame.views.data()));
  const XrViewStateFlags needed = XR_VIEW_STATE_POSITION_VALID_BIT | XR_VIEW_STATE_ORIENTATION_VALID_BIT;
  frame.views_valid = count == 2 && (view_state.viewStateFlags & needed) == needed;
  return frame;
}

void HeadsetSession::end_frame(const HeadsetFrame& frame, const std::array<float, 4>& background,
                               const std::function<void(VkCommandBuffer, std::size_t)>& record) {
  std::array<XrCompositionLayerProjectionView, 2> projected{};
  const bool draw = frame.render && frame.views_valid;
  if (draw) {
    for (std::size_t e = 0; e < eyes_.size(); ++e) {
      Eye& eye = *eyes_[e];
      std::uint32_t index = 0;
      XrSwapchainImageAcquireInfo acquire{XR_TYPE_SWAPCHAIN_IMAGE_ACQUIRE_INFO};
      XR_CHECK(xrAcquireSwapchainImage(eye.swapchain, &acquire, &index));
      XrSwapchainImageWaitInfo wait{XR_TYPE_SWAPCHAIN_IMAGE_WAIT_INFO};
      wait.timeout = XR_INFINITE_DURATION;
      XR_CHECK(xrWaitSwapchainImage(eye.swapchain, &wait));
      context_->submit_and_wait([&](VkCommandBuffer cmd) {
        begin_render_pass(cmd, render_pass_.get(), eye.framebuffers.at(index).get(), eye.extent, samples_,
                          background);
        record(cmd, e);
        vkCmdEndRenderPass(cmd);
      });
      XrSwapchainImageReleaseInfo release{XR_TYPE_SWAPCHAIN_IMAGE_RELEASE_INFO};
      XR_CHECK(xrReleaseSwapchainImage(eye.swapchain, &release));
      projected[e] = {XR_TYPE_COMPOSITION_LAYER_PROJECTION_VIEW};
      projected[e].pose = frame.views[e].pose;
      projected[e].fov = frame.views[e].fov;
      projected[e].subImage.swapchain = eye.swapchain;
      projected[e].subImage.imageRect = {{0, 0},
                                         {std::int32_t(eye.extent.width), std::int32_t(eye.extent.height)}};
    }
  }
  XrCompositionLayerProjection layer{XR_TYPE_COMPOSITION_LAYER_PROJECTION};
  layer.space = space_;
  layer.viewCount = 2;
  layer.views = projected.data();
  const XrCompositionLayerBaseHeader* layers[] = {
      reinterpret_cast<const XrCompositionLayerBaseHeader*>(&layer)};
  XrFrameEndInfo end{XR_TYPE_FRAME_END_INFO};
  end.displayTime = frame.display_time;
  end.environmentBlendMode = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
  end.layerCount = draw ? 1 : 0;
  end.layers = draw ? layers : nullptr;
  XR_CHECK(xrEndFrame(session_, &end));
}

}  // namespace sketchsurf::vk
