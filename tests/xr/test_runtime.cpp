// A test OpenXR runtime, for the studio's headset tests only: the loader loads it when
// XR_RUNTIME_JSON names its manifest (test_runtime.json, written by CMake next to the library).
//
// It plays a headset on the application's own Vulkan device (lavapipe in CI): XR_KHR_vulkan_enable2
// (the Vulkan instance and device made through the application's vkGetInstanceProcAddr), one
// system with a stereo view configuration, the session life cycle (IDLE -> READY, then
// SYNCHRONIZED -> VISIBLE -> FOCUSED once begun; STOPPING when the application asks to exit or the
// scripted time is over; IDLE -> EXITING once ended), swapchains whose VkImages it makes on the
// application's device, frames on a simulated 64 Hz clock (multiples of 1/64 s are exact in
// binary, so a track sampled at k/64 s is met exactly), stage, local and view spaces, actions
// (one right-hand controller whose poses, trigger and buttons come from a sketchsurf track) and
// haptics. It never sleeps: frames come as fast as the application renders them.
//
// Environment:
//   SKETCHSURF_TEST_XR_TRACK    the track (sketchsurf-track JSON) the controller plays; none: idle
//   SKETCHSURF_TEST_XR_OUT      folder for report.json (at xrDestroyInstance) and the two eyes'
//                               last images, eye_0.ppm and eye_1.ppm
//   SKETCHSURF_TEST_XR_PROFILE  the controller's interaction profile
//                               (default /interaction_profiles/oculus/touch_controller)
//   SKETCHSURF_TEST_XR_FRAMES   frames before the runtime stops the session (default: the
//                               track's length plus 16 frames)
//   SKETCHSURF_TEST_XR_SIZE     eye image size WxH (default 512x448)
//   SKETCHSURF_TEST_XR_NO_HMD   set: xrGetSystem finds no head-mounted display

#include <vulkan/vulkan.h>
#define XR_USE_GRAPHICS_API_VULKAN
#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "engine/input/track.h"
#include "engine/vk/commands.h"
#include "engine/vk/xr_check.h"

// The loader's negotiation structs (the OpenXR SDK's loader_interfaces.h, which Debian does not
// ship), version 1.
extern "C" {
enum XrLoaderInterfaceStructs {
  XR_LOADER_INTERFACE_STRUCT_UNINTIALIZED = 0,
  XR_LOADER_INTERFACE_STRUCT_LOADER_INFO,
  XR_LOADER_INTERFACE_STRUCT_API_LAYER_REQUEST,
  XR_LOADER_INTERFACE_STRUCT_RUNTIME_REQUEST,
};
struct XrNegotiateLoaderInfo {
  XrLoaderInterfaceStructs structType;
  uint32_t structVersion;
  size_t structSize;
  uint32_t minInterfaceVersion;
  uint32_t maxInterfaceVersion;
  XrVersion minApiVersion;
  XrVersion maxApiVersion;
};
struct XrNegotiateRuntimeRequest {
  XrLoaderInterfaceStructs structType;
  uint32_t structVersion;
  size_t structSize;
  uint32_t runtimeInterfaceVersion;
  XrVersion runtimeApiVersion;
  PFN_xrGetInstanceProcAddr getInstanceProcAddr;
};
}

namespace {

using sketchsurf::input::Button;
using sketchsurf::input::ControllerState;
using sketchsurf::vk::transition;

constexpr XrTime kPeriod = 15'625'000;  // 1/64 s
constexpr XrTime kStart = 1'000'000'000;

std::string env(const char* name) {
  const char* v = std::getenv(name);
  return v ? v : "";
}

Eigen::Isometry3d to_iso(const XrPosef& p) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Eigen::Quaterniond(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z)
                   .normalized()
                   .toRotationMatrix();
  t.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  return t;
}

XrPosef to_pose(const Eigen::Isometry3d& t) {
  const Eigen::Quaterniond q(t.linear());
  const Eigen::Vector3d p = t.translation();
  return {{float(q.x()), float(q.y()), float(q.z()), float(q.w())},
          {float(p.x()), float(p.y()), float(p.z())}};
}

struct Action;
struct ActionSet {
  std::string name;
  bool attached = false;
  std::vector<Action*> actions;
};
struct Action {
  ActionSet* set = nullptr;
  std::string name;
  XrActionType type = XR_ACTION_TYPE_BOOLEAN_INPUT;
  float last = 0.0f;
  XrTime changed = 0;
  bool changed_since_sync = false;
};
struct Space {
  bool reference = true;
  XrReferenceSpaceType type = XR_REFERENCE_SPACE_TYPE_STAGE;
  Action* action = nullptr;
  Eigen::Isometry3d offset = Eigen::Isometry3d::Identity();
};
struct SwapImage {
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
};
struct Swapchain {
  VkFormat format = VK_FORMAT_UNDEFINED;
  std::uint32_t width = 0, height = 0;
  std::vector<SwapImage> images;
  std::uint32_t next = 0;
  std::vector<std::uint32_t> acquired;
  bool waited = false;
  std::optional<std::uint32_t> released;
};

/// Everything of the one instance this runtime serves at a time.
struct Runtime {
  std::vector<std::string> paths;  // XrPath n is paths[n - 1]
  std::set<void*> live;            // every handle given out and not destroyed
  // Vulkan, from XR_KHR_vulkan_enable2 and the session's graphics binding.
  PFN_vkGetInstanceProcAddr gipa = nullptr;
  VkInstance vk_instance = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  std::uint32_t queue_family = 0;
  // The session.
  bool session = false, running = false, exit_requested = false;
  XrSessionState state = XR_SESSION_STATE_UNKNOWN;
  std::vector<XrSessionState> states;  // every state sent
  std::vector<XrEventDataBuffer> events;
  std::map<std::string, std::vector<std::pair<Action*, std::string>>> bindings;  // profile -> bindings
  bool profile_bound = false;
  std::int64_t frames_waited = 0, frames_ended = 0, frames_with_layers = 0;
  XrTime display_time = 0;
  std::int64_t stop_frame = 0;
  bool stopped_by_runtime = false, session_ended = false, session_destroyed = false;
  std::size_t haptics = 0;
  std::vector<double> haptic_times;
  std::vector<std::string> errors;  // misuse seen (acquire twice, release without wait, ...)
  std::vector<std::string> images_written;
  // Configuration.
  std::string profile = "/interaction_profiles/oculus/touch_controller";
  std::uint32_t width = 512, height = 448;
  bool no_hmd = false;
  sketchsurf::input::Track track;
  std::filesystem::path out;
};

Runtime* g_runtime = nullptr;  // the C entry points reach the instance's state through it

Runtime& rt() { return *g_runtime; }

template <class T>
T* as(void* handle) {
  return g_runtime && g_runtime->live.count(handle) ? static_cast<T*>(handle) : nullptr;
}

template <class Handle, class T>
Handle give(T* object) {
  rt().live.insert(object);
  return reinterpret_cast<Handle>(object);
}

