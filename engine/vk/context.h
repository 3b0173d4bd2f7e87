#pragma once
// The Vulkan context: instance, physical device choice, logical device, one graphics queue and a
// command pool. Everything the renderer creates hangs off one Context.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "engine/vk/handle.h"

namespace sketchsurf::vk {

/// Whether to enable the Khronos validation layer.
enum class Validation {
  Off,
  On,           ///< enable it; a log line says so when the layer is not installed
  DebugBuilds,  ///< enable it when installed in builds without NDEBUG
};

/// Who makes the instance and the device in place of Vulkan's own calls: an OpenXR runtime does
/// (XR_KHR_vulkan_enable2: it adds the extensions it needs and names the physical device of the
/// headset). An empty member means Vulkan's call (or choose_device()).
struct ContextFactory {
  std::function<VkResult(const VkInstanceCreateInfo&, VkInstance*)> create_instance;
  std::function<VkPhysicalDevice(VkInstance)> physical_device;  ///< throws when there is none
  std::function<VkResult(VkPhysicalDevice, const VkDeviceCreateInfo&, VkDevice*)> create_device;
};

/// How to create a Context.
struct ContextOptions {
  std::string device;                            ///< case-insensitive substring of the device name; empty = best
  Validation validation = Validation::DebugBuilds;  ///< Khronos validation layer
  std::function<void(const std::string&)> log;   ///< receives notable events, one line each; may be empty
  std::vector<std::string> instance_extensions;  ///< extra instance extensions (a window system's
                                                 ///< surface extensions, from GLFW)
  bool presentation = false;                     ///< enable VK_KHR_swapchain; only devices that
                                                 ///< have it are chosen
  ContextFactory factory;                        ///< how the instance and the device are made
};

/// What we need to know about a physical device to choose it.
struct DeviceInfo {
  std::string name;                                                 ///< VkPhysicalDeviceProperties::deviceName
  VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;        ///< discrete, integrated, CPU, ...
  bool graphics = false;                                            ///< has a graphics queue family
};

/// The outcome of choose_device(): a device, or the reason there is none (vk-bootstrap style).
struct DeviceChoice {
  std::optional<std::size_t> index;  ///< chosen entry of the list; empty when none fits
  bool software = false;             ///< the chosen device renders on the CPU (lavapipe)
  std::string message;               ///< why none fits; or, for a software fallback, the log line
};

/// Chooses among `devices`: with a non-empty `request`, the first graphics-capable device whose
/// name contains it (case-insensitive); otherwise discrete GPU > integrated > virtual > CPU.
/// Never throws; an empty index means no device fits and `message` says why (listing the names).
DeviceChoice choose_device(const std::vector<DeviceInfo>& devices, const std::string& request);

/// Instance + device + graphics queue + command pool. Not copyable or movable (the validation
/// callback points at it). Throws Error (Processing) naming the Debian package when no Vulkan
/// driver is installed, Error (Usage) when `options.device` matches no device.
class Context {
 public:
  explicit Context(const ContextOptions& options = {});
  ~Context() = default;
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  VkInstance instance() const { return instance_.get(); }
  VkPhysicalDevice physical_device() const { return physical_; }
  VkDevice device() const { return device_.get(); }
  VkQueue queue() const { return queue_; }
  std::uint32_t queue_family() const { return queue_family_; }
  VkCommandPool command_pool() const { return pool_.get(); }
  const DeviceInfo& device_info() const { return info_; }
  bool software() const { return info_.type == VK_PHYSICAL_DEVICE_TYPE_CPU; }
  const VkPhysicalDeviceLimits& limits() const { return limits_; }

  /// True when the validation layer is active; its warnings and errors go to validation_messages().
  bool validation_enabled() const { return messenger_.get() != VK_NULL_HANDLE; }
  /// Every validation warning or error reported so far, one string each.
  const std::vector<std::string>& validation_messages() const { return messages_; }

  /// A memory type index allowed by `type_bits` with all of `properties`; throws if none.
  std::uint32_t memory_type(std::uint32_t type_bits, VkMemoryPropertyFlags properties) const;
  /// The largest sample count <= `wanted` supported for colour and depth framebuffers.
  VkSampleCountFlagBits supported_samples(VkSampleCountFlagBits wanted) const;
  /// Records commands with `record` into a fresh command buffer, submits it and waits for it.
  void submit_and_wait(const std::function<void(VkCommandBuffer)>& record) const;
  /// Gives `handle` a name shown by validation messages and debuggers (no-op without validation).
  void set_name(VkObjectType type, std::uint64_t handle, const char* name) const;

 private:
  void log(const std::string& line) const;
  static VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                   VkDebugUtilsMessageTypeFlagsEXT types,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                   void* self);

  // Declaration order is destruction order reversed: the pool goes before the device, the device
  // before the instance.
  ContextOptions options_;
  std::vector<std::string> messages_;
  UniqueInstance instance_;
  UniqueMessenger messenger_;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  UniqueDevice device_;
  VkQueue queue_ = VK_NULL_HANDLE;
  std::uint32_t queue_family_ = 0;
  DeviceInfo info_;
  VkPhysicalDeviceLimits limits_{};
  VkPhysicalDeviceMemoryProperties memory_{};
  UniqueCommandPool pool_;
  PFN_vkSetDebugUtilsObjectNameEXT set_object_name_ = nullptr;
};

}  // namespace sketchsurf::vk
