#pragma once
// Headless render target (after Sascha Willems' renderheadless): colour + depth, multisampled
// when the device allows, resolved into a single-sample image that is copied to a linear,
// host-visible image for readback.

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <vector>

#include "engine/vk/context.h"
#include "engine/vk/image.h"

namespace sketchsurf::vk {

/// An offscreen colour (RGBA8, UNORM) + depth target of a fixed size.
class OffscreenTarget {
 public:
  /// `samples` is a wish: the largest supported count not above it is used. Throws VulkanError.
  OffscreenTarget(const Context& context, VkExtent2D extent,
                  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_4_BIT);

  VkExtent2D extent() const { return extent_; }
  VkSampleCountFlagBits samples() const { return samples_; }
  VkRenderPass render_pass() const { return render_pass_.get(); }
  VkFramebuffer framebuffer() const { return framebuffer_.get(); }

  /// Records the start of the render pass clearing to `background` (RGBA in [0, 1]) and depth 1,
  /// with the viewport and scissor covering the whole target.
  void begin(VkCommandBuffer cmd, const std::array<float, 4>& background) const;
  /// Records the end of the render pass and the copy of the resolved image into the readback image.
  void end_and_copy(VkCommandBuffer cmd) const;
  /// After the commands of end_and_copy() completed: the pixels, row-major from the top-left,
  /// 4 bytes (R, G, B, A) each, rows tightly packed (the readback image's row pitch is honoured).
  std::vector<std::uint8_t> read_pixels() const;

 private:
  const Context* context_;
  VkExtent2D extent_;
  VkSampleCountFlagBits samples_;
  VkFormat depth_format_;
  Image color_msaa_;  // only when samples_ > 1
  Image depth_;
  Image resolved_;
  Image readback_;
  UniqueRenderPass render_pass_;
  UniqueFramebuffer framebuffer_;
};

}  // namespace sketchsurf::vk
