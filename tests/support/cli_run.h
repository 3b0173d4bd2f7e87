#pragma once
// Runs the sketchsurf executable from a CLI test (SKETCHSURF_CLI is set by sketchsurf_add_test).

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace sketchsurf::testing {

/// What a run of the CLI gave: its exit code (-1 when it died of a signal) and its stderr.
struct CliRun {
  int exit_code = -1;
  std::string err;
};

/// Runs `sketchsurf ARGS` (ARGS already quoted for the shell) with stdout discarded; stderr goes
/// through `dir`/stderr.txt.
inline CliRun run_cli(const std::string& args, const std::filesystem::path& dir) {
  const std::filesystem::path err = dir / "stderr.txt";
  const std::string command = std::string("'") + SKETCHSURF_CLI + "' " + args + " > /dev/null 2> '" +
                              err.string() + "'";
  const int status = std::system(command.c_str());
  std::ifstream in(err);
  std::stringstream text;
  text << in.rdbuf();
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str()};
}

}  // namespace sketchsurf::testing
