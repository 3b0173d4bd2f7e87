#pragma once
// Writing files so that a failure never leaves a partial or clobbered file behind, alone
// (write_atomically) or as the outputs of one run that are committed together (StagedFiles).
//
// Temporary files are named FILE.tmp-PID-TAG, next to FILE. One left behind by a process that
// was killed (SIGKILL, power loss) is removed by the next write to FILE, once no process with
// that id runs.

#include <filesystem>
#include <functional>
#include <ostream>
#include <utility>
#include <vector>

namespace sketchsurf {

/// Calls `write` on a stream to a temporary file next to `file`, flushes and closes it, then
/// renames it over `file`. On any failure (exception from `write`, stream error, rename error)
/// the temporary file is removed and `file` is untouched. Stream, close and rename failures throw
/// Error (Processing) naming the file; an Error thrown by `write` gets "FILE: " in front of its
/// message; any other exception passes through unchanged.
void write_atomically(const std::filesystem::path& file,
                      const std::function<void(std::ostream&)>& write);

/// The outputs of one run, committed together or not at all. Each output is written under a
/// temporary name next to it (same directory, so the final rename stays on one file system; same
/// extension, so writers that choose the format by extension still do); commit() renames them
/// all over their final names. Destroyed before commit(), it removes every temporary file, so a
/// run that fails or is cancelled changes no output.
class StagedFiles {
 public:
  StagedFiles() = default;
  StagedFiles(const StagedFiles&) = delete;
  StagedFiles& operator=(const StagedFiles&) = delete;
  ~StagedFiles();

  /// Calls `write` with the temporary path that stands for `file`. An Error it throws has the
  /// temporary name in its message replaced by `file`; nothing is left under that name then.
  void write(const std::filesystem::path& file,
             const std::function<void(const std::filesystem::path&)>& write);

  /// Renames every written file over its final name, in the order written. Throws Error
  /// (Processing) naming the file when a rename fails; the files not renamed yet are removed.
  void commit();

 private:
  std::vector<std::pair<std::filesystem::path, std::filesystem::path>> staged_;  // temporary, final
};

}  // namespace sketchsurf
