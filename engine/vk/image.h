#pragma once
// Images: a VkImage with its own memory and, for attachments, a view.

#include <vulkan/vulkan.h>

#include <cstddef>

#include "engine/vk/commands.h"
#include "engine/vk/context.h"

namespace sketchsurf::vk {

/// What an Image is.
struct ImageDesc {
  VkExtent2D extent{1, 1};                           ///< pixels
  VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;        ///< texel format
  VkImageUsageFlags usage = 0;                       ///< VK_IMAGE_USAGE_* bits
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;  ///< MSAA samples
  VkImageTiling tiling = VK_IMAGE_TILING_OPTIMAL;    ///< LINEAR only for host readback
  VkImageAspectFlags view_aspect = 0;                ///< aspect of the view; 0 = no view
  bool host_visible = false;                         ///< host-visible coherent memory, kept mapped
};

/// A VkImage, its memory and an optional view. Move-only.
class Image {
 public:
  Image() = default;
  /// Throws VulkanError when creation or allocation fails.
  Image(const Context& context, const ImageDesc& desc, const char* name = nullptr);

  VkImage get() const { return image_.get(); }
  VkImageView view() const { return view_.get(); }
  const ImageDesc& desc() const { return desc_; }
  /// The mapped memory of a host-visible image (nullptr otherwise); see vkGetImageSubresourceLayout.
  const std::byte* mapped() const { return mapped_; }

 private:
  ImageDesc desc_;
  UniqueImage image_;
  UniqueMemory memory_;
  UniqueImageView view_;
  std::byte* mapped_ = nullptr;
};


}  // namespace sketchsurf::vk
