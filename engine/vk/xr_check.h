#pragma once
// XR_CHECK: turns a failed OpenXR call into an XrError (a sketchsurf::Error of kind Processing)
// naming the call, the XrResult and where it happened, as VK_CHECK does for Vulkan; the names of
// OpenXR's results and session states.

#include <openxr/openxr.h>

#include <string>

#include "surfacing/error.h"

namespace sketchsurf::vk {

/// The enumerator name of an XrResult ("XR_ERROR_SESSION_LOST"), or "XrResult(N)".
std::string xr_result_name(XrResult result);

/// The session state without its prefix: "IDLE", "READY", "FOCUSED", ...
std::string xr_state_name(XrSessionState state);

/// A failed OpenXR call.
class XrError : public Error {
 public:
  XrError(XrResult result, const std::string& message)
      : Error(ErrorKind::Processing, message), result_(result) {}
  XrResult result() const { return result_; }

 private:
  XrResult result_;
};

/// Throws XrError "CALL failed: RESULT (FILE:LINE)". Used by XR_CHECK.
[[noreturn]] void throw_xr_error(XrResult result, const char* call, const char* file, int line);

}  // namespace sketchsurf::vk

/// Evaluates an OpenXR call once; throws sketchsurf::vk::XrError when it fails (XR_FAILED).
/// Success codes other than XR_SUCCESS (XR_SESSION_LOSS_PENDING, XR_FRAME_DISCARDED, ...) pass.
#define XR_CHECK(call)                                                               \
  do {                                                                               \
    const XrResult xr_check_result_ = (call);                                        \
    if (XR_FAILED(xr_check_result_))                                                 \
      ::sketchsurf::vk::throw_xr_error(xr_check_result_, #call, __FILE__, __LINE__); \
  } while (0)
