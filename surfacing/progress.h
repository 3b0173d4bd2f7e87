#pragma once
// Progress reporting and cancellation, shared by every long stage.

#include <functional>
#include <string_view>

#include "surfacing/error.h"

namespace sketchsurf {

/// Called with a stage name and a fraction in [0, 1]; returns false to ask the work to stop.
using ProgressCallback = std::function<bool(std::string_view stage, double fraction)>;

/// A stage's handle on the pipeline's callback. A default-constructed Progress reports nothing.
class Progress {
 public:
  Progress() = default;
  explicit Progress(ProgressCallback callback) : callback_(std::move(callback)) {}

  /// Reports progress; throws Error(Cancelled) when the callback asks to stop.
  void update(std::string_view stage, double fraction) const {
    if (callback_ && !callback_(stage, fraction))
      throw Error(ErrorKind::Cancelled, "cancelled during " + std::string(stage));
  }

 private:
  ProgressCallback callback_;
};

}  // namespace sketchsurf
