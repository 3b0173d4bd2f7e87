#include "surfacing/sketch/io/input_limits.h"

#include <charconv>
#include <cstdlib>
#include <cstring>
#include <string_view>

#include "surfacing/error.h"

namespace sketchsurf {

namespace {

/// The environment variable `name` as a positive whole number times `unit`, or `fallback`.
std::uint64_t from_env(const char* name, std::uint64_t unit, std::uint64_t fallback) {
  const char* text = std::getenv(name);
  if (!text) return fallback;
  std::uint64_t value = 0;
  const char* end = text + std::strlen(text);
  const auto [ptr, ec] = std::from_chars(text, end, value);
  if (ec != std::errc() || ptr != end || value == 0 || value > UINT64_MAX / unit) return fallback;
  return value * unit;
}

}  // namespace

InputLimits InputLimits::from_environment() {
  InputLimits limits;
  limits.file_bytes = from_env("SKETCHSURF_MAX_INPUT_MB", 1ull << 20, limits.file_bytes);
  limits.line_bytes = from_env("SKETCHSURF_MAX_LINE_KB", 1ull << 10, limits.line_bytes);
  limits.points = from_env("SKETCHSURF_MAX_POINTS", 1, limits.points);
  return limits;
}

PointBudget::PointBudget(const std::filesystem::path& file)
    : file_(file), limit_(InputLimits::from_environment().points) {}

void PointBudget::take(std::uint64_t count) {
  if (count <= limit_ - taken_) {
    taken_ += count;
    return;
  }
  throw Error::input(file_, "the sketch holds more than " + std::to_string(limit_) +
                                " points, the limit; if the file is right, raise it with "
                                "SKETCHSURF_MAX_POINTS=<count>");
}

std::uint64_t check_input_file(const std::filesystem::path& file, const InputLimits& limits) {
  std::error_code ec;
  const auto status = std::filesystem::status(file, ec);
  if (ec || !std::filesystem::exists(status)) throw Error::input(file, "no such file");
  if (std::filesystem::is_directory(status)) throw Error::input(file, "is a directory");
  if (!std::filesystem::is_regular_file(status))
    throw Error::input(file, "is not a regular file (a pipe, a socket or a device): copy its "
                             "contents into a file and read that");
  const std::uint64_t size = std::filesystem::file_size(file, ec);
  if (ec) throw Error::input(file, "cannot read: " + ec.message());
  if (size > limits.file_bytes)
    throw Error::input(file, std::to_string(size) + " bytes is over the input limit of " +
                                 std::to_string(limits.file_bytes >> 20) +
                                 " MiB; if the file is right, raise it with "
                                 "SKETCHSURF_MAX_INPUT_MB=<MiB>");
  return size;
}

}  // namespace sketchsurf
