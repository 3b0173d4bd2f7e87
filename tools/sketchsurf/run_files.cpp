#include "tools/sketchsurf/run_files.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <csignal>
#include <cstring>

#include "surfacing/error.h"

namespace sketchsurf::cli {

namespace fs = std::filesystem;

namespace {

std::atomic<bool> g_cancel{false};
static_assert(std::atomic<bool>::is_always_lock_free, "set from a signal handler");

extern "C" void on_cancel_signal(int signal) {
  if (g_cancel.exchange(true)) {  // the second Ctrl-C: stop now
    std::signal(signal, SIG_DFL);
    std::raise(signal);
  }
}

std::string lower(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : ", ") + s;
  return out;
}

/// Whether `a` and `b` are the same file: the same inode when both exist, else the same
/// absolute path once links and "." / ".." are resolved.
bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) return fs::equivalent(a, b, ec) && !ec;
  const fs::path ca = fs::weakly_canonical(a, ec);
  if (ec) return false;
  const fs::path cb = fs::weakly_canonical(b, ec);
  return !ec && ca == cb;
}

CLI::Validator number_check(const std::string& what, const std::function<bool(double)>& ok) {
  return CLI::Validator(
      [what, ok](std::string& text) -> std::string {
        double value = 0;
        const char* end = text.data() + text.size();
        const auto [ptr, ec] = std::from_chars(text.data(), end, value);
        if (text.empty() || ec != std::errc() || ptr != end || !std::isfinite(value) || !ok(value))
          return "expected " + what + ", got '" + text + "'";
        return {};
      },
      what);
}

}  // namespace

RunFiles::RunFiles() {
  struct sigaction action {};
  action.sa_handler = on_cancel_signal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

bool cancel_requested() { return g_cancel.load(); }

void RunFiles::input(const std::string& file) {
  if (!file.empty()) inputs_.emplace_back(file);
}

void RunFiles::output(const std::string& option, const std::string& file,
                      const std::vector<std::string>& extensions) {
  const fs::path path(file);
  const std::string named = option + " " + file;
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw Error::usage(named + " is a directory: give a file name");
  if (!extensions.empty() &&
      std::find(extensions.begin(), extensions.end(), lower(path.extension().string())) == extensions.end())
    throw Error::usage(named + ": unknown extension '" + path.extension().string() +
                       "'; give a file name ending in " + join(extensions));
  for (const auto& in : inputs_)
    if (same_file(path, in))
      throw Error::usage(named + " is the input " + in.string() +
                         ": choose another output name (an input is never overwritten)");
  for (const auto& out : outputs_)
    if (same_file(path, out))
      throw Error::usage(named + " is also the output " + out.string() + ": give each output its own name");
  const fs::path dir = path.has_parent_path() ? path.parent_path() : fs::path(".");
  if (!fs::is_directory(dir, ec))
    throw Error::usage(named + ": the directory " + dir.string() +
                       " does not exist; create it first or write somewhere else");
  if (access(dir.c_str(), W_OK | X_OK) != 0)
    throw Error::usage(named + ": cannot write into the directory " + dir.string() + " (" +
                       std::strerror(errno) + "); choose a directory you may write to");
  outputs_.push_back(path);
}

void RunFiles::write(const std::string& file, const std::function<void(const fs::path&)>& writer) {
  staged_.write(file, writer);
}

void RunFiles::commit() {
  if (cancel_requested()) throw Error(ErrorKind::Cancelled, "cancelled; no output was changed");
  staged_.commit();
}

CLI::Validator whole_number(std::uint64_t lo, std::uint64_t hi) {
  const std::string range = "expected a whole number from " + std::to_string(lo) + " to " +
                            std::to_string(hi);
  return CLI::Validator(
      [lo, hi, range](std::string& text) -> std::string {
        std::uint64_t value = 0;
        const char* end = text.data() + text.size();
        const auto [ptr, ec] = std::from_chars(text.data(), end, value);
        if (text.empty() || ec != std::errc() || ptr != end || value < lo || value > hi)
          return range + ", got '" + text + "'";
        return {};
      },
      "INT in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
}

CLI::Validator positive_number() {
  return number_check("a number > 0", [](double v) { return v > 0; });
}

CLI::Validator non_negative_number() {
  return number_check("a number >= 0", [](double v) { return v >= 0; });
}

std::map<std::string, double> parse_params(const std::vector<std::string>& assignments) {
  std::map<std::string, double> out;
  for (const std::string& a : assignments) {
    const std::size_t eq = a.find('=');
    double value = 0;
    const char* end = a.data() + a.size();
    const auto [ptr, ec] = eq == std::string::npos ? std::from_chars_result{end, std::errc::invalid_argument}
                                                   : std::from_chars(a.data() + eq + 1, end, value);
    if (eq == std::string::npos || eq == 0 || eq + 1 == a.size() || ec != std::errc() ||
        ptr != end || !std::isfinite(value))
      throw Error::usage("--param: expected NAME=VALUE with a number as the value (for example "
                         "proxy.lambda=0.001), got '" + a + "'");
    out[a.substr(0, eq)] = value;
  }
  return out;
}

}  // namespace sketchsurf::cli
