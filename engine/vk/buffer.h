#pragma once
// Buffers: a VkBuffer with its own memory; host-visible ones stay mapped for their lifetime.

#include <vulkan/vulkan.h>

#include <cstddef>
#include <span>

#include "engine/vk/context.h"

namespace sketchsurf::vk {

/// Where a buffer's memory lives.
enum class MemoryUse {
  DeviceLocal,  ///< fastest for the GPU; filled with upload_buffer()
  HostVisible,  ///< host-visible and coherent, persistently mapped (staging, readback)
};

/// A VkBuffer and its memory. Move-only.
class Buffer {
 public:
  Buffer() = default;
  /// Throws VulkanError when allocation fails. `size` > 0 bytes.
  Buffer(const Context& context, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use,
         const char* name = nullptr);

  VkBuffer get() const { return buffer_.get(); }
  VkDeviceSize size() const { return size_; }
  /// The mapped bytes of a HostVisible buffer; nullptr for DeviceLocal.
  std::byte* mapped() const { return mapped_; }

 private:
  UniqueBuffer buffer_;
  UniqueMemory memory_;
  VkDeviceSize size_ = 0;
  std::byte* mapped_ = nullptr;
};

/// A DeviceLocal buffer holding `bytes` (copied through a staging buffer, waits for the copy).
/// `usage` gets VK_BUFFER_USAGE_TRANSFER_DST_BIT added. Empty `bytes` give an empty Buffer.
Buffer upload_buffer(const Context& context, std::span<const std::byte> bytes,
                     VkBufferUsageFlags usage, const char* name = nullptr);

}  // namespace sketchsurf::vk
