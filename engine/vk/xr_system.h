#pragma once
// The headset's OpenXR system: the instance (with XR_KHR_vulkan_enable2), the head-mounted
// display and its stereo view configuration, and the Vulkan context made through the runtime (it
// creates the instance and the device and names the physical device the headset is wired to).

#include <vulkan/vulkan.h>
// openxr_platform.h needs the Vulkan types first.
#define XR_USE_GRAPHICS_API_VULKAN
#include <openxr/openxr.h>
#include <openxr/openxr_platform.h>

#include <array>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "engine/vk/context.h"
#include "surfacing/error.h"

namespace sketchsurf::vk {

/// No headset to use: no OpenXR runtime, a runtime that cannot start, no head-mounted display or
/// no Vulkan support in the runtime. what() is one line naming what is missing.
class XrUnavailable : public Error {
 public:
  explicit XrUnavailable(const std::string& message) : Error(ErrorKind::Processing, message) {}
};

/// The runtime manifest the OpenXR loader would use: $XR_RUNTIME_JSON, else
/// openxr/1/active_runtime.json in $XDG_CONFIG_HOME (~/.config), the $XDG_CONFIG_DIRS
/// (/etc/xdg) and /etc. Empty when there is none; `why` then says where it looked.
std::optional<std::filesystem::path> find_runtime_manifest(std::string* why);

struct XrSystemOptions {
  std::string application = "sketchsurf";       ///< the application name the runtime shows
  std::function<void(const std::string&)> log;  ///< notable events, one line each; may be empty
};

class XrSystem {
 public:
  /// Throws XrUnavailable (no runtime, no headset, no Vulkan support), XrError (other failures).
  explicit XrSystem(const XrSystemOptions& options = {});
  ~XrSystem();
  XrSystem(const XrSystem&) = delete;
  XrSystem& operator=(const XrSystem&) = delete;

  XrInstance instance() const { return instance_; }
  XrSystemId system() const { return system_; }
  const std::string& runtime_name() const { return runtime_; }
  const std::string& system_name() const { return system_name_; }
  /// The recommended image size of each eye (left, right).
  const std::array<XrViewConfigurationView, 2>& eye_views() const { return eye_views_; }

  /// A Vulkan context whose instance, physical device and device the runtime makes (the
  /// extensions and layers of `options` are passed on to it). Throws XrError, Error.
  std::unique_ptr<Context> create_context(ContextOptions options) const;

  /// Looks up an OpenXR function of this instance; throws XrError when the runtime lacks it.
  template <class Function>
  Function function(const char* name) const {
    return reinterpret_cast<Function>(raw_function(name));
  }

 private:
  PFN_xrVoidFunction raw_function(const char* name) const;
  void log(const std::string& line) const;

  XrSystemOptions options_;
  XrInstance instance_ = XR_NULL_HANDLE;
  XrSystemId system_ = XR_NULL_SYSTEM_ID;
  std::string runtime_, system_name_;
  std::array<XrViewConfigurationView, 2> eye_views_{};
  XrVersion min_vulkan_ = 0;  ///< the oldest Vulkan the runtime works with
};

}  // namespace sketchsurf::vk
