#pragma once
// VK_CHECK: turns a failed Vulkan call into a VulkanError (a sketchsurf::Error of kind Processing)
// naming the call, the VkResult and where it happened. Library code never aborts.

#include <vulkan/vulkan.h>

#include <string>

#include "surfacing/error.h"

namespace sketchsurf::vk {

/// The enumerator name of a VkResult ("VK_ERROR_OUT_OF_DEVICE_MEMORY"), or "VkResult(N)".
const char* result_name(VkResult result);

/// A failed Vulkan call. kind() is Processing, so the CLI exits with code 4.
class VulkanError : public Error {
 public:
  VulkanError(VkResult result, const std::string& message)
      : Error(ErrorKind::Processing, message), result_(result) {}
  VkResult result() const { return result_; }

 private:
  VkResult result_;
};

/// Throws VulkanError "CALL failed: RESULT (FILE:LINE)". Used by VK_CHECK.
[[noreturn]] void throw_vk_error(VkResult result, const char* call, const char* file, int line);

/// The message for a machine without a usable Vulkan driver: names the Debian package to install.
std::string missing_driver_message(const std::string& detail);

}  // namespace sketchsurf::vk

/// Evaluates a Vulkan call once; throws sketchsurf::vk::VulkanError unless it returns VK_SUCCESS.
#define VK_CHECK(call)                                                              \
  do {                                                                              \
    const VkResult vk_check_result_ = (call);                                       \
    if (vk_check_result_ != VK_SUCCESS)                                             \
      ::sketchsurf::vk::throw_vk_error(vk_check_result_, #call, __FILE__, __LINE__); \
  } while (0)
