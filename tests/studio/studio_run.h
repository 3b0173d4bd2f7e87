#pragma once
// Runs sketchsurf-studio from the studio tests (SKETCHSURF_STUDIO is set by tests/studio's CMake):
// to the end, or in the background while the test watches its log and acts on it.

#include <gtest/gtest.h>
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <thread>

#include "tests/support/cli_run.h"

namespace sketchsurf::testing {

/// The bundled cube sketch and the track that draws its edges.
inline std::filesystem::path data_file(const std::string& name) {
  return std::filesystem::path(SKETCHSURF_TESTS_DIR) / "data" / name;
}

inline std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// Runs `[ENV] sketchsurf-studio ARGS` (ARGS quoted for the shell), stdout and stderr into
/// `dir`/log.txt; gives the exit code and that log.
inline CliRun run_studio(const std::string& args, const std::filesystem::path& dir,
                         const std::string& env = "") {
  const std::filesystem::path log = dir / "log.txt";
  const std::string command = env + " timeout 300 '" + std::string(SKETCHSURF_STUDIO) + "' " + args +
                              " > '" + log.string() + "' 2>&1";
  const int status = std::system(command.c_str());
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, read_text(log)};
}

/// sketchsurf-studio running in the background, its stdout and stderr going to a log file.
class StudioProcess {
 public:
  StudioProcess(const std::vector<std::string>& args, const std::filesystem::path& log) : log_(log) {
    pid_ = fork();
    if (pid_ == 0) {
      const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      dup2(fd, 1);
      dup2(fd, 2);
      std::vector<char*> argv;
      std::string exe = SKETCHSURF_STUDIO;
      argv.push_back(exe.data());
      std::vector<std::string> copy = args;
      for (auto& a : copy) argv.push_back(a.data());
      argv.push_back(nullptr);
      execv(exe.c_str(), argv.data());
      _exit(127);
    }
  }
  ~StudioProcess() {
    if (pid_ > 0 && !exited_) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
  }
  pid_t pid() const { return pid_; }
  std::string log() const { return read_text(log_); }
  /// Waits until `done(log)` holds (true) or the process ends or `timeout_s` passes.
  bool wait_until(const std::function<bool(const std::string&)>& done, double timeout_s = 60.0) {
    const auto until = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
    while (std::chrono::steady_clock::now() < until) {
      if (done(log())) return true;
      if (!exited_ && waitpid(pid_, &status_, WNOHANG) == pid_) exited_ = true;
      if (exited_) return done(log());
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return false;
  }
  /// Waits until the log contains `text` (true) or the process ends or `timeout_s` passes.
  bool wait_for(const std::string& text, double timeout_s = 60.0) {
    return wait_until([&](const std::string& log) { return log.find(text) != std::string::npos; }, timeout_s);
  }
  /// Sends `signal` and waits for the end; the exit code (-signal when killed by one).
  int stop(int signal) {
    if (!exited_) {
      kill(pid_, signal);
      waitpid(pid_, &status_, 0);
      exited_ = true;
    }
    return WIFEXITED(status_) ? WEXITSTATUS(status_) : -WTERMSIG(status_);
  }

 private:
  std::filesystem::path log_;
  pid_t pid_ = -1;
  int status_ = 0;
  bool exited_ = false;
};

}  // namespace sketchsurf::testing
