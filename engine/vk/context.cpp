#include "engine/vk/context.h"

#include <algorithm>
#include <cctype>
#include <cstring>

#include "engine/vk/check.h"

namespace sketchsurf::vk {

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

/// Preference of a device type: higher is better.
int rank(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 1;
    default: return 0;
  }
}

std::string device_list(const std::vector<DeviceInfo>& devices) {
  std::string out;
  for (const auto& d : devices) out += (out.empty() ? "'" : ", '") + d.name + "'";
  return out.empty() ? "none" : out;
}

bool layer_available(const char* name) {
  std::uint32_t count = 0;
  if (vkEnumerateInstanceLayerProperties(&count, nullptr) != VK_SUCCESS) return false;
  std::vector<VkLayerProperties> layers(count);
  if (vkEnumerateInstanceLayerProperties(&count, layers.data()) != VK_SUCCESS) return false;
  return std::any_of(layers.begin(), layers.end(),
                     [&](const VkLayerProperties& l) { return std::strcmp(l.layerName, name) == 0; });
}

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";

bool has_device_extension(VkPhysicalDevice device, const char* name) {
  std::uint32_t count = 0;
  if (vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr) != VK_SUCCESS) return false;
  std::vector<VkExtensionProperties> extensions(count);
  if (vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data()) != VK_SUCCESS)
    return false;
  return std::any_of(extensions.begin(), extensions.end(), [&](const VkExtensionProperties& e) {
    return std::strcmp(e.extensionName, name) == 0;
  });
}

#ifdef NDEBUG
constexpr bool kDebugBuild = false;
#else
constexpr bool kDebugBuild = true;
#endif

}  // namespace

DeviceChoice choose_device(const std::vector<DeviceInfo>& devices, const std::string& request) {
  DeviceChoice choice;
  if (!request.empty()) {
    const std::string wanted = lower(request);
    for (std::size_t i = 0; i < devices.size(); ++i)
      if (devices[i].graphics && lower(devices[i].name).find(wanted) != std::string::npos) {
        choice.index = i;
        choice.software = devices[i].type == VK_PHYSICAL_DEVICE_TYPE_CPU;
        return choice;
      }
    choice.message = "no Vulkan device with graphics matches '" + request + "' (available: " +
                     device_list(devices) + ")";
    return choice;
  }
  int best = -1;
  for (std::size_t i = 0; i < devices.size(); ++i)
    if (devices[i].graphics && rank(devices[i].type) > best) {
      best = rank(devices[i].type);
      choice.index = i;
    }
  if (!choice.index) {
    choice.message = "no Vulkan device with a graphics queue (devices: " + device_list(devices) + ")";
    return choice;
  }
  const DeviceInfo& chosen = devices[*choice.index];
  choice.software = chosen.type == VK_PHYSICAL_DEVICE_TYPE_CPU;
  if (choice.software)
    choice.message = "no GPU with Vulkan found; rendering on the CPU with '" + chosen.name + "'";
  return choice;
}

