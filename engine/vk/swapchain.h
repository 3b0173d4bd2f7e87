#pragma once
// The window's render target: a swapchain on a surface, with the same attachments as the
// offscreen target (multisampled colour when the device allows, depth, resolve into the image
// presented), a render pass compatible across re-creations (format and samples kept) and one
// framebuffer per swapchain image. Re-created on resize; the pipelines built for its render pass
// stay valid.

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <vector>

#include "engine/vk/buffer.h"
#include "engine/vk/context.h"
#include "engine/vk/image.h"

namespace sketchsurf::vk {

class Swapchain {
 public:
  /// `extent` is the window's framebuffer size (each >= 1). `vsync` presents in FIFO mode,
  /// otherwise MAILBOX or IMMEDIATE when the surface has one. Throws VulkanError, or Error
  /// (Processing) when the device cannot present to the surface.
  Swapchain(const Context& context, VkSurfaceKHR surface, VkExtent2D extent, bool vsync,
            VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_4_BIT);
  ~Swapchain();
  Swapchain(const Swapchain&) = delete;
  Swapchain& operator=(const Swapchain&) = delete;

  /// Waits for the device to be idle and builds the swapchain again for `extent` (a resize).
  void recreate(VkExtent2D extent);

  VkSwapchainKHR get() const { return swapchain_.get(); }
  VkExtent2D extent() const { return extent_; }
  VkFormat format() const { return format_.format; }
  VkSampleCountFlagBits samples() const { return samples_; }
  VkRenderPass render_pass() const { return render_pass_.get(); }
  std::uint32_t image_count() const { return static_cast<std::uint32_t>(images_.size()); }
  std::uint32_t min_image_count() const { return min_images_; }
  VkPresentModeKHR present_mode() const { return present_mode_; }

  /// Records the start of the render pass on image `index`, clearing to `background`, with the
  /// viewport and scissor covering the image.
  void begin(VkCommandBuffer cmd, std::uint32_t index, const std::array<float, 4>& background) const;
  /// True when images can be copied out (for screenshots).
  bool readable() const { return readable_; }
  /// After the render pass on image `index` ended: records its copy into `buffer` (host-visible,
  /// width * height * 4 bytes), leaving the image ready to present.
  void record_copy(VkCommandBuffer cmd, std::uint32_t index, const Buffer& buffer) const;
  /// The pixels copied by record_copy() (once its commands completed), as RGBA rows from the top.
  std::vector<std::uint8_t> pixels(const Buffer& buffer) const;

 private:
  void build(VkExtent2D extent, VkSwapchainKHR old);

  const Context* context_;
  VkSurfaceKHR surface_;
  bool vsync_;
  VkSurfaceFormatKHR format_{};
  VkPresentModeKHR present_mode_ = VK_PRESENT_MODE_FIFO_KHR;
  VkSampleCountFlagBits samples_;
  VkFormat depth_format_ = VK_FORMAT_UNDEFINED;
  VkExtent2D extent_{};
  std::uint32_t min_images_ = 2;
  bool readable_ = false;
  UniqueRenderPass render_pass_;
  UniqueSwapchain swapchain_;
  std::vector<VkImage> images_;
  std::vector<UniqueImageView> views_;
  Image color_msaa_;
  Image depth_;
  std::vector<UniqueFramebuffer> framebuffers_;
};

}  // namespace sketchsurf::vk
