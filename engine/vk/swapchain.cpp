#include "engine/vk/swapchain.h"

#include <algorithm>
#include <cstring>

#include "engine/vk/check.h"
#include "engine/vk/render_pass.h"

namespace sketchsurf::vk {

namespace {

/// An 8-bit UNORM format, so that the window shows the colours the offscreen target (RGBA8
/// UNORM) writes to PNG: the same pictures on both targets.
VkSurfaceFormatKHR choose_format(VkPhysicalDevice device, VkSurfaceKHR surface) {
  std::uint32_t count = 0;
  VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(device, surface, &count, nullptr));
  std::vector<VkSurfaceFormatKHR> formats(count);
  VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(device, surface, &count, formats.data()));
  if (formats.empty()) throw Error::processing("the window surface offers no format");
  for (VkFormat wanted : {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM})
    for (const auto& f : formats)
      if (f.format == wanted) return f;
  return formats.front();
}

VkPresentModeKHR choose_mode(VkPhysicalDevice device, VkSurfaceKHR surface, bool vsync) {
  if (vsync) return VK_PRESENT_MODE_FIFO_KHR;  // always supported
  std::uint32_t count = 0;
  VK_CHECK(vkGetPhysicalDeviceSurfacePresentModesKHR(device, surface, &count, nullptr));
  std::vector<VkPresentModeKHR> modes(count);
  VK_CHECK(vkGetPhysicalDeviceSurfacePresentModesKHR(device, surface, &count, modes.data()));
  for (VkPresentModeKHR wanted : {VK_PRESENT_MODE_MAILBOX_KHR, VK_PRESENT_MODE_IMMEDIATE_KHR})
    if (std::find(modes.begin(), modes.end(), wanted) != modes.end()) return wanted;
  return VK_PRESENT_MODE_FIFO_KHR;
}

}  // namespace

Swapchain::Swapchain(const Context& context, VkSurfaceKHR surface, VkExtent2D extent, bool vsync,
                     VkSampleCountFlagBits samples)
    : context_(&context),
      surface_(surface),
      vsync_(vsync),
      samples_(context.supported_samples(samples)) {
  VkBool32 present = VK_FALSE;
  VK_CHECK(vkGetPhysicalDeviceSurfaceSupportKHR(context.physical_device(), context.queue_family(),
                                                surface, &present));
  if (!present)
    throw Error::processing("'" + context.device_info().name +
                            "' cannot present to this window; run with --headless");
  format_ = choose_format(context.physical_device(), surface);
  present_mode_ = choose_mode(context.physical_device(), surface, vsync);
  depth_format_ = choose_depth_format(context);

  // Attachments (render_pass.h): the swapchain image is the colour target, or the resolve target
  // with MSAA; it ends ready to present.
  // The image is acquired (semaphore waited at COLOR_ATTACHMENT_OUTPUT) before it is written;
  // depth is reused by the next frame only after this one's depth tests.
  VkSubpassDependency dep{};
  dep.srcSubpass = VK_SUBPASS_EXTERNAL;
  dep.dstSubpass = 0;
  dep.srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                     VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
  dep.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                     VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT;
  dep.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  dep.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT |
                      VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
  render_pass_ = create_render_pass(context, format_.format, depth_format_, samples_,
                                    VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, {dep});
  build(extent, VK_NULL_HANDLE);
}

Swapchain::~Swapchain() {
  if (context_) vkDeviceWaitIdle(context_->device());
}

void Swapchain::recreate(VkExtent2D extent) {
  VK_CHECK(vkDeviceWaitIdle(context_->device()));
  framebuffers_.clear();
  views_.clear();
  build(extent, swapchain_.get());
}

