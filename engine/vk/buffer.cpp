#include "engine/vk/buffer.h"

#include <cstring>

#include "engine/vk/check.h"

namespace sketchsurf::vk {

Buffer::Buffer(const Context& context, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use,
               const char* name)
    : size_(size) {
  const VkDevice device = context.device();
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkBuffer buffer = VK_NULL_HANDLE;
  VK_CHECK(vkCreateBuffer(device, &info, nullptr, &buffer));
  buffer_ = UniqueBuffer(device, buffer);
  if (name) context.set_name(VK_OBJECT_TYPE_BUFFER, reinterpret_cast<std::uint64_t>(buffer), name);

  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(device, buffer, &req);
  const VkMemoryPropertyFlags props =
      use == MemoryUse::HostVisible
          ? VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT
          : VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = req.size;
  alloc.memoryTypeIndex = context.memory_type(req.memoryTypeBits, props);
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VK_CHECK(vkAllocateMemory(device, &alloc, nullptr, &memory));
  memory_ = UniqueMemory(device, memory);
  VK_CHECK(vkBindBufferMemory(device, buffer, memory, 0));
  if (use == MemoryUse::HostVisible) {
    void* data = nullptr;
    VK_CHECK(vkMapMemory(device, memory, 0, VK_WHOLE_SIZE, 0, &data));
    mapped_ = static_cast<std::byte*>(data);
  }
}

Buffer upload_buffer(const Context& context, std::span<const std::byte> bytes,
                     VkBufferUsageFlags usage, const char* name) {
  if (bytes.empty()) return {};
  Buffer staging(context, bytes.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::HostVisible);
  std::memcpy(staging.mapped(), bytes.data(), bytes.size());
  Buffer target(context, bytes.size(), usage | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                MemoryUse::DeviceLocal, name);
  context.submit_and_wait([&](VkCommandBuffer cmd) {
    const VkBufferCopy region{0, 0, bytes.size()};
    vkCmdCopyBuffer(cmd, staging.get(), target.get(), 1, &region);
  });
  return target;
}

}  // namespace sketchsurf::vk
