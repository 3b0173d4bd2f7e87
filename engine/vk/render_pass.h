#pragma once
// What the offscreen target and the window's swapchain share: the depth format, the render pass
// (colour, depth and, with MSAA, the resolve target), the framebuffers and how a pass begins.
// The targets differ only in the image they end in and how it is handed on (copied to the host,
// or presented).

#include <vulkan/vulkan.h>

#include <array>
#include <vector>

#include "engine/vk/context.h"
#include "engine/vk/handle.h"

namespace sketchsurf::vk {

/// The first of D32, D24S8 and D16 that `context`'s device can attach; Error (Processing) when
/// none.
VkFormat choose_depth_format(const Context& context);

/// A one-subpass render pass: attachment 0 colour in `color` (multisampled when `samples` > 1,
/// else the target image itself), 1 depth in `depth`, 2 the target image as resolve target (only
/// with MSAA). The target image is cleared and ends in `final_layout`; depth is not kept.
UniqueRenderPass create_render_pass(const Context& context, VkFormat color, VkFormat depth,
                                    VkSampleCountFlagBits samples, VkImageLayout final_layout,
                                    const std::vector<VkSubpassDependency>& dependencies);

/// A framebuffer of `extent` for `pass` with `views` in the attachment order above.
UniqueFramebuffer create_framebuffer(const Context& context, VkRenderPass pass, VkExtent2D extent,
                                     const std::vector<VkImageView>& views);

/// Begins `pass` on `framebuffer`, clearing colour to `background` and depth to 1, and sets the
/// viewport and scissor to the whole `extent`.
void begin_render_pass(VkCommandBuffer cmd, VkRenderPass pass, VkFramebuffer framebuffer,
                       VkExtent2D extent, VkSampleCountFlagBits samples,
                       const std::array<float, 4>& background);

}  // namespace sketchsurf::vk