void Swapchain::build(VkExtent2D wanted, VkSwapchainKHR old) {
  const VkDevice device = context_->device();
  VkSurfaceCapabilitiesKHR caps;
  VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(context_->physical_device(), surface_, &caps));
  if (caps.currentExtent.width != UINT32_MAX) {
    extent_ = caps.currentExtent;
  } else {
    extent_.width = std::clamp(wanted.width, caps.minImageExtent.width, caps.maxImageExtent.width);
    extent_.height = std::clamp(wanted.height, caps.minImageExtent.height, caps.maxImageExtent.height);
  }
  extent_.width = std::max(extent_.width, 1u);
  extent_.height = std::max(extent_.height, 1u);
  min_images_ = std::max(2u, caps.minImageCount);
  std::uint32_t count = caps.minImageCount + 1;
  if (caps.maxImageCount > 0) count = std::min(count, caps.maxImageCount);
  readable_ = (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT) != 0;

  VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  info.surface = surface_;
  info.minImageCount = count;
  info.imageFormat = format_.format;
  info.imageColorSpace = format_.colorSpace;
  info.imageExtent = extent_;
  info.imageArrayLayers = 1;
  info.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT |
                    (readable_ ? VK_IMAGE_USAGE_TRANSFER_SRC_BIT : 0);
  info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.preTransform = caps.currentTransform;
  info.compositeAlpha = (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
                            ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                            : static_cast<VkCompositeAlphaFlagBitsKHR>(
                                  caps.supportedCompositeAlpha & -caps.supportedCompositeAlpha);
  info.presentMode = present_mode_;
  info.clipped = VK_TRUE;
  info.oldSwapchain = old;
  VkSwapchainKHR swapchain = VK_NULL_HANDLE;
  VK_CHECK(vkCreateSwapchainKHR(device, &info, nullptr, &swapchain));
  swapchain_ = UniqueSwapchain(device, swapchain);  // destroys the old one

  std::uint32_t n = 0;
  VK_CHECK(vkGetSwapchainImagesKHR(device, swapchain, &n, nullptr));
  images_.resize(n);
  VK_CHECK(vkGetSwapchainImagesKHR(device, swapchain, &n, images_.data()));

  const bool msaa = samples_ != VK_SAMPLE_COUNT_1_BIT;
  if (msaa)
    color_msaa_ = Image(*context_,
                        {extent_, format_.format,
                         VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT,
                         samples_, VK_IMAGE_TILING_OPTIMAL, VK_IMAGE_ASPECT_COLOR_BIT, false},
                        "window colour (msaa)");
  depth_ = Image(*context_,
                 {extent_, depth_format_,
                  VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT,
                  samples_, VK_IMAGE_TILING_OPTIMAL, VK_IMAGE_ASPECT_DEPTH_BIT, false},
                 "window depth");
  for (VkImage image : images_) {
    VkImageViewCreateInfo view_info{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    view_info.image = image;
    view_info.viewType = VK_IMAGE_VIEW_TYPE_2D;
    view_info.format = format_.format;
    view_info.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageView view = VK_NULL_HANDLE;
    VK_CHECK(vkCreateImageView(device, &view_info, nullptr, &view));
    views_.emplace_back(device, view);
    std::vector<VkImageView> attachments;
    attachments.push_back(msaa ? color_msaa_.view() : view);
    attachments.push_back(depth_.view());
    if (msaa) attachments.push_back(view);
    framebuffers_.push_back(create_framebuffer(*context_, render_pass_.get(), extent_, attachments));
  }
}

void Swapchain::begin(VkCommandBuffer cmd, std::uint32_t index,
                      const std::array<float, 4>& background) const {
  begin_render_pass(cmd, render_pass_.get(), framebuffers_.at(index).get(), extent_, samples_, background);
}

void Swapchain::record_copy(VkCommandBuffer cmd, std::uint32_t index, const Buffer& buffer) const {
  record_readback(cmd, images_.at(index), VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, extent_, buffer.get(),
                  VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT);
}

std::vector<std::uint8_t> Swapchain::pixels(const Buffer& buffer) const {
  const std::size_t n = std::size_t(extent_.width) * extent_.height * 4;
  std::vector<std::uint8_t> out(n);
  std::memcpy(out.data(), buffer.mapped(), n);
  const bool bgra = format_.format == VK_FORMAT_B8G8R8A8_UNORM || format_.format == VK_FORMAT_B8G8R8A8_SRGB;
  for (std::size_t i = 0; i < n; i += 4) {
    if (bgra) std::swap(out[i], out[i + 2]);
    out[i + 3] = 255;  // the window is opaque whatever the alpha written
  }
  return out;
}

}  // namespace sketchsurf::vk
