#include "surfacing/sketch/io/text_io.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>

#include "surfacing/error.h"
#include "surfacing/sketch/io/input_limits.h"

namespace sketchsurf::io_detail {

namespace {

std::string_view strip_plus(std::string_view token) {
  if (token.size() > 1 && token[0] == '+' && token[1] != '-') token.remove_prefix(1);
  return token;
}

template <typename T>
std::optional<T> parse_whole(std::string_view token) {
  token = strip_plus(token);
  T value{};
  const char* end = token.data() + token.size();
  const auto [ptr, ec] = std::from_chars(token.data(), end, value);
  if (ec != std::errc() || ptr != end) return std::nullopt;
  if constexpr (std::is_floating_point_v<T>) {
    if (!std::isfinite(value)) return std::nullopt;
  }
  return value;
}

template <typename T>
void append_shortest(std::string& out, T value) {
  if (value == T(0) && std::signbit(value)) {
    out += "-0.0";
    return;
  }
  char buffer[64];
  const auto [ptr, ec] = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, ptr);
}

}  // namespace

std::string read_file(const std::filesystem::path& file) {
  const std::uint64_t size = check_input_file(file, InputLimits::from_environment());
  std::ifstream in(file, std::ios::binary);
  if (!in) throw Error::input(file, std::string("cannot open: ") + std::strerror(errno));
  std::string bytes(static_cast<std::size_t>(size), '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(size));
  if (in.bad() || in.gcount() != static_cast<std::streamsize>(size))
    throw Error::input(file, "read error (the file changed while it was read?)");
  return bytes;
}

void check_not_empty(std::string_view text, const std::filesystem::path& file) {
  if (text.find_first_not_of(" \t\r\n\f\v") == std::string_view::npos)
    throw Error::input(file, "the file is empty");
}

std::string excerpt(std::string_view text) {
  constexpr std::size_t kMax = 80;
  std::string out = "'";
  std::size_t i = 0;
  for (; i < text.size() && out.size() <= kMax; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      static constexpr char kHex[] = "0123456789abcdef";
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  out += i < text.size() ? "'... (" + std::to_string(text.size()) + " bytes)" : "'";
  return out;
}

LineReader::LineReader(std::string_view text, const std::filesystem::path& file)
    : text_(text), file_(&file), max_line_(InputLimits::from_environment().line_bytes) {}

bool LineReader::next(std::string_view& line) {
  if (pos_ >= text_.size()) return false;
  const std::size_t end = text_.find('\n', pos_);
  const std::size_t stop = end == std::string_view::npos ? text_.size() : end;
  if (file_ && stop - pos_ > max_line_)
    throw Error::input_at_line(*file_, line_ + 1,
                               "the line is " + std::to_string(stop - pos_) +
                                   " bytes long, over the limit of " +
                                   std::to_string(max_line_ >> 10) +
                                   " KiB (not a text sketch?); if the file is right, raise it "
                                   "with SKETCHSURF_MAX_LINE_KB=<KiB>");
  line = text_.substr(pos_, stop - pos_);
  pos_ = end == std::string_view::npos ? text_.size() : end + 1;
  ++line_;
  while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t' ||
                           line.back() == '\f' || line.back() == '\v'))
    line.remove_suffix(1);
  return true;
}

void split_tokens(std::string_view line, std::vector<std::string_view>& tokens) {
  tokens.clear();
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
}

std::optional<double> parse_double(std::string_view token) { return parse_whole<double>(token); }
std::optional<float> parse_float(std::string_view token) { return parse_whole<float>(token); }
std::optional<std::int64_t> parse_int(std::string_view token) {
  return parse_whole<std::int64_t>(token);
}

void append_number(std::string& out, double value) { append_shortest(out, value); }
void append_number(std::string& out, float value) { append_shortest(out, value); }

std::string lower_extension(const std::filesystem::path& file) {
  auto ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

}  // namespace sketchsurf::io_detail
