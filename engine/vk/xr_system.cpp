#include "engine/vk/xr_system.h"

#include <cstdlib>
#include <cstring>
#include <vector>

#include "engine/vk/check.h"
#include "engine/vk/xr_check.h"

namespace sketchsurf::vk {

namespace {

std::string env(const char* name) {
  const char* v = std::getenv(name);
  return v ? v : "";
}

/// The parts of a colon-separated list, empty parts left out.
std::vector<std::string> split_paths(const std::string& list) {
  std::vector<std::string> out;
  std::size_t start = 0;
  while (start <= list.size()) {
    const std::size_t colon = std::min(list.find(':', start), list.size());
    if (colon > start) out.push_back(list.substr(start, colon - start));
    start = colon + 1;
  }
  return out;
}

std::string version_text(XrVersion v) {
  return std::to_string(XR_VERSION_MAJOR(v)) + "." + std::to_string(XR_VERSION_MINOR(v)) + "." +
         std::to_string(XR_VERSION_PATCH(v));
}

}  // namespace

std::optional<std::filesystem::path> find_runtime_manifest(std::string* why) {
  const std::string named = env("XR_RUNTIME_JSON");
  if (!named.empty()) {
    if (std::filesystem::is_regular_file(named)) return std::filesystem::path(named);
    if (why) *why = "no OpenXR runtime: XR_RUNTIME_JSON names " + named + ", which is not a file";
    return std::nullopt;
  }
  std::vector<std::string> dirs;
  const std::string home = env("XDG_CONFIG_HOME");
  if (!home.empty())
    dirs.push_back(home);
  else if (!env("HOME").empty())
    dirs.push_back(env("HOME") + "/.config");
  const std::string config_dirs = env("XDG_CONFIG_DIRS");
  for (const auto& d : split_paths(config_dirs.empty() ? "/etc/xdg" : config_dirs)) dirs.push_back(d);
  dirs.push_back("/etc");
  std::string looked;
  for (const auto& d : dirs) {
    const std::filesystem::path file = std::filesystem::path(d) / "openxr/1/active_runtime.json";
    if (std::filesystem::exists(file)) return file;
    looked += (looked.empty() ? "" : ", ") + file.string();
  }
  if (why)
    *why = "no OpenXR runtime: XR_RUNTIME_JSON unset and no active_runtime.json (looked for " + looked +
           "; install Monado, SteamVR or another runtime, or set XR_RUNTIME_JSON)";
  return std::nullopt;
}

XrSystem::XrSystem(const XrSystemOptions& options) : options_(options) {
  std::string why;
  const auto manifest = find_runtime_manifest(&why);
  if (!manifest) throw XrUnavailable(why);

  const char* extension = XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME;
  XrInstanceCreateInfo info{XR_TYPE_INSTANCE_CREATE_INFO};
  std::strncpy(info.applicationInfo.applicationName, options.application.c_str(),
               XR_MAX_APPLICATION_NAME_SIZE - 1);
  std::strncpy(info.applicationInfo.engineName, "sketchsurf", XR_MAX_ENGINE_NAME_SIZE - 1);
  info.applicationInfo.apiVersion = XR_MAKE_VERSION(1, 0, 0);
  info.enabledExtensionCount = 1;
  info.enabledExtensionNames = &extension;
  const XrResult created = xrCreateInstance(&info, &instance_);
  if (created == XR_ERROR_EXTENSION_NOT_PRESENT)
    throw XrUnavailable("the OpenXR runtime of " + manifest->string() + " has no Vulkan support (" +
                        XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME + ")");
  if (XR_FAILED(created))
    throw XrUnavailable("the OpenXR runtime of " + manifest->string() + " did not start (" +
                        xr_result_name(created) + ")");
  try {
    XrInstanceProperties props{XR_TYPE_INSTANCE_PROPERTIES};
    XR_CHECK(xrGetInstanceProperties(instance_, &props));
    runtime_ = std::string(props.runtimeName) + " " + version_text(props.runtimeVersion);
    XrSystemGetInfo get{XR_TYPE_SYSTEM_GET_INFO};
    get.formFactor = XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY;
    const XrResult found = xrGetSystem(instance_, &get, &system_);
    if (found == XR_ERROR_FORM_FACTOR_UNAVAILABLE || found == XR_ERROR_FORM_FACTOR_UNSUPPORTED)
      throw XrUnavailable("no headset: the OpenXR runtime '" + runtime_ + "' sees no head-mounted display (" +
                          xr_result_name(found) + ")");
    XR_CHECK(found);
    XrSystemProperties system_props{XR_TYPE_SYSTEM_PROPERTIES};
    XR_CHECK(xrGetSystemProperties(instance_, system_, &system_props));
    system_name_ = system_props.systemName;
    std::uint32_t count = 0;
    XR_CHECK(xrEnumerateViewConfigurationViews(instance_, system_, XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO,
                                               0, &count, nullptr));
    if (count != 2)
      throw XrUnavailable("no headset: '" + system_name_ + "' has no stereo view configuration");
    for (auto& v : eye_views_) v = {XR_TYPE_VIEW_CONFIGURATION_VIEW};
    XR_CHECK(xrEnumerateViewConfigurationViews(instance_, system_, XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO,
                                               count, &count, eye_views_.data()));
    const auto requirements =
        function<PFN_xrGetVulkanGraphicsRequirements2KHR>("xrGetVulkanGraphicsRequirements2KHR");
    XrGraphicsRequirementsVulkan2KHR needs{XR_TYPE_GRAPHICS_REQUIREMENTS_VULKAN2_KHR};
    XR_CHECK(requirements(instance_, system_, &needs));
    min_vulkan_ = needs.minApiVersionSupported;
    log("OpenXR runtime '" + runtime_ + "', headset '" + system_name_ + "', " +
        std::to_string(eye_views_[0].recommendedImageRectWidth) + "x" +
        std::to_string(eye_views_[0].recommendedImageRectHeight) + " per eye");
  } catch (...) {
    xrDestroyInstance(instance_);
    throw;
  }
}

XrSystem::~XrSystem() {
  if (instance_ != XR_NULL_HANDLE) xrDestroyInstance(instance_);
}

PFN_xrVoidFunction XrSystem::raw_function(const char* name) const {
  PFN_xrVoidFunction f = nullptr;
  XR_CHECK(xrGetInstanceProcAddr(instance_, name, &f));
  return f;
}

void XrSystem::log(const std::string& line) const {
  if (options_.log) options_.log(line);
}

std::unique_ptr<Context> XrSystem::create_context(ContextOptions options) const {
  // The context asks for Vulkan 1.1; a runtime that needs a newer one says so here.
  if (min_vulkan_ > XR_MAKE_VERSION(1, 1, 0))
    throw XrUnavailable("the OpenXR runtime '" + runtime_ + "' needs Vulkan " + version_text(min_vulkan_) +
                        "; sketchsurf uses 1.1");
  const auto create_instance = function<PFN_xrCreateVulkanInstanceKHR>("xrCreateVulkanInstanceKHR");
  const auto physical_device = function<PFN_xrGetVulkanGraphicsDevice2KHR>("xrGetVulkanGraphicsDevice2KHR");
  const auto create_device = function<PFN_xrCreateVulkanDeviceKHR>("xrCreateVulkanDeviceKHR");
  const XrInstance instance = instance_;
  const XrSystemId system = system_;
  options.factory.create_instance = [=](const VkInstanceCreateInfo& info, VkInstance* out) {
    XrVulkanInstanceCreateInfoKHR xr{XR_TYPE_VULKAN_INSTANCE_CREATE_INFO_KHR};
    xr.systemId = system;
    xr.pfnGetInstanceProcAddr = &vkGetInstanceProcAddr;
    xr.vulkanCreateInfo = &info;
    VkResult result = VK_SUCCESS;
    XR_CHECK(create_instance(instance, &xr, out, &result));
    return result;
  };
  options.factory.physical_device = [=](VkInstance vk_instance) {
    XrVulkanGraphicsDeviceGetInfoKHR get{XR_TYPE_VULKAN_GRAPHICS_DEVICE_GET_INFO_KHR};
    get.systemId = system;
    get.vulkanInstance = vk_instance;
    VkPhysicalDevice device = VK_NULL_HANDLE;
    XR_CHECK(physical_device(instance, &get, &device));
    return device;
  };
  options.factory.create_device = [=](VkPhysicalDevice physical, const VkDeviceCreateInfo& info,
                                      VkDevice* out) {
    XrVulkanDeviceCreateInfoKHR xr{XR_TYPE_VULKAN_DEVICE_CREATE_INFO_KHR};
    xr.systemId = system;
    xr.pfnGetInstanceProcAddr = &vkGetInstanceProcAddr;
    xr.vulkanPhysicalDevice = physical;
    xr.vulkanCreateInfo = &info;
    VkResult result = VK_SUCCESS;
    XR_CHECK(create_device(instance, &xr, out, &result));
    return result;
  };
  return std::make_unique<Context>(options);
}

}  // namespace sketchsurf::vk