void push_state(XrSessionState state) {
  XrEventDataBuffer buffer{XR_TYPE_EVENT_DATA_BUFFER};
  auto& e = reinterpret_cast<XrEventDataSessionStateChanged&>(buffer);
  e.type = XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED;
  e.next = nullptr;
  e.session = reinterpret_cast<XrSession>(&rt());
  e.state = state;
  e.time = rt().display_time;
  rt().events.push_back(buffer);
}

/// The sample of the track at frame time `time`: the last one not after it.
std::optional<ControllerState> sample_at(XrTime time) {
  if (time < kStart + kPeriod) return std::nullopt;
  const double t = double(time - kStart - kPeriod) * 1e-9;
  std::optional<ControllerState> found;
  for (const auto& e : rt().track.events) {
    if (e.time_s > t) break;
    if (e.state) found = e.state;
  }
  return found;
}

/// The value of a controller input path (below /user/hand/right) for `s`; none when the runtime's
/// controller has no such input.
std::optional<float> input_value(const std::string& path, const ControllerState& s) {
  const std::string hand = "/user/hand/right/input/";
  if (path.rfind(hand, 0) != 0) return std::nullopt;
  const std::string input = path.substr(hand.size());
  const auto button = [&](Button b) { return s.pressed(b) ? 1.0f : 0.0f; };
  if (input == "trigger/value") return s.trigger;
  if (input == "select/click" || input == "trigger/click") return button(Button::Draw);
  if (input == "squeeze/value" || input == "squeeze/click") return button(Button::Grab);
  if (input == "a/click") return button(Button::Undo);
  if (input == "b/click") return button(Button::Redo);
  if (input == "menu/click" || input == "thumbstick/click") return button(Button::Menu);
  if (input == "trackpad/click" || input == "trackpad/x") return 0.0f;
  return std::nullopt;
}

bool is_pose_input(const std::string& path) {
  return path == "/user/hand/right/input/aim/pose" || path == "/user/hand/right/input/grip/pose";
}

/// The bound paths of `action` under the runtime's profile (empty: the action is inactive).
std::vector<std::string> bound_paths(const Action* action) {
  std::vector<std::string> out;
  if (!rt().profile_bound || !action->set->attached) return out;
  const auto it = rt().bindings.find(rt().profile);
  if (it == rt().bindings.end()) return out;
  for (const auto& [a, path] : it->second)
    if (a == action) out.push_back(path);
  return out;
}

bool focused() { return rt().state == XR_SESSION_STATE_FOCUSED; }

/// The pose of `space` in the stage at `time`, if known.
std::optional<Eigen::Isometry3d> stage_pose(const Space& space, XrTime time) {
  if (space.reference) {
    Eigen::Isometry3d base = Eigen::Isometry3d::Identity();
    if (space.type == XR_REFERENCE_SPACE_TYPE_VIEW) base.translation() = Eigen::Vector3d(0, 1.6, 0);
    return base * space.offset;
  }
  if (!focused()) return std::nullopt;
  bool pose_bound = false;
  for (const auto& p : bound_paths(space.action)) pose_bound = pose_bound || is_pose_input(p);
  const auto s = sample_at(time);
  if (!pose_bound || !s || !s->tracked) return std::nullopt;
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = s->pose.orientation.normalized().toRotationMatrix();
  t.translation() = s->pose.position;
  return t * space.offset;
}

// --- Vulkan helpers -----------------------------------------------------------------------------

template <class F>
F instance_function(const char* name) {
  return reinterpret_cast<F>(rt().gipa(rt().vk_instance, name));
}

std::uint32_t memory_type(std::uint32_t bits, VkMemoryPropertyFlags flags) {
  VkPhysicalDeviceMemoryProperties props;
  vkGetPhysicalDeviceMemoryProperties(rt().physical, &props);
  for (std::uint32_t i = 0; i < props.memoryTypeCount; ++i)
    if ((bits & (1u << i)) && (props.memoryTypes[i].propertyFlags & flags) == flags) return i;
  return 0;
}

