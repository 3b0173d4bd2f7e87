#include "engine/vk/xr_check.h"

#include <openxr/openxr_reflection.h>

namespace sketchsurf::vk {

std::string xr_result_name(XrResult result) {
  switch (result) {
#define SKETCHSURF_XR_RESULT_CASE(name, value) \
  case name:                                   \
    return #name;
    XR_LIST_ENUM_XrResult(SKETCHSURF_XR_RESULT_CASE)
#undef SKETCHSURF_XR_RESULT_CASE
            default : return "XrResult(" +
                      std::to_string(int(result)) + ")";
  }
}

std::string xr_state_name(XrSessionState state) {
  switch (state) {
#define SKETCHSURF_XR_STATE_CASE(name, value) \
  case name:                                  \
    return std::string(#name).substr(sizeof "XR_SESSION_STATE_" - 1);
    XR_LIST_ENUM_XrSessionState(SKETCHSURF_XR_STATE_CASE)
#undef SKETCHSURF_XR_STATE_CASE
            default : return "XrSessionState(" +
                      std::to_string(int(state)) + ")";
  }
}

void throw_xr_error(XrResult result, const char* call, const char* file, int line) {
  throw XrError(result, std::string(call) + " failed: " + xr_result_name(result) + " (" + file + ":" +
                            std::to_string(line) + ")");
}

}  // namespace sketchsurf::vk
