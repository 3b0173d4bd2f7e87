#pragma once
// Upper bounds on what the readers accept. A corrupt or hostile file (gigabytes of NUL bytes, a
// device such as /dev/zero, a zip bomb) is refused with a message before memory is taken for it.
// The defaults are far above any real sketch or mesh (the largest sketches seen are under 1 MB);
// each bound can be raised with an environment variable, named in the refusal.

#include <cstdint>
#include <filesystem>

namespace sketchsurf {

/// What a reader accepts at most.
struct InputLimits {
  std::uint64_t file_bytes = 256ull << 20;  ///< an input file, and a .tilt's inflated zip entry
                                            ///< (SKETCHSURF_MAX_INPUT_MB, in MiB)
  std::uint64_t line_bytes = 4ull << 20;    ///< one line of a text format
                                            ///< (SKETCHSURF_MAX_LINE_KB, in KiB)

  /// The defaults, with SKETCHSURF_MAX_INPUT_MB and SKETCHSURF_MAX_LINE_KB applied when set to a
  /// positive whole number (other values are ignored).
  static InputLimits from_environment();
};

/// Checks that `file` can be read as a whole: it exists, is a regular file (not a FIFO, a device
/// or a directory; symbolic links are followed) and is at most `limits.file_bytes` long.
/// Returns its size. Throws Error (Input) naming the file and, for the size, how to raise it.
std::uint64_t check_input_file(const std::filesystem::path& file, const InputLimits& limits);

}  // namespace sketchsurf
