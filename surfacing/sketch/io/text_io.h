#pragma once
// Helpers shared by the text readers and writers of sketch/io (not part of the public API):
// whole-file reading, line splitting with line numbers, strict number parsing, and shortest
// round-trip number printing.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace sketchsurf::io_detail {

/// The bytes of `file`, after check_input_file() with InputLimits::from_environment(). Throws
/// Error (Input) naming the file when it cannot be opened or read, is not a regular file or is
/// over the size limit.
std::string read_file(const std::filesystem::path& file);

/// Throws Error (Input) "FILE: the file is empty" when `text` holds nothing but whitespace.
void check_not_empty(std::string_view text, const std::filesystem::path& file);

/// A piece of a file's text fit for a message: single-quoted, cut to about 80 characters (with
/// "...") and with control and non-ASCII bytes written as \xNN, so a message never carries NUL
/// bytes or megabytes of a broken line.
std::string excerpt(std::string_view text);

/// The file's extension in lower case, with its dot (".ply").
std::string lower_extension(const std::filesystem::path& file);

/// Iterates over the lines of a text, counting them from 1. A line loses its line ending (LF or
/// CRLF) and its trailing whitespace, so "v 3 \r\n" gives "v 3".
class LineReader {
 public:
  explicit LineReader(std::string_view text) : text_(text) {}
  /// Same, refusing lines longer than InputLimits::from_environment().line_bytes: next() throws
  /// Error (Input) naming `file` and the line.
  LineReader(std::string_view text, const std::filesystem::path& file);
  /// The next line, or false at the end of the text.
  bool next(std::string_view& line);
  /// Number of the line last returned by next() (1-based).
  std::size_t line_number() const { return line_; }
  /// Bytes not yet consumed.
  std::size_t bytes_left() const { return text_.size() - pos_; }

 private:
  std::string_view text_;
  const std::filesystem::path* file_ = nullptr;  ///< set when lines are limited
  std::size_t max_line_ = 0;
  std::size_t pos_ = 0;
  std::size_t line_ = 0;
};

/// Splits a line at spaces and tabs, dropping empty tokens.
void split_tokens(std::string_view line, std::vector<std::string_view>& tokens);

/// Parses a whole token as a finite double (an optional leading '+' is accepted); nullopt when the
/// token is not a number, has trailing characters or is NaN/Inf.
std::optional<double> parse_double(std::string_view token);
/// Parses a whole token as a finite float, correctly rounded from the decimal text.
std::optional<float> parse_float(std::string_view token);
/// Parses a whole token as a signed integer (an optional leading '+' is accepted).
std::optional<std::int64_t> parse_int(std::string_view token);

/// Appends the shortest decimal text that reads back as exactly `value` (finite values only).
/// Negative zero is printed as "-0.0" so that JSON readers keep its sign.
void append_number(std::string& out, double value);
/// Same for a float: reading the text back as a float gives the same bits.
void append_number(std::string& out, float value);

}  // namespace sketchsurf::io_detail
