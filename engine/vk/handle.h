#pragma once
// Move-only owners of Vulkan handles (after Vulkan-Samples' VulkanResource): copying is deleted,
// moving hands the handle over with std::exchange, the destructor destroys it.

#include <vulkan/vulkan.h>

#include <utility>

namespace sketchsurf::vk {

/// Owns one handle created from a VkDevice and destroyed by `Destroy(device, handle, nullptr)`.
template <class Handle, auto Destroy>
class DeviceHandle {
 public:
  DeviceHandle() = default;
  DeviceHandle(VkDevice device, Handle handle) : device_(device), handle_(handle) {}
  ~DeviceHandle() { reset(); }
  DeviceHandle(const DeviceHandle&) = delete;
  DeviceHandle& operator=(const DeviceHandle&) = delete;
  DeviceHandle(DeviceHandle&& other) noexcept
      : device_(std::exchange(other.device_, VK_NULL_HANDLE)),
        handle_(std::exchange(other.handle_, VK_NULL_HANDLE)) {}
  DeviceHandle& operator=(DeviceHandle&& other) noexcept {
    if (this != &other) {
      reset();
      device_ = std::exchange(other.device_, VK_NULL_HANDLE);
      handle_ = std::exchange(other.handle_, VK_NULL_HANDLE);
    }
    return *this;
  }

  Handle get() const { return handle_; }
  explicit operator bool() const { return handle_ != VK_NULL_HANDLE; }
  /// Destroys the handle now (no-op when empty).
  void reset() {
    if (handle_ != VK_NULL_HANDLE) Destroy(device_, handle_, nullptr);
    handle_ = VK_NULL_HANDLE;
    device_ = VK_NULL_HANDLE;
  }

 private:
  VkDevice device_ = VK_NULL_HANDLE;
  Handle handle_ = VK_NULL_HANDLE;
};

using UniqueBuffer = DeviceHandle<VkBuffer, &vkDestroyBuffer>;
using UniqueMemory = DeviceHandle<VkDeviceMemory, &vkFreeMemory>;
using UniqueImage = DeviceHandle<VkImage, &vkDestroyImage>;
using UniqueImageView = DeviceHandle<VkImageView, &vkDestroyImageView>;
using UniqueRenderPass = DeviceHandle<VkRenderPass, &vkDestroyRenderPass>;
using UniqueFramebuffer = DeviceHandle<VkFramebuffer, &vkDestroyFramebuffer>;
using UniqueShaderModule = DeviceHandle<VkShaderModule, &vkDestroyShaderModule>;
using UniquePipelineLayout = DeviceHandle<VkPipelineLayout, &vkDestroyPipelineLayout>;
using UniquePipeline = DeviceHandle<VkPipeline, &vkDestroyPipeline>;
using UniqueCommandPool = DeviceHandle<VkCommandPool, &vkDestroyCommandPool>;
using UniqueFence = DeviceHandle<VkFence, &vkDestroyFence>;
using UniqueSemaphore = DeviceHandle<VkSemaphore, &vkDestroySemaphore>;
using UniqueDescriptorPool = DeviceHandle<VkDescriptorPool, &vkDestroyDescriptorPool>;
using UniqueSwapchain = DeviceHandle<VkSwapchainKHR, &vkDestroySwapchainKHR>;

/// Owns a handle that is destroyed by `Destroy(handle, nullptr)`: VkInstance, VkDevice.
template <class Handle, auto Destroy>
class RootHandle {
 public:
  RootHandle() = default;
  explicit RootHandle(Handle handle) : handle_(handle) {}
  ~RootHandle() { reset(); }
  RootHandle(const RootHandle&) = delete;
  RootHandle& operator=(const RootHandle&) = delete;
  RootHandle(RootHandle&& other) noexcept : handle_(std::exchange(other.handle_, VK_NULL_HANDLE)) {}
  RootHandle& operator=(RootHandle&& other) noexcept {
    if (this != &other) {
      reset();
      handle_ = std::exchange(other.handle_, VK_NULL_HANDLE);
    }
    return *this;
  }
  Handle get() const { return handle_; }
  void reset() {
    if (handle_ != VK_NULL_HANDLE) Destroy(handle_, nullptr);
    handle_ = VK_NULL_HANDLE;
  }

 private:
  Handle handle_ = VK_NULL_HANDLE;
};

using UniqueInstance = RootHandle<VkInstance, &vkDestroyInstance>;
using UniqueDevice = RootHandle<VkDevice, &vkDestroyDevice>;

/// Owns a VkDebugUtilsMessengerEXT (an extension object: its destroy function is looked up).
class UniqueMessenger {
 public:
  UniqueMessenger() = default;
  UniqueMessenger(VkInstance instance, VkDebugUtilsMessengerEXT messenger)
      : instance_(instance), messenger_(messenger) {}
  ~UniqueMessenger() { reset(); }
  UniqueMessenger(const UniqueMessenger&) = delete;
  UniqueMessenger& operator=(const UniqueMessenger&) = delete;
  UniqueMessenger(UniqueMessenger&& other) noexcept
      : instance_(std::exchange(other.instance_, VK_NULL_HANDLE)),
        messenger_(std::exchange(other.messenger_, VK_NULL_HANDLE)) {}
  UniqueMessenger& operator=(UniqueMessenger&& other) noexcept {
    if (this != &other) {
      reset();
      instance_ = std::exchange(other.instance_, VK_NULL_HANDLE);
      messenger_ = std::exchange(other.messenger_, VK_NULL_HANDLE);
    }
    return *this;
  }
  VkDebugUtilsMessengerEXT get() const { return messenger_; }
  void reset() {
    if (messenger_ != VK_NULL_HANDLE) {
      auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
          vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
      if (destroy) destroy(instance_, messenger_, nullptr);
    }
    messenger_ = VK_NULL_HANDLE;
    instance_ = VK_NULL_HANDLE;
  }

 private:
  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
};

}  // namespace sketchsurf::vk