Context::Context(const ContextOptions& options) : options_(options) {
  const bool want_validation =
      options.validation == Validation::On ||
      (options.validation == Validation::DebugBuilds && kDebugBuild);
  const bool validation = want_validation && layer_available(kValidationLayer);
  if (want_validation && !validation && options.validation == Validation::On)
    log("the Vulkan validation layer is not installed (Debian package vulkan-validationlayers); "
        "running without it");

  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "sketchsurf";
  app.pEngineName = "sketchsurf";
  app.apiVersion = VK_API_VERSION_1_1;
  std::vector<const char*> layers, extensions;
  if (validation) {
    layers.push_back(kValidationLayer);
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  }
  for (const auto& e : options_.instance_extensions) extensions.push_back(e.c_str());
  VkDebugUtilsMessengerCreateInfoEXT messenger_info{
      VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  messenger_info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                   VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messenger_info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
  messenger_info.pfnUserCallback = &Context::on_message;
  messenger_info.pUserData = this;

  VkInstanceCreateInfo instance_info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  instance_info.pApplicationInfo = &app;
  instance_info.enabledLayerCount = static_cast<std::uint32_t>(layers.size());
  instance_info.ppEnabledLayerNames = layers.data();
  instance_info.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
  instance_info.ppEnabledExtensionNames = extensions.data();
  if (validation) instance_info.pNext = &messenger_info;  // also covers vkCreate/DestroyInstance
  VkInstance instance = VK_NULL_HANDLE;
  const VkResult created = options.factory.create_instance
                               ? options.factory.create_instance(instance_info, &instance)
                               : vkCreateInstance(&instance_info, nullptr, &instance);
  if (created == VK_ERROR_INCOMPATIBLE_DRIVER || created == VK_ERROR_INITIALIZATION_FAILED)
    throw Error::processing(missing_driver_message(std::string("vkCreateInstance: ") +
                                                   result_name(created)));
  VK_CHECK(created);
  instance_ = UniqueInstance(instance);

  if (validation) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance, "vkCreateDebugUtilsMessengerEXT"));
    VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
    if (create) VK_CHECK(create(instance, &messenger_info, nullptr, &messenger));
    messenger_ = UniqueMessenger(instance, messenger);
    set_object_name_ = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
        vkGetInstanceProcAddr(instance, "vkSetDebugUtilsObjectNameEXT"));
  }

  std::uint32_t count = 0;
  const VkResult enumerated = vkEnumeratePhysicalDevices(instance, &count, nullptr);
  if (enumerated == VK_ERROR_INITIALIZATION_FAILED || (enumerated == VK_SUCCESS && count == 0))
    throw Error::processing(missing_driver_message("no Vulkan device found"));
  VK_CHECK(enumerated);
  std::vector<VkPhysicalDevice> physical(count);
  VK_CHECK(vkEnumeratePhysicalDevices(instance, &count, physical.data()));
  std::vector<DeviceInfo> infos;
  std::vector<std::uint32_t> graphics_family(count, 0);
  for (std::uint32_t i = 0; i < count; ++i) {
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(physical[i], &props);
    DeviceInfo info{props.deviceName, props.deviceType, false};
    if (options.presentation && !has_device_extension(physical[i], VK_KHR_SWAPCHAIN_EXTENSION_NAME)) {
      infos.push_back(info);  // no graphics flag: never chosen
      continue;
    }
    std::uint32_t families = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical[i], &families, nullptr);
    std::vector<VkQueueFamilyProperties> family_props(families);
    vkGetPhysicalDeviceQueueFamilyProperties(physical[i], &families, family_props.data());
    for (std::uint32_t f = 0; f < families; ++f)
      if (family_props[f].queueFlags & VK_QUEUE_GRAPHICS_BIT) {
        info.graphics = true;
        graphics_family[i] = f;
        break;
      }
    infos.push_back(info);
  }
  DeviceChoice choice = choose_device(infos, options.device);
  if (options.factory.physical_device) {
    const VkPhysicalDevice wanted = options.factory.physical_device(instance);
    const auto found = std::find(physical.begin(), physical.end(), wanted);
    if (found == physical.end() || !infos[std::size_t(found - physical.begin())].graphics)
      throw Error::processing("the Vulkan device chosen for the headset has no graphics queue (devices: " +
                              device_list(infos) + ")");
    choice.index = std::size_t(found - physical.begin());
    choice.software = infos[*choice.index].type == VK_PHYSICAL_DEVICE_TYPE_CPU;
    choice.message = "rendering on the CPU with '" + infos[*choice.index].name +
                     "', the device the OpenXR runtime named";
  }
  if (!choice.index) {
    if (!options.device.empty()) throw Error::usage(choice.message);
    throw Error::processing(missing_driver_message(choice.message));
  }
  if (choice.software && options.device.empty()) log(choice.message);
  physical_ = physical[*choice.index];
  info_ = infos[*choice.index];
  queue_family_ = graphics_family[*choice.index];
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(physical_, &props);
  limits_ = props.limits;
  vkGetPhysicalDeviceMemoryProperties(physical_, &memory_);

  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queue_info.queueFamilyIndex = queue_family_;
  queue_info.queueCount = 1;
  queue_info.pQueuePriorities = &priority;
  VkDeviceCreateInfo device_info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  device_info.queueCreateInfoCount = 1;
  device_info.pQueueCreateInfos = &queue_info;
  const char* swapchain_extension = VK_KHR_SWAPCHAIN_EXTENSION_NAME;
  if (options.presentation) {
    device_info.enabledExtensionCount = 1;
    device_info.ppEnabledExtensionNames = &swapchain_extension;
  }
  VkDevice device = VK_NULL_HANDLE;
  VK_CHECK(options.factory.create_device ? options.factory.create_device(physical_, device_info, &device)
                                         : vkCreateDevice(physical_, &device_info, nullptr, &device));
  device_ = UniqueDevice(device);
  vkGetDeviceQueue(device, queue_family_, 0, &queue_);

  VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pool_info.queueFamilyIndex = queue_family_;
  VkCommandPool pool = VK_NULL_HANDLE;
  VK_CHECK(vkCreateCommandPool(device, &pool_info, nullptr, &pool));
  pool_ = UniqueCommandPool(device, pool);
}