/// Records commands into a one-time command buffer on the application's queue and waits.
template <class Record>
void submit(Record record) {
  VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pool_info.queueFamilyIndex = rt().queue_family;
  VkCommandPool pool = VK_NULL_HANDLE;
  vkCreateCommandPool(rt().device, &pool_info, nullptr, &pool);
  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = pool;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  vkAllocateCommandBuffers(rt().device, &alloc, &cmd);
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vkBeginCommandBuffer(cmd, &begin);
  record(cmd);
  vkEndCommandBuffer(cmd);
  VkSubmitInfo info{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  info.commandBufferCount = 1;
  info.pCommandBuffers = &cmd;
  vkQueueSubmit(rt().queue, 1, &info, VK_NULL_HANDLE);
  vkQueueWaitIdle(rt().queue);
  vkDestroyCommandPool(rt().device, pool, nullptr);
}

/// Copies the released image of `sc` to the host and writes it as a binary PPM (RGB).
void write_image(const Swapchain& sc, const std::filesystem::path& file) {
  const VkImage image = sc.images.at(*sc.released).image;
  const VkDeviceSize size = VkDeviceSize(sc.width) * sc.height * 4;
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  info.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  VkBuffer buffer = VK_NULL_HANDLE;
  vkCreateBuffer(rt().device, &info, nullptr, &buffer);
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(rt().device, buffer, &req);
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = req.size;
  alloc.memoryTypeIndex = memory_type(
      req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  VkDeviceMemory memory = VK_NULL_HANDLE;
  vkAllocateMemory(rt().device, &alloc, nullptr, &memory);
  vkBindBufferMemory(rt().device, buffer, memory, 0);
  submit([&](VkCommandBuffer cmd) {
    sketchsurf::vk::record_readback(cmd, image, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, {sc.width, sc.height},
                                    buffer, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT);
  });
  void* mapped = nullptr;
  vkMapMemory(rt().device, memory, 0, size, 0, &mapped);
  const auto* px = static_cast<const std::uint8_t*>(mapped);
  const bool bgra = sc.format == VK_FORMAT_B8G8R8A8_SRGB || sc.format == VK_FORMAT_B8G8R8A8_UNORM;
  std::ofstream ppm(file, std::ios::binary);
  ppm << "P6\n" << sc.width << " " << sc.height << "\n255\n";
  for (std::size_t i = 0; i < std::size_t(sc.width) * sc.height; ++i) {
    const std::uint8_t* p = px + 4 * i;
    const char rgb[3] = {char(bgra ? p[2] : p[0]), char(p[1]), char(bgra ? p[0] : p[2])};
    ppm.write(rgb, 3);
  }
  vkUnmapMemory(rt().device, memory);
  vkDestroyBuffer(rt().device, buffer, nullptr);
  vkFreeMemory(rt().device, memory, nullptr);
  rt().images_written.push_back(file.filename().string());
}

void write_report() {
  if (rt().out.empty()) return;
  nlohmann::json j;
  for (auto s : rt().states) j["states"].push_back(sketchsurf::vk::xr_state_name(s));
  j["frames_waited"] = rt().frames_waited;
  j["frames_ended"] = rt().frames_ended;
  j["frames_with_layers"] = rt().frames_with_layers;
  j["haptics"] = rt().haptics;
  j["haptic_times"] = rt().haptic_times;
  j["stopped_by_runtime"] = rt().stopped_by_runtime;
  j["session_ended"] = rt().session_ended;
  j["session_destroyed"] = rt().session_destroyed;
  j["instance_destroyed"] = true;
  j["profile_bound"] = rt().profile_bound ? rt().profile : "";
  j["images"] = rt().images_written;
  j["errors"] = rt().errors;
  const auto file = rt().out / "report.json";
  const auto tmp = rt().out / "report.json.tmp";
  std::ofstream(tmp) << j.dump(1) << "\n";
  std::filesystem::rename(tmp, file);
}

// --- OpenXR entry points --------------------------------------------------------------------------

#define XR_FN(name) XRAPI_ATTR XrResult XRAPI_CALL name

XR_FN(EnumerateApiLayerProperties)(uint32_t, uint32_t* count, XrApiLayerProperties*) {
  *count = 0;
  return XR_SUCCESS;
}

XR_FN(EnumerateInstanceExtensionProperties)
(const char* layer, uint32_t capacity, uint32_t* count, XrExtensionProperties* props) {
  if (layer) return XR_ERROR_API_LAYER_NOT_PRESENT;
  *count = 1;
  if (capacity == 0) return XR_SUCCESS;
  if (capacity < 1) return XR_ERROR_SIZE_INSUFFICIENT;
  std::strcpy(props[0].extensionName, XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME);
  props[0].extensionVersion = XR_KHR_vulkan_enable2_SPEC_VERSION;
  return XR_SUCCESS;
}

XR_FN(CreateInstance)(const XrInstanceCreateInfo* info, XrInstance* instance) {
  if (g_runtime) return XR_ERROR_LIMIT_REACHED;
  for (std::uint32_t i = 0; i < info->enabledExtensionCount; ++i)
    if (std::strcmp(info->enabledExtensionNames[i], XR_KHR_VULKAN_ENABLE2_EXTENSION_NAME) != 0)
      return XR_ERROR_EXTENSION_NOT_PRESENT;
  g_runtime = new Runtime;
  Runtime& r = rt();
  if (!env("SKETCHSURF_TEST_XR_PROFILE").empty()) r.profile = env("SKETCHSURF_TEST_XR_PROFILE");
  r.no_hmd = !env("SKETCHSURF_TEST_XR_NO_HMD").empty();
  r.out = env("SKETCHSURF_TEST_XR_OUT");
  if (const std::string size = env("SKETCHSURF_TEST_XR_SIZE"); !size.empty())
    std::sscanf(size.c_str(), "%ux%u", &r.width, &r.height);
  try {
    if (!env("SKETCHSURF_TEST_XR_TRACK").empty())
      r.track = sketchsurf::input::read_track(env("SKETCHSURF_TEST_XR_TRACK"));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "test runtime: %s\n", e.what());
    delete g_runtime;
    g_runtime = nullptr;
    return XR_ERROR_RUNTIME_FAILURE;
  }
  r.stop_frame = std::int64_t(r.track.duration() * 64.0 + 0.5) + 16;
  if (!env("SKETCHSURF_TEST_XR_FRAMES").empty())
    r.stop_frame = std::atoll(env("SKETCHSURF_TEST_XR_FRAMES").c_str());
  *instance = give<XrInstance>(g_runtime);
  return XR_SUCCESS;
}

XR_FN(DestroyInstance)(XrInstance instance) {
  if (!as<Runtime>(instance)) return XR_ERROR_HANDLE_INVALID;
  write_report();
  delete g_runtime;
  g_runtime = nullptr;
  return XR_SUCCESS;
}

XR_FN(GetInstanceProperties)(XrInstance, XrInstanceProperties* props) {
  props->runtimeVersion = XR_MAKE_VERSION(1, 0, 0);
  std::strcpy(props->runtimeName, "sketchsurf test runtime");
  return XR_SUCCESS;
}

XR_FN(PollEvent)(XrInstance, XrEventDataBuffer* event) {
  auto& events = rt().events;
  if (events.empty()) return XR_EVENT_UNAVAILABLE;
  *event = events.front();
  events.erase(events.begin());
  if (event->type == XR_TYPE_EVENT_DATA_SESSION_STATE_CHANGED)
    rt().state = reinterpret_cast<XrEventDataSessionStateChanged*>(event)->state;
  return XR_SUCCESS;
}

XR_FN(ResultToString)(XrInstance, XrResult value, char buffer[XR_MAX_RESULT_STRING_SIZE]) {
  std::snprintf(buffer, XR_MAX_RESULT_STRING_SIZE, "XR_RESULT_%d", int(value));
  return XR_SUCCESS;
}

XR_FN(StructureTypeToString)(XrInstance, XrStructureType value, char buffer[XR_MAX_STRUCTURE_NAME_SIZE]) {
  std::snprintf(buffer, XR_MAX_STRUCTURE_NAME_SIZE, "XR_STRUCTURE_TYPE_%d", int(value));
  return XR_SUCCESS;
}

constexpr XrSystemId kSystem = 1;

XR_FN(GetSystem)(XrInstance, const XrSystemGetInfo* info, XrSystemId* system) {
  if (info->formFactor != XR_FORM_FACTOR_HEAD_MOUNTED_DISPLAY || rt().no_hmd)
    return XR_ERROR_FORM_FACTOR_UNAVAILABLE;
  *system = kSystem;
  return XR_SUCCESS;
}

XR_FN(GetSystemProperties)(XrInstance, XrSystemId system, XrSystemProperties* props) {
  if (system != kSystem) return XR_ERROR_SYSTEM_INVALID;
  props->systemId = kSystem;
  props->vendorId = 0;
  std::strcpy(props->systemName, "sketchsurf test headset");
  props->graphicsProperties = {rt().width, rt().height, 1};
  props->trackingProperties = {XR_TRUE, XR_TRUE};
  return XR_SUCCESS;
}

XR_FN(EnumerateEnvironmentBlendModes)
(XrInstance, XrSystemId, XrViewConfigurationType, uint32_t capacity, uint32_t* count,
 XrEnvironmentBlendMode* modes) {
  *count = 1;
  if (capacity >= 1) modes[0] = XR_ENVIRONMENT_BLEND_MODE_OPAQUE;
  return XR_SUCCESS;
}

XR_FN(EnumerateViewConfigurations)
(XrInstance, XrSystemId, uint32_t capacity, uint32_t* count, XrViewConfigurationType* types) {
  *count = 1;
  if (capacity >= 1) types[0] = XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO;
  return XR_SUCCESS;
}

XR_FN(GetViewConfigurationProperties)
(XrInstance, XrSystemId, XrViewConfigurationType type, XrViewConfigurationProperties* props) {
  if (type != XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO) return XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED;
  props->viewConfigurationType = type;
  props->fovMutable = XR_FALSE;
  return XR_SUCCESS;
}

XR_FN(EnumerateViewConfigurationViews)
(XrInstance, XrSystemId, XrViewConfigurationType type, uint32_t capacity, uint32_t* count,
 XrViewConfigurationView* views) {
  if (type != XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO) return XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED;
  *count = 2;
  if (capacity == 0) return XR_SUCCESS;
  if (capacity < 2) return XR_ERROR_SIZE_INSUFFICIENT;
  for (int i = 0; i < 2; ++i) {
    views[i].recommendedImageRectWidth = rt().width;
    views[i].recommendedImageRectHeight = rt().height;
    views[i].maxImageRectWidth = 4096;
    views[i].maxImageRectHeight = 4096;
    views[i].recommendedSwapchainSampleCount = 1;
    views[i].maxSwapchainSampleCount = 1;
  }
  return XR_SUCCESS;
}

// XR_KHR_vulkan_enable2.
XR_FN(GetVulkanGraphicsRequirements2KHR)(XrInstance, XrSystemId, XrGraphicsRequirementsVulkanKHR* req) {
  req->minApiVersionSupported = XR_MAKE_VERSION(1, 0, 0);
  req->maxApiVersionSupported = XR_MAKE_VERSION(1, 3, 0);
  return XR_SUCCESS;
}

XR_FN(CreateVulkanInstanceKHR)
(XrInstance, const XrVulkanInstanceCreateInfoKHR* info, VkInstance* instance, VkResult* result) {
  rt().gipa = info->pfnGetInstanceProcAddr;
  const auto create = reinterpret_cast<PFN_vkCreateInstance>(rt().gipa(VK_NULL_HANDLE, "vkCreateInstance"));
  *result = create(info->vulkanCreateInfo, info->vulkanAllocator, instance);
  if (*result == VK_SUCCESS) rt().vk_instance = *instance;
  return XR_SUCCESS;
}

XR_FN(GetVulkanGraphicsDevice2KHR)
(XrInstance, const XrVulkanGraphicsDeviceGetInfoKHR* info, VkPhysicalDevice* device) {
  rt().vk_instance = info->vulkanInstance;
  const auto enumerate = instance_function<PFN_vkEnumeratePhysicalDevices>("vkEnumeratePhysicalDevices");
  std::uint32_t count = 0;
  enumerate(info->vulkanInstance, &count, nullptr);
  if (count == 0) return XR_ERROR_RUNTIME_FAILURE;
  std::vector<VkPhysicalDevice> devices(count);
  enumerate(info->vulkanInstance, &count, devices.data());
  *device = devices[0];
  return XR_SUCCESS;
}

XR_FN(CreateVulkanDeviceKHR)
(XrInstance, const XrVulkanDeviceCreateInfoKHR* info, VkDevice* device, VkResult* result) {
  const auto create = instance_function<PFN_vkCreateDevice>("vkCreateDevice");
  *result = create(info->vulkanPhysicalDevice, info->vulkanCreateInfo, info->vulkanAllocator, device);
  return XR_SUCCESS;
}

XR_FN(CreateSession)(XrInstance, const XrSessionCreateInfo* info, XrSession* session) {
  if (rt().session) return XR_ERROR_LIMIT_REACHED;
  const auto* binding = static_cast<const XrGraphicsBindingVulkan2KHR*>(info->next);
  if (!binding || binding->type != XR_TYPE_GRAPHICS_BINDING_VULKAN2_KHR)
    return XR_ERROR_GRAPHICS_DEVICE_INVALID;
  rt().physical = binding->physicalDevice;
  rt().device = binding->device;
  rt().queue_family = binding->queueFamilyIndex;
  vkGetDeviceQueue(binding->device, binding->queueFamilyIndex, binding->queueIndex, &rt().queue);
  rt().session = true;
  for (auto s : {XR_SESSION_STATE_IDLE, XR_SESSION_STATE_READY}) {
    push_state(s);
    rt().states.push_back(s);
  }
  *session = reinterpret_cast<XrSession>(&rt());
  return XR_SUCCESS;
}

XR_FN(DestroySession)(XrSession) {
  rt().session = false;
  rt().session_destroyed = true;
  return XR_SUCCESS;
}

XR_FN(BeginSession)(XrSession, const XrSessionBeginInfo* info) {
  if (rt().state != XR_SESSION_STATE_READY) return XR_ERROR_SESSION_NOT_READY;
  if (info->primaryViewConfigurationType != XR_VIEW_CONFIGURATION_TYPE_PRIMARY_STEREO)
    return XR_ERROR_VIEW_CONFIGURATION_TYPE_UNSUPPORTED;
  rt().running = true;
  for (auto s : {XR_SESSION_STATE_SYNCHRONIZED, XR_SESSION_STATE_VISIBLE, XR_SESSION_STATE_FOCUSED}) {
    push_state(s);
    rt().states.push_back(s);
  }
  return XR_SUCCESS;
}

/// FOCUSED -> VISIBLE -> SYNCHRONIZED -> STOPPING.
void stop() {
  for (auto s : {XR_SESSION_STATE_VISIBLE, XR_SESSION_STATE_SYNCHRONIZED, XR_SESSION_STATE_STOPPING}) {
    push_state(s);
    rt().states.push_back(s);
  }
}

XR_FN(EndSession)(XrSession) {
  if (rt().state != XR_SESSION_STATE_STOPPING) return XR_ERROR_SESSION_NOT_STOPPING;
  rt().running = false;
  rt().session_ended = true;
  for (auto s : {XR_SESSION_STATE_IDLE, XR_SESSION_STATE_EXITING}) {
    push_state(s);
    rt().states.push_back(s);
  }
  return XR_SUCCESS;
}

XR_FN(RequestExitSession)(XrSession) {
  if (!rt().running) return XR_ERROR_SESSION_NOT_RUNNING;
  if (!rt().exit_requested && !rt().stopped_by_runtime) stop();
  rt().exit_requested = true;
  return XR_SUCCESS;
}

XR_FN(EnumerateReferenceSpaces)(XrSession, uint32_t capacity, uint32_t* count, XrReferenceSpaceType* spaces) {
  *count = 3;
  if (capacity == 0) return XR_SUCCESS;
  if (capacity < 3) return XR_ERROR_SIZE_INSUFFICIENT;
  spaces[0] = XR_REFERENCE_SPACE_TYPE_VIEW;
  spaces[1] = XR_REFERENCE_SPACE_TYPE_LOCAL;
  spaces[2] = XR_REFERENCE_SPACE_TYPE_STAGE;
  return XR_SUCCESS;
}

XR_FN(CreateReferenceSpace)(XrSession, const XrReferenceSpaceCreateInfo* info, XrSpace* space) {
  auto* s = new Space;
  s->type = info->referenceSpaceType;
  s->offset = to_iso(info->poseInReferenceSpace);
  *space = give<XrSpace>(s);
  return XR_SUCCESS;
}

XR_FN(GetReferenceSpaceBoundsRect)(XrSession, XrReferenceSpaceType, XrExtent2Df* bounds) {
  *bounds = {2.0f, 2.0f};
  return XR_SUCCESS;
}

XR_FN(CreateActionSpace)(XrSession, const XrActionSpaceCreateInfo* info, XrSpace* space) {
  auto* action = as<Action>(info->action);
  if (!action) return XR_ERROR_HANDLE_INVALID;
  auto* s = new Space;
  s->reference = false;
  s->action = action;
  s->offset = to_iso(info->poseInActionSpace);
  *space = give<XrSpace>(s);
  return XR_SUCCESS;
}

XR_FN(LocateSpace)(XrSpace space, XrSpace base, XrTime time, XrSpaceLocation* location) {
  const Space* s = as<Space>(space);
  const Space* b = as<Space>(base);
  if (!s || !b) return XR_ERROR_HANDLE_INVALID;
  const auto ps = stage_pose(*s, time), pb = stage_pose(*b, time);
  location->locationFlags = 0;
  location->pose = {{0, 0, 0, 1}, {0, 0, 0}};
  if (ps && pb) {
    location->pose = to_pose(pb->inverse() * *ps);
    location->locationFlags = XR_SPACE_LOCATION_POSITION_VALID_BIT | XR_SPACE_LOCATION_ORIENTATION_VALID_BIT |
                              XR_SPACE_LOCATION_POSITION_TRACKED_BIT |
                              XR_SPACE_LOCATION_ORIENTATION_TRACKED_BIT;
  }
  return XR_SUCCESS;
}

XR_FN(DestroySpace)(XrSpace space) {
  Space* s = as<Space>(space);
  if (!s) return XR_ERROR_HANDLE_INVALID;
  rt().live.erase(s);
  delete s;
  return XR_SUCCESS;
}

XR_FN(EnumerateSwapchainFormats)(XrSession, uint32_t capacity, uint32_t* count, int64_t* formats) {
  const std::int64_t offered[] = {VK_FORMAT_R8G8B8A8_SRGB, VK_FORMAT_B8G8R8A8_SRGB, VK_FORMAT_R8G8B8A8_UNORM,
                                  VK_FORMAT_B8G8R8A8_UNORM};
  *count = 4;
  if (capacity == 0) return XR_SUCCESS;
  if (capacity < 4) return XR_ERROR_SIZE_INSUFFICIENT;
  std::copy(std::begin(offered), std::end(offered), formats);
  return XR_SUCCESS;
}

XR_FN(CreateSwapchain)(XrSession, const XrSwapchainCreateInfo* info, XrSwapchain* swapchain) {
  auto sc = std::make_unique<Swapchain>();
  sc->format = VkFormat(info->format);
  sc->width = info->width;
  sc->height = info->height;
  VkImageCreateInfo image_info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  image_info.flags =
      (info->usageFlags & XR_SWAPCHAIN_USAGE_MUTABLE_FORMAT_BIT) ? VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT : 0;
  image_info.imageType = VK_IMAGE_TYPE_2D;
  image_info.format = sc->format;
  image_info.extent = {info->width, info->height, 1};
  image_info.mipLevels = 1;
  image_info.arrayLayers = 1;
  image_info.samples = VK_SAMPLE_COUNT_1_BIT;
  image_info.tiling = VK_IMAGE_TILING_OPTIMAL;
  // Colour attachment for the application, transfer source for the runtime's readback.
  image_info.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  image_info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  for (int i = 0; i < 3; ++i) {
    SwapImage img;
    if (vkCreateImage(rt().device, &image_info, nullptr, &img.image) != VK_SUCCESS)
      return XR_ERROR_RUNTIME_FAILURE;
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(rt().device, img.image, &req);
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    vkAllocateMemory(rt().device, &alloc, nullptr, &img.memory);
    vkBindImageMemory(rt().device, img.image, img.memory, 0);
    sc->images.push_back(img);
  }
  // The application receives every image in COLOR_ATTACHMENT_OPTIMAL.
  submit([&](VkCommandBuffer cmd) {
    for (const auto& img : sc->images)
      transition(cmd, img.image, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, 0,
                 VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT,
                 VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT);
  });
  *swapchain = give<XrSwapchain>(sc.release());
  return XR_SUCCESS;
}

XR_FN(DestroySwapchain)(XrSwapchain swapchain) {
  Swapchain* sc = as<Swapchain>(swapchain);
  if (!sc) return XR_ERROR_HANDLE_INVALID;
  vkQueueWaitIdle(rt().queue);
  for (const auto& img : sc->images) {
    vkDestroyImage(rt().device, img.image, nullptr);
    vkFreeMemory(rt().device, img.memory, nullptr);
  }
  rt().live.erase(sc);
  delete sc;
  return XR_SUCCESS;
}

XR_FN(EnumerateSwapchainImages)
(XrSwapchain swapchain, uint32_t capacity, uint32_t* count, XrSwapchainImageBaseHeader* images) {
  Swapchain* sc = as<Swapchain>(swapchain);
  if (!sc) return XR_ERROR_HANDLE_INVALID;
  *count = std::uint32_t(sc->images.size());
  if (capacity == 0) return XR_SUCCESS;
  if (capacity < *count) return XR_ERROR_SIZE_INSUFFICIENT;
  auto* out = reinterpret_cast<XrSwapchainImageVulkan2KHR*>(images);
  for (std::uint32_t i = 0; i < *count; ++i) out[i].image = sc->images[i].image;
  return XR_SUCCESS;
}

XR_FN(AcquireSwapchainImage)(XrSwapchain swapchain, const XrSwapchainImageAcquireInfo*, uint32_t* index) {
  Swapchain* sc = as<Swapchain>(swapchain);
  if (!sc) return XR_ERROR_HANDLE_INVALID;
  if (sc->acquired.size() >= sc->images.size()) {
    rt().errors.push_back("xrAcquireSwapchainImage: every image is acquired");
    return XR_ERROR_CALL_ORDER_INVALID;
  }
  *index = sc->next;
  sc->acquired.push_back(sc->next);
  sc->next = (sc->next + 1) % std::uint32_t(sc->images.size());
  return XR_SUCCESS;
}

XR_FN(WaitSwapchainImage)(XrSwapchain swapchain, const XrSwapchainImageWaitInfo*) {
  Swapchain* sc = as<Swapchain>(swapchain);
  if (!sc) return XR_ERROR_HANDLE_INVALID;
  if (sc->acquired.empty()) {
    rt().errors.push_back("xrWaitSwapchainImage: no image acquired");
    return XR_ERROR_CALL_ORDER_INVALID;
  }
  sc->waited = true;
  return XR_SUCCESS;
}

XR_FN(ReleaseSwapchainImage)(XrSwapchain swapchain, const XrSwapchainImageReleaseInfo*) {
  Swapchain* sc = as<Swapchain>(swapchain);
  if (!sc) return XR_ERROR_HANDLE_INVALID;
  if (sc->acquired.empty() || !sc->waited) {
    rt().errors.push_back("xrReleaseSwapchainImage: no image waited for");
    return XR_ERROR_CALL_ORDER_INVALID;
  }
  sc->released = sc->acquired.front();
  sc->acquired.erase(sc->acquired.begin());
  sc->waited = false;
  return XR_SUCCESS;
}

XR_FN(WaitFrame)(XrSession, const XrFrameWaitInfo*, XrFrameState* state) {
  if (!rt().running) return XR_ERROR_SESSION_NOT_RUNNING;
  ++rt().frames_waited;
  rt().display_time = kStart + rt().frames_waited * kPeriod;
  state->predictedDisplayTime = rt().display_time;
  state->predictedDisplayPeriod = kPeriod;
  state->shouldRender = rt().state == XR_SESSION_STATE_VISIBLE || rt().state == XR_SESSION_STATE_FOCUSED;
  return XR_SUCCESS;
}

XR_FN(BeginFrame)(XrSession, const XrFrameBeginInfo*) {
  return rt().running ? XR_SUCCESS : XR_ERROR_SESSION_NOT_RUNNING;
}

XR_FN(EndFrame)(XrSession, const XrFrameEndInfo* info) {
  if (!rt().running) return XR_ERROR_SESSION_NOT_RUNNING;
  ++rt().frames_ended;
  std::vector<const Swapchain*> eyes;
  for (std::uint32_t i = 0; i < info->layerCount; ++i) {
    if (info->layers[i]->type != XR_TYPE_COMPOSITION_LAYER_PROJECTION) continue;
    const auto* layer = reinterpret_cast<const XrCompositionLayerProjection*>(info->layers[i]);
    for (std::uint32_t v = 0; v < layer->viewCount; ++v)
      if (const Swapchain* sc = as<Swapchain>(layer->views[v].subImage.swapchain); sc && sc->released)
        eyes.push_back(sc);
  }
  if (eyes.size() == 2) ++rt().frames_with_layers;
  if (rt().frames_ended == rt().stop_frame && !rt().exit_requested) {
    if (!rt().out.empty())
      for (std::size_t e = 0; e < eyes.size(); ++e)
        write_image(*eyes[e], rt().out / ("eye_" + std::to_string(e) + ".ppm"));
    rt().stopped_by_runtime = true;
    stop();
  }
  return XR_SUCCESS;
}

XR_FN(LocateViews)
(XrSession, const XrViewLocateInfo* info, XrViewState* state, uint32_t capacity, uint32_t* count,
 XrView* views) {
  *count = 2;
  if (capacity == 0) return XR_SUCCESS;
  if (capacity < 2) return XR_ERROR_SIZE_INSUFFICIENT;
  const Space* base = as<Space>(info->space);
  if (!base) return XR_ERROR_HANDLE_INVALID;
  const auto pb = stage_pose(*base, info->displayTime);
  state->viewStateFlags = XR_VIEW_STATE_POSITION_VALID_BIT | XR_VIEW_STATE_ORIENTATION_VALID_BIT |
                          XR_VIEW_STATE_POSITION_TRACKED_BIT | XR_VIEW_STATE_ORIENTATION_TRACKED_BIT;
  // A head at 1.6 m looking down -z, eyes 64 mm apart, each with an asymmetric field of view
  // wider on its outer side (as a real headset's).
  for (int e = 0; e < 2; ++e) {
    Eigen::Isometry3d eye = Eigen::Isometry3d::Identity();
    eye.translation() = Eigen::Vector3d(e == 0 ? -0.032 : 0.032, 1.6, 0.0);
    views[e].pose = to_pose(pb->inverse() * eye);
    views[e].fov = e == 0 ? XrFovf{-0.80f, 0.70f, 0.72f, -0.78f} : XrFovf{-0.70f, 0.80f, 0.72f, -0.78f};
  }
  return XR_SUCCESS;
}

XR_FN(StringToPath)(XrInstance, const char* text, XrPath* path) {
  auto& paths = rt().paths;
  const auto it = std::find(paths.begin(), paths.end(), text);
  if (it != paths.end()) {
    *path = XrPath(it - paths.begin() + 1);
  } else {
    paths.emplace_back(text);
    *path = XrPath(paths.size());
  }
  return XR_SUCCESS;
}

XR_FN(PathToString)(XrInstance, XrPath path, uint32_t capacity, uint32_t* count, char* buffer) {
  if (path == XR_NULL_PATH || path > rt().paths.size()) return XR_ERROR_PATH_INVALID;
  const std::string& text = rt().paths[path - 1];
  *count = std::uint32_t(text.size() + 1);
  if (capacity == 0) return XR_SUCCESS;
  if (capacity < *count) return XR_ERROR_SIZE_INSUFFICIENT;
  std::memcpy(buffer, text.c_str(), text.size() + 1);
  return XR_SUCCESS;
}

XR_FN(CreateActionSet)(XrInstance, const XrActionSetCreateInfo* info, XrActionSet* set) {
  auto* s = new ActionSet;
  s->name = info->actionSetName;
  *set = give<XrActionSet>(s);
  return XR_SUCCESS;
}

XR_FN(DestroyActionSet)(XrActionSet set) {
  ActionSet* s = as<ActionSet>(set);
  if (!s) return XR_ERROR_HANDLE_INVALID;
  for (auto& [profile, list] : rt().bindings)
    list.erase(std::remove_if(list.begin(), list.end(), [&](const auto& b) { return b.first->set == s; }),
               list.end());
  for (Action* a : s->actions) {
    rt().live.erase(a);
    delete a;
  }
  rt().live.erase(s);
  delete s;
  return XR_SUCCESS;
}

XR_FN(CreateAction)(XrActionSet set, const XrActionCreateInfo* info, XrAction* action) {
  ActionSet* s = as<ActionSet>(set);
  if (!s) return XR_ERROR_HANDLE_INVALID;
  if (s->attached) return XR_ERROR_ACTIONSETS_ALREADY_ATTACHED;
  auto* a = new Action;
  a->set = s;
  a->name = info->actionName;
  a->type = info->actionType;
  s->actions.push_back(a);
  *action = give<XrAction>(a);
  return XR_SUCCESS;
}

XR_FN(DestroyAction)(XrAction) { return XR_SUCCESS; }  // freed with its set

/// The text of `path`; empty when it is not one of ours.
std::string path_text(XrPath path) {
  return path == XR_NULL_PATH || path > rt().paths.size() ? std::string() : rt().paths[path - 1];
}

XR_FN(SuggestInteractionProfileBindings)(XrInstance, const XrInteractionProfileSuggestedBinding* info) {
  const std::string profile = path_text(info->interactionProfile);
  if (profile.empty()) return XR_ERROR_PATH_INVALID;
  std::vector<std::pair<Action*, std::string>> list;
  for (std::uint32_t i = 0; i < info->countSuggestedBindings; ++i) {
    Action* a = as<Action>(info->suggestedBindings[i].action);
    const std::string path = path_text(info->suggestedBindings[i].binding);
    if (!a) return XR_ERROR_HANDLE_INVALID;
    if (path.empty()) return XR_ERROR_PATH_INVALID;
    list.emplace_back(a, path);
  }
  rt().bindings[profile] = std::move(list);
  return XR_SUCCESS;
}

XR_FN(AttachSessionActionSets)(XrSession, const XrSessionActionSetsAttachInfo* info) {
  for (std::uint32_t i = 0; i < info->countActionSets; ++i) {
    ActionSet* s = as<ActionSet>(info->actionSets[i]);
    if (!s) return XR_ERROR_HANDLE_INVALID;
    if (s->attached) return XR_ERROR_ACTIONSETS_ALREADY_ATTACHED;
    s->attached = true;
  }
  // The controller is bound once the application suggested bindings for it.
  rt().profile_bound = rt().bindings.count(rt().profile) > 0;
  if (rt().profile_bound) {
    XrEventDataBuffer buffer{XR_TYPE_EVENT_DATA_BUFFER};
    auto& e = reinterpret_cast<XrEventDataInteractionProfileChanged&>(buffer);
    e.type = XR_TYPE_EVENT_DATA_INTERACTION_PROFILE_CHANGED;
    e.next = nullptr;
    e.session = reinterpret_cast<XrSession>(&rt());
    rt().events.push_back(buffer);
  }
  return XR_SUCCESS;
}

XR_FN(GetCurrentInteractionProfile)(XrSession, XrPath top, XrInteractionProfileState* state) {
  state->interactionProfile = XR_NULL_PATH;
  if (rt().profile_bound && path_text(top) == "/user/hand/right") {
    XrPath p = XR_NULL_PATH;
    StringToPath(XR_NULL_HANDLE, rt().profile.c_str(), &p);
    state->interactionProfile = p;
  }
  return XR_SUCCESS;
}

/// The action's value now: the largest of its bound inputs (a boolean input reads 0 or 1); none
/// when it is inactive.
std::optional<float> action_value(const Action* action) {
  if (!focused()) return std::nullopt;
  const auto s = sample_at(rt().display_time);
  std::optional<float> value;
  for (const auto& path : bound_paths(action))
    if (const auto v = input_value(path, s ? *s : ControllerState{}))
      value = std::max(value.value_or(0.0f), *v);
  return value;
}

XR_FN(SyncActions)(XrSession, const XrActionsSyncInfo* info) {
  for (std::uint32_t i = 0; i < info->countActiveActionSets; ++i) {
    ActionSet* s = as<ActionSet>(info->activeActionSets[i].actionSet);
    if (!s) return XR_ERROR_HANDLE_INVALID;
    if (!s->attached) return XR_ERROR_ACTIONSET_NOT_ATTACHED;
    for (Action* a : s->actions) {
      const float v = action_value(a).value_or(0.0f);
      a->changed_since_sync = v != a->last;
      if (a->changed_since_sync) a->changed = rt().display_time;
      a->last = v;
    }
  }
  return focused() ? XR_SUCCESS : XR_SESSION_NOT_FOCUSED;
}

XR_FN(GetActionStateBoolean)(XrSession, const XrActionStateGetInfo* info, XrActionStateBoolean* state) {
  const Action* a = as<Action>(info->action);
  if (!a) return XR_ERROR_HANDLE_INVALID;
  if (a->type != XR_ACTION_TYPE_BOOLEAN_INPUT) return XR_ERROR_ACTION_TYPE_MISMATCH;
  state->isActive = action_value(a) ? XR_TRUE : XR_FALSE;
  state->currentState = a->last > 0.5f ? XR_TRUE : XR_FALSE;
  state->changedSinceLastSync = a->changed_since_sync ? XR_TRUE : XR_FALSE;
  state->lastChangeTime = a->changed;
  return XR_SUCCESS;
}

XR_FN(GetActionStateFloat)(XrSession, const XrActionStateGetInfo* info, XrActionStateFloat* state) {
  const Action* a = as<Action>(info->action);
  if (!a) return XR_ERROR_HANDLE_INVALID;
  if (a->type != XR_ACTION_TYPE_FLOAT_INPUT) return XR_ERROR_ACTION_TYPE_MISMATCH;
  state->isActive = action_value(a) ? XR_TRUE : XR_FALSE;
  state->currentState = a->last;
  state->changedSinceLastSync = a->changed_since_sync ? XR_TRUE : XR_FALSE;
  state->lastChangeTime = a->changed;
  return XR_SUCCESS;
}

XR_FN(GetActionStateVector2f)(XrSession, const XrActionStateGetInfo*, XrActionStateVector2f* state) {
  state->isActive = XR_FALSE;
  state->currentState = {0.0f, 0.0f};
  state->changedSinceLastSync = XR_FALSE;
  state->lastChangeTime = 0;
  return XR_SUCCESS;
}

XR_FN(GetActionStatePose)(XrSession, const XrActionStateGetInfo* info, XrActionStatePose* state) {
  const Action* a = as<Action>(info->action);
  if (!a) return XR_ERROR_HANDLE_INVALID;
  if (a->type != XR_ACTION_TYPE_POSE_INPUT) return XR_ERROR_ACTION_TYPE_MISMATCH;
  bool bound = false;
  for (const auto& p : bound_paths(a)) bound = bound || is_pose_input(p);
  state->isActive = bound && focused() ? XR_TRUE : XR_FALSE;
  return XR_SUCCESS;
}

XR_FN(EnumerateBoundSourcesForAction)
(XrSession, const XrBoundSourcesForActionEnumerateInfo*, uint32_t, uint32_t* count, XrPath*) {
  *count = 0;
  return XR_SUCCESS;
}

XR_FN(GetInputSourceLocalizedName)
(XrSession, const XrInputSourceLocalizedNameGetInfo*, uint32_t capacity, uint32_t* count, char* buffer) {
  *count = 1;
  if (capacity >= 1) buffer[0] = '\0';
  return XR_SUCCESS;
}

XR_FN(ApplyHapticFeedback)(XrSession, const XrHapticActionInfo* info, const XrHapticBaseHeader* haptic) {
  const Action* a = as<Action>(info->action);
  if (!a) return XR_ERROR_HANDLE_INVALID;
  if (a->type != XR_ACTION_TYPE_VIBRATION_OUTPUT) return XR_ERROR_ACTION_TYPE_MISMATCH;
  if (haptic->type != XR_TYPE_HAPTIC_VIBRATION) return XR_ERROR_VALIDATION_FAILURE;
  ++rt().haptics;
  rt().haptic_times.push_back(double(rt().display_time - kStart - kPeriod) * 1e-9);
  return XR_SUCCESS;
}

XR_FN(StopHapticFeedback)(XrSession, const XrHapticActionInfo*) { return XR_SUCCESS; }

XR_FN(GetInstanceProcAddr)(XrInstance instance, const char* name, PFN_xrVoidFunction* function);

/// Every function of the runtime, by name.
const std::map<std::string, PFN_xrVoidFunction>& functions() {
#define SKETCHSURF_XR_ENTRY(name) \
  { "xr" #name, reinterpret_cast<PFN_xrVoidFunction>(&name) }
  static const std::map<std::string, PFN_xrVoidFunction> table = {
      SKETCHSURF_XR_ENTRY(GetInstanceProcAddr),
      SKETCHSURF_XR_ENTRY(EnumerateApiLayerProperties),
      SKETCHSURF_XR_ENTRY(EnumerateInstanceExtensionProperties),
      SKETCHSURF_XR_ENTRY(CreateInstance),
      SKETCHSURF_XR_ENTRY(DestroyInstance),
      SKETCHSURF_XR_ENTRY(GetInstanceProperties),
      SKETCHSURF_XR_ENTRY(PollEvent),
      SKETCHSURF_XR_ENTRY(ResultToString),
      SKETCHSURF_XR_ENTRY(StructureTypeToString),
      SKETCHSURF_XR_ENTRY(GetSystem),
      SKETCHSURF_XR_ENTRY(GetSystemProperties),
      SKETCHSURF_XR_ENTRY(EnumerateEnvironmentBlendModes),
      SKETCHSURF_XR_ENTRY(CreateSession),
      SKETCHSURF_XR_ENTRY(DestroySession),
      SKETCHSURF_XR_ENTRY(EnumerateReferenceSpaces),
      SKETCHSURF_XR_ENTRY(CreateReferenceSpace),
      SKETCHSURF_XR_ENTRY(GetReferenceSpaceBoundsRect),
      SKETCHSURF_XR_ENTRY(CreateActionSpace),
      SKETCHSURF_XR_ENTRY(LocateSpace),
      SKETCHSURF_XR_ENTRY(DestroySpace),
      SKETCHSURF_XR_ENTRY(EnumerateViewConfigurations),
      SKETCHSURF_XR_ENTRY(GetViewConfigurationProperties),
      SKETCHSURF_XR_ENTRY(EnumerateViewConfigurationViews),
      SKETCHSURF_XR_ENTRY(EnumerateSwapchainFormats),
      SKETCHSURF_XR_ENTRY(CreateSwapchain),
      SKETCHSURF_XR_ENTRY(DestroySwapchain),
      SKETCHSURF_XR_ENTRY(EnumerateSwapchainImages),
      SKETCHSURF_XR_ENTRY(AcquireSwapchainImage),
      SKETCHSURF_XR_ENTRY(WaitSwapchainImage),
      SKETCHSURF_XR_ENTRY(ReleaseSwapchainImage),
      SKETCHSURF_XR_ENTRY(BeginSession),
      SKETCHSURF_XR_ENTRY(EndSession),
      SKETCHSURF_XR_ENTRY(RequestExitSession),
      SKETCHSURF_XR_ENTRY(WaitFrame),
      SKETCHSURF_XR_ENTRY(BeginFrame),
      SKETCHSURF_XR_ENTRY(EndFrame),
      SKETCHSURF_XR_ENTRY(LocateViews),
      SKETCHSURF_XR_ENTRY(StringToPath),
      SKETCHSURF_XR_ENTRY(PathToString),
      SKETCHSURF_XR_ENTRY(CreateActionSet),
      SKETCHSURF_XR_ENTRY(DestroyActionSet),
      SKETCHSURF_XR_ENTRY(CreateAction),
      SKETCHSURF_XR_ENTRY(DestroyAction),
      SKETCHSURF_XR_ENTRY(SuggestInteractionProfileBindings),
      SKETCHSURF_XR_ENTRY(AttachSessionActionSets),
      SKETCHSURF_XR_ENTRY(GetCurrentInteractionProfile),
      SKETCHSURF_XR_ENTRY(GetActionStateBoolean),
      SKETCHSURF_XR_ENTRY(GetActionStateFloat),
      SKETCHSURF_XR_ENTRY(GetActionStateVector2f),
      SKETCHSURF_XR_ENTRY(GetActionStatePose),
      SKETCHSURF_XR_ENTRY(SyncActions),
      SKETCHSURF_XR_ENTRY(EnumerateBoundSourcesForAction),
      SKETCHSURF_XR_ENTRY(GetInputSourceLocalizedName),
      SKETCHSURF_XR_ENTRY(ApplyHapticFeedback),
      SKETCHSURF_XR_ENTRY(StopHapticFeedback),
      SKETCHSURF_XR_ENTRY(GetVulkanGraphicsRequirements2KHR),
      SKETCHSURF_XR_ENTRY(CreateVulkanInstanceKHR),
      SKETCHSURF_XR_ENTRY(GetVulkanGraphicsDevice2KHR),
      SKETCHSURF_XR_ENTRY(CreateVulkanDeviceKHR),
  };
#undef SKETCHSURF_XR_ENTRY
  return table;
}

XR_FN(GetInstanceProcAddr)(XrInstance instance, const char* name, PFN_xrVoidFunction* function) {
  const auto& table = functions();
  const auto it = table.find(name);
  *function = nullptr;
  if (it == table.end()) return XR_ERROR_FUNCTION_UNSUPPORTED;
  // Before an instance exists only the functions that create one may be asked for.
  const bool global = std::strcmp(name, "xrEnumerateInstanceExtensionProperties") == 0 ||
                      std::strcmp(name, "xrEnumerateApiLayerProperties") == 0 ||
                      std::strcmp(name, "xrCreateInstance") == 0;
  if (instance == XR_NULL_HANDLE && !global) return XR_ERROR_HANDLE_INVALID;
  *function = it->second;
  return XR_SUCCESS;
}

}  // namespace

extern "C" __attribute__((visibility("default"))) XrResult xrNegotiateLoaderRuntimeInterface(
    const XrNegotiateLoaderInfo* info, XrNegotiateRuntimeRequest* request) {
  if (!info || !request || info->structType != XR_LOADER_INTERFACE_STRUCT_LOADER_INFO ||
      request->structType != XR_LOADER_INTERFACE_STRUCT_RUNTIME_REQUEST || info->minInterfaceVersion > 1 ||
      info->maxInterfaceVersion < 1)
    return XR_ERROR_INITIALIZATION_FAILED;
  request->runtimeInterfaceVersion = 1;
  request->runtimeApiVersion = XR_CURRENT_API_VERSION;
  request->getInstanceProcAddr = &GetInstanceProcAddr;
  return XR_SUCCESS;
}
