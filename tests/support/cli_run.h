#pragma once
// Runs the sketchsurf executable from a CLI test (SKETCHSURF_CLI is set by sketchsurf_add_test).

#include <gtest/gtest.h>
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

/// `path` in single quotes, for the shell (built by appending: GCC 12 warns falsely on "'" + s).
inline std::string quoted(const std::filesystem::path& path) {
  std::string out(1, '\'');
  out += path.string();
  out += '\'';
  return out;
}

/// A fresh, empty folder for the running test, named after `prefix` and the test (the tests of one
/// binary may run in parallel under CTest).
inline std::filesystem::path scratch_dir(const std::string& prefix) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() /
      (prefix + ::testing::UnitTest::GetInstance()->current_test_info()->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace sketchsurf::testing
