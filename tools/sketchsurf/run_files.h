#pragma once
// What keeps a user's files safe across a command run: outputs checked before any work starts
// (extension, directory, never an input), written under temporary names and committed together
// at the end, and Ctrl-C (SIGINT, SIGTERM) turned into a clean cancellation (exit 130) that
// leaves no output changed and no temporary file behind.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "surfacing/sketch/io/atomic_file.h"

namespace sketchsurf::cli {

/// Whether SIGINT or SIGTERM was received since a RunFiles was made.
bool cancel_requested();

/// The inputs and outputs of one command run.
class RunFiles {
 public:
  /// Installs the SIGINT/SIGTERM handler: the first signal asks the run to stop
  /// (cancel_requested() turns true, the progress callbacks and commit() then throw
  /// Error(Cancelled)); a second one ends the process at once (its temporary files are removed
  /// by the next run). Commands that write nothing keep the default: Ctrl-C ends them at once.
  RunFiles();

  /// Notes a file the run reads, so that no output may be it.
  void input(const std::string& file);
  /// Checks an output before the work starts: its extension is one of `extensions` (any when
  /// empty), its directory exists and may be written, it is not a directory, not an input (the
  /// same file however named: links and relative paths are resolved) and not another output.
  /// `option` names it in the messages ("-o", "--report"). Throws Error (Usage) saying what to do.
  void output(const std::string& option, const std::string& file,
              const std::vector<std::string>& extensions = {});
  /// Writes an output under a temporary name (StagedFiles::write); it appears at commit().
  void write(const std::string& file, const std::function<void(const std::filesystem::path&)>& writer);
  /// Puts every output in place, unless the run was cancelled: then throws Error (Cancelled)
  /// and the temporary files are removed.
  void commit();

 private:
  std::vector<std::filesystem::path> inputs_;
  std::vector<std::filesystem::path> outputs_;
  StagedFiles staged_;
};

/// CLI11 check: a whole number in [lo, hi], said in words when it is not ("--restarts: expected a
/// whole number from 1 to 1000, got '0'").
CLI::Validator whole_number(std::uint64_t lo, std::uint64_t hi);
/// CLI11 check: a finite number > 0.
CLI::Validator positive_number();
/// CLI11 check: a finite number >= 0.
CLI::Validator non_negative_number();

/// The --param assignments "NAME=VALUE" (a dotted parameter name as Params::apply() takes it, a
/// finite number) as a map; throws Error (Usage) quoting the first one that is not of that form.
/// A name given twice keeps its last value.
std::map<std::string, double> parse_params(const std::vector<std::string>& assignments);

/// Largest --threads accepted (0 = all cores); more threads than this only cost memory.
constexpr std::uint64_t kMaxThreads = 1024;

}  // namespace sketchsurf::cli
