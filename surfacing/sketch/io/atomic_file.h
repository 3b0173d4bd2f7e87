#pragma once
// Writing a file so that a failure never leaves a partial or clobbered file behind.

#include <filesystem>
#include <functional>
#include <ostream>

namespace sketchsurf {

/// Calls `write` on a stream to a temporary file next to `file`, flushes and closes it, then
/// renames it over `file`. On any failure (exception from `write`, stream error, rename error)
/// the temporary file is removed and `file` is untouched. Stream, close and rename failures throw
/// Error (Processing); whatever `write` throws passes through unchanged.
void write_atomically(const std::filesystem::path& file,
                      const std::function<void(std::ostream&)>& write);

}  // namespace sketchsurf