void Context::log(const std::string& line) const {
  if (options_.log) options_.log(line);
}

VkBool32 Context::on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                             VkDebugUtilsMessageTypeFlagsEXT,
                             const VkDebugUtilsMessengerCallbackDataEXT* data, void* self) {
  auto* context = static_cast<Context*>(self);
  const std::string text =
      std::string(severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT ? "validation error: "
                                                                             : "validation warning: ") +
      (data && data->pMessage ? data->pMessage : "(no message)");
  context->messages_.push_back(text);
  context->log(text);
  return VK_FALSE;
}

std::uint32_t Context::memory_type(std::uint32_t type_bits, VkMemoryPropertyFlags properties) const {
  for (std::uint32_t i = 0; i < memory_.memoryTypeCount; ++i)
    if ((type_bits & (1u << i)) && (memory_.memoryTypes[i].propertyFlags & properties) == properties)
      return i;
  throw Error::processing("no Vulkan memory type with properties " + std::to_string(properties) +
                          " on '" + info_.name + "'");
}

VkSampleCountFlagBits Context::supported_samples(VkSampleCountFlagBits wanted) const {
  const VkSampleCountFlags both =
      limits_.framebufferColorSampleCounts & limits_.framebufferDepthSampleCounts;
  for (auto s = static_cast<std::uint32_t>(wanted); s > 1; s >>= 1)
    if (both & s) return static_cast<VkSampleCountFlagBits>(s);
  return VK_SAMPLE_COUNT_1_BIT;
}

void Context::submit_and_wait(const std::function<void(VkCommandBuffer)>& record) const {
  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = pool_.get();
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VK_CHECK(vkAllocateCommandBuffers(device(), &alloc, &cmd));
  // Frees the command buffer however we leave (an exception from `record` included).
  struct Free {
    VkDevice device;
    VkCommandPool pool;
    VkCommandBuffer cmd;
    ~Free() { vkFreeCommandBuffers(device, pool, 1, &cmd); }
  } free_cmd{device(), pool_.get(), cmd};

  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
  record(cmd);
  VK_CHECK(vkEndCommandBuffer(cmd));

  VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence fence_handle = VK_NULL_HANDLE;
  VK_CHECK(vkCreateFence(device(), &fence_info, nullptr, &fence_handle));
  const UniqueFence fence(device(), fence_handle);
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  VK_CHECK(vkQueueSubmit(queue_, 1, &submit, fence.get()));
  VK_CHECK(vkWaitForFences(device(), 1, &fence_handle, VK_TRUE, UINT64_MAX));
}

void Context::set_name(VkObjectType type, std::uint64_t handle, const char* name) const {
  if (!set_object_name_ || handle == 0) return;
  VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
  info.objectType = type;
  info.objectHandle = handle;
  info.pObjectName = name;
  set_object_name_(device(), &info);
}

}  // namespace sketchsurf::vk
