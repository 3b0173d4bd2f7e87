#pragma once
// sketchsurf::Error: the one exception type the library throws for problems a user can act on.

#include <filesystem>
#include <stdexcept>
#include <string>

namespace sketchsurf {

/// What kind of failure an Error reports. The CLI maps each kind to its own exit code.
enum class ErrorKind {
  Usage,       ///< the call itself is wrong (bad option, unknown extension); exit code 2
  Input,       ///< a file cannot be read or is not valid; exit code 3
  Processing,  ///< valid input that a stage could not process; exit code 4
  Cancelled,   ///< the progress callback asked to stop; exit code 130
};

/// An error with a message that says what was wrong and, for input, where (file, offset or line).
class Error : public std::runtime_error {
 public:
  Error(ErrorKind kind, const std::string& message) : std::runtime_error(message), kind_(kind) {}

  ErrorKind kind() const { return kind_; }

  /// "FILE: what" for an invalid or unreadable input file.
  static Error input(const std::filesystem::path& file, const std::string& what);
  /// "FILE: byte OFFSET: what" for binary formats.
  static Error input_at_byte(const std::filesystem::path& file, std::uint64_t offset,
                             const std::string& what);
  /// "FILE:LINE: what" for text formats (lines count from 1).
  static Error input_at_line(const std::filesystem::path& file, std::size_t line,
                             const std::string& what);
  static Error usage(const std::string& what) { return {ErrorKind::Usage, what}; }
  static Error processing(const std::string& what) { return {ErrorKind::Processing, what}; }

 private:
  ErrorKind kind_;
};

/// The process exit code the CLI uses for an error of this kind (2, 3, 4 or 130).
int exit_code(ErrorKind kind);

}  // namespace sketchsurf
