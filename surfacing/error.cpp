#include "surfacing/error.h"

namespace sketchsurf {

Error Error::input(const std::filesystem::path& file, const std::string& what) {
  return {ErrorKind::Input, file.string() + ": " + what};
}

Error Error::input_at_byte(const std::filesystem::path& file, std::uint64_t offset,
                           const std::string& what) {
  return {ErrorKind::Input, file.string() + ": byte " + std::to_string(offset) + ": " + what};
}

Error Error::input_at_line(const std::filesystem::path& file, std::size_t line,
                           const std::string& what) {
  return {ErrorKind::Input, file.string() + ":" + std::to_string(line) + ": " + what};
}

int exit_code(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::Usage: return 2;
    case ErrorKind::Input: return 3;
    case ErrorKind::Processing: return 4;
    case ErrorKind::Cancelled: return 130;
  }
  return 4;
}

}  // namespace sketchsurf
