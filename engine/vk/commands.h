#pragma once
// Commands that every render target records, and the test OpenXR runtime with them (it hands its
// swapchain images over in the layout OpenXR prescribes and reads them back): layout transitions
// and the copy of a rendered image to a host buffer. Need no Context.

#include <vulkan/vulkan.h>

namespace sketchsurf::vk {

/// Records a pipeline barrier moving a whole single-mip colour image between layouts.
void transition(VkCommandBuffer cmd, VkImage image, VkImageLayout from, VkImageLayout to,
                VkAccessFlags src_access, VkAccessFlags dst_access, VkPipelineStageFlags src_stage,
                VkPipelineStageFlags dst_stage);

/// Records the copy of a colour image of `extent`, rendered (colour attachment writes) and left in
/// `layout`, into `buffer` (tightly packed rows from the top) for the host to read once the
/// commands completed; the image goes back to `layout`, ready for `next_stage`.
void record_readback(VkCommandBuffer cmd, VkImage image, VkImageLayout layout, VkExtent2D extent,
                     VkBuffer buffer, VkPipelineStageFlags next_stage);

}  // namespace sketchsurf::vk
