#include "engine/vk/check.h"

namespace sketchsurf::vk {

const char* result_name(VkResult result) {
  switch (result) {
#define SKETCHSURF_VK_RESULT(name) \
  case name:                       \
    return #name;
    SKETCHSURF_VK_RESULT(VK_SUCCESS)
    SKETCHSURF_VK_RESULT(VK_NOT_READY)
    SKETCHSURF_VK_RESULT(VK_TIMEOUT)
    SKETCHSURF_VK_RESULT(VK_EVENT_SET)
    SKETCHSURF_VK_RESULT(VK_EVENT_RESET)
    SKETCHSURF_VK_RESULT(VK_INCOMPLETE)
    SKETCHSURF_VK_RESULT(VK_ERROR_OUT_OF_HOST_MEMORY)
    SKETCHSURF_VK_RESULT(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    SKETCHSURF_VK_RESULT(VK_ERROR_INITIALIZATION_FAILED)
    SKETCHSURF_VK_RESULT(VK_ERROR_DEVICE_LOST)
    SKETCHSURF_VK_RESULT(VK_ERROR_MEMORY_MAP_FAILED)
    SKETCHSURF_VK_RESULT(VK_ERROR_LAYER_NOT_PRESENT)
    SKETCHSURF_VK_RESULT(VK_ERROR_EXTENSION_NOT_PRESENT)
    SKETCHSURF_VK_RESULT(VK_ERROR_FEATURE_NOT_PRESENT)
    SKETCHSURF_VK_RESULT(VK_ERROR_INCOMPATIBLE_DRIVER)
    SKETCHSURF_VK_RESULT(VK_ERROR_TOO_MANY_OBJECTS)
    SKETCHSURF_VK_RESULT(VK_ERROR_FORMAT_NOT_SUPPORTED)
    SKETCHSURF_VK_RESULT(VK_ERROR_FRAGMENTED_POOL)
    SKETCHSURF_VK_RESULT(VK_ERROR_UNKNOWN)
    SKETCHSURF_VK_RESULT(VK_ERROR_OUT_OF_POOL_MEMORY)
    SKETCHSURF_VK_RESULT(VK_ERROR_INVALID_EXTERNAL_HANDLE)
    SKETCHSURF_VK_RESULT(VK_ERROR_FRAGMENTATION)
    SKETCHSURF_VK_RESULT(VK_ERROR_INVALID_OPAQUE_CAPTURE_ADDRESS)
    SKETCHSURF_VK_RESULT(VK_ERROR_SURFACE_LOST_KHR)
    SKETCHSURF_VK_RESULT(VK_ERROR_NATIVE_WINDOW_IN_USE_KHR)
    SKETCHSURF_VK_RESULT(VK_SUBOPTIMAL_KHR)
    SKETCHSURF_VK_RESULT(VK_ERROR_OUT_OF_DATE_KHR)
    SKETCHSURF_VK_RESULT(VK_ERROR_VALIDATION_FAILED_EXT)
#undef SKETCHSURF_VK_RESULT
    default:
      return "VkResult(unknown)";
  }
}

void throw_vk_error(VkResult result, const char* call, const char* file, int line) {
  std::string name = result_name(result);
  if (name == "VkResult(unknown)") name = "VkResult(" + std::to_string(static_cast<int>(result)) + ")";
  throw VulkanError(result, std::string(call) + " failed: " + name + " (" + file + ":" +
                                std::to_string(line) + ")");
}

std::string missing_driver_message(const std::string& detail) {
  return "no usable Vulkan driver (" + detail +
         "); install the Debian package 'mesa-vulkan-drivers' (software rendering with lavapipe) "
         "or your GPU's Vulkan driver";
}

}  // namespace sketchsurf::vk
