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
  std::uint64_t points = 10'000'000;        ///< points of one sketch, all strokes together
                                            ///< (SKETCHSURF_MAX_POINTS, a count)

  /// The defaults, with SKETCHSURF_MAX_INPUT_MB, SKETCHSURF_MAX_LINE_KB and SKETCHSURF_MAX_POINTS
  /// applied when set to a positive whole number (other values are ignored).
  static InputLimits from_environment();
};

/// Counts the points of one sketch as a reader takes them in. A file under the size limit can
/// still describe far more points than it holds bytes for (a .curves header `v 1000000000`, OBJ
/// `l` records that repeat one vertex): the reader asks before it allocates, and the sketch is
/// refused once it would hold more than InputLimits::points.
class PointBudget {
 public:
  /// The limit of InputLimits::from_environment(); `file` is named in the refusal.
  explicit PointBudget(const std::filesystem::path& file);

  /// Accounts for `count` more points. Throws Error (Input) naming the file, the limit and how
  /// to raise it when the total would pass the limit.
  void take(std::uint64_t count);
  /// Points taken so far.
  std::uint64_t taken() const { return taken_; }
  std::uint64_t limit() const { return limit_; }

 private:
  std::filesystem::path file_;
  std::uint64_t limit_;
  std::uint64_t taken_ = 0;
};

/// Checks that `file` can be read as a whole: it exists, is a regular file (not a FIFO, a device
/// or a directory; symbolic links are followed) and is at most `limits.file_bytes` long.
/// Returns its size. Throws Error (Input) naming the file and, for the size, how to raise it.
std::uint64_t check_input_file(const std::filesystem::path& file, const InputLimits& limits);

}  // namespace sketchsurf
