#include "surfacing/sketch/io/curves.h"

#include <algorithm>

#include "surfacing/error.h"
#include "surfacing/sketch/io/atomic_file.h"
#include "surfacing/sketch/io/input_limits.h"
#include "surfacing/sketch/io/text_io.h"

namespace sketchsurf {

namespace {

/// Parses "x y z" into a point; false when the line is not exactly three finite numbers.
bool parse_point(std::string_view line, std::vector<std::string_view>& tokens, Eigen::Vector3d& p) {
  io_detail::split_tokens(line, tokens);
  if (tokens.size() != 3) return false;
  for (int c = 0; c < 3; ++c) {
    const auto d = io_detail::parse_double(tokens[c]);
    if (!d) return false;
    p[c] = *d;
  }
  return true;
}

}  // namespace

Sketch read_curves(const std::filesystem::path& file, Warnings* warnings) {
  const std::string text = io_detail::read_file(file);
  io_detail::check_not_empty(text, file);
  io_detail::LineReader lines(text, file);
  std::vector<std::string_view> tokens;
  Sketch sketch;
  sketch.provenance = "CASSIE .curves: " + file.filename().string();
  std::size_t empty_strokes = 0;
  PointBudget budget(file);
  std::string_view line;
  while (lines.next(line)) {
    io_detail::split_tokens(line, tokens);
    if (tokens.empty()) continue;  // blank line
    const std::size_t header_line = lines.line_number();
    if (tokens.size() != 2 || tokens[0] != "v")
      throw Error::input_at_line(file, header_line,
                                 "expected a stroke header 'v N', got " + io_detail::excerpt(line));
    const auto n = io_detail::parse_int(tokens[1]);
    if (!n || *n < 0)
      throw Error::input_at_line(file, header_line,
                                 "expected a point count >= 0 after 'v', got " +
                                     io_detail::excerpt(tokens[1]));
    // Every point line holds at least "0 0 0\n" (6 bytes): refuse an absurd count before
    // reserving memory for it.
    if (static_cast<std::uint64_t>(*n) > lines.bytes_left() / 6 + 1)
      throw Error::input_at_line(file, header_line,
                                 "stroke " + std::to_string(sketch.strokes.size()) + " declares " +
                                     std::to_string(*n) + " points but only " +
                                     std::to_string(lines.bytes_left()) + " bytes remain");
    budget.take(static_cast<std::uint64_t>(*n));
    Stroke stroke;
    stroke.points.reserve(static_cast<std::size_t>(*n));
    while (stroke.points.size() < static_cast<std::size_t>(*n)) {
      if (!lines.next(line))
        throw Error::input_at_line(
            file, lines.line_number(),
            "stroke " + std::to_string(sketch.strokes.size()) + " (header at line " +
                std::to_string(header_line) + ") declares " + std::to_string(*n) +
                " points but the file ends after " + std::to_string(stroke.points.size()));
      if (line.find_first_not_of(" \t") == std::string_view::npos) continue;
      Eigen::Vector3d p;
      if (!parse_point(line, tokens, p)) {
        const bool header = !tokens.empty() && tokens[0] == "v";
        throw Error::input_at_line(
            file, lines.line_number(),
            header ? "stroke " + std::to_string(sketch.strokes.size()) + " (header at line " +
                         std::to_string(header_line) + ") declares " + std::to_string(*n) +
                         " points but has only " + std::to_string(stroke.points.size())
                   : "expected a point 'x y z' (three numbers), got " +
                         io_detail::excerpt(line));
      }
      stroke.points.push_back(p);
    }
    if (stroke.points.empty()) {
      ++empty_strokes;
      continue;
    }
    stroke.id = static_cast<std::int64_t>(sketch.strokes.size());
    sketch.strokes.push_back(std::move(stroke));
  }
  if (empty_strokes && warnings)
    warnings->push_back("skipped " + std::to_string(empty_strokes) + " stroke(s) with no points");
  return sketch;
}

void write_curves(const Sketch& sketch, const std::filesystem::path& file) {
  write_atomically(file, [&](std::ostream& out) {
    std::string text;
    for (std::size_t s = 0; s < sketch.strokes.size(); ++s) {
      const Stroke& stroke = sketch.strokes[s];
      if (stroke.points.empty()) continue;  // `v 0` carries nothing; the reader would skip it
      text = "v " + std::to_string(stroke.points.size()) + "\n";
      for (std::size_t i = 0; i < stroke.points.size(); ++i) {
        const Eigen::Vector3d& p = stroke.points[i];
        if (!p.allFinite())
          throw Error::processing("stroke " + std::to_string(s) + " point " + std::to_string(i) +
                                  " is not finite (NaN or Inf): clean the sketch first");
        for (int c = 0; c < 3; ++c) {
          if (c) text += ' ';
          io_detail::append_number(text, p[c]);
        }
        text += '\n';
      }
      out.write(text.data(), static_cast<std::streamsize>(text.size()));
    }
  });
}

}  // namespace sketchsurf
