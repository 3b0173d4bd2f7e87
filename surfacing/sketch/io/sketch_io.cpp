#include "surfacing/sketch/io/sketch_io.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <limits>
#include <sstream>

#include "surfacing/error.h"
#include "surfacing/sketch/io/curves.h"
#include "surfacing/sketch/io/json.h"
#include "surfacing/sketch/io/obj_polylines.h"
#include "surfacing/sketch/io/text_io.h"
#include "surfacing/sketch/io/tilt.h"

namespace sketchsurf {

using io_detail::lower_extension;

namespace {

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : ", ") + s;
  return out;
}

/// Refuses the first point that is not finite or has a coordinate beyond +-limit.
void check_coordinates(const Sketch& sketch, const std::filesystem::path& file, double limit) {
  for (std::size_t s = 0; s < sketch.strokes.size(); ++s) {
    const auto& points = sketch.strokes[s].points;
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (points[i].allFinite() && points[i].cwiseAbs().maxCoeff() <= limit) continue;
      std::ostringstream what;
      what << "stroke " << s << " point " << i << " (" << points[i].x() << ", " << points[i].y()
           << ", " << points[i].z() << "): ";
      if (!points[i].allFinite())
        what << "a coordinate is not finite (NaN or Inf)";
      else
        what << "a coordinate is beyond +-" << limit << ", larger than any sketch";
      what << "; fix or remove that point";
      throw Error::input(file, what.str());
    }
  }
}

}  // namespace

std::vector<std::string> readable_sketch_extensions() { return {".tilt", ".curves", ".obj", ".json"}; }
std::vector<std::string> writable_sketch_extensions() { return {".json", ".tilt", ".obj", ".curves"}; }

Sketch read_sketch(const std::filesystem::path& file, Warnings* warnings) {
  const auto ext = lower_extension(file);
  std::error_code ec;
  if (!std::filesystem::exists(file, ec))
    throw Error::input(file, "no such file");
  Sketch sketch;
  if (ext == ".tilt") {
    sketch = read_tilt(file, warnings);
  } else {
    if (std::filesystem::is_directory(file, ec))
      throw Error::input(file, "is a directory (only the .tilt format has a directory form)");
    if (ext == ".curves") sketch = read_curves(file, warnings);
    else if (ext == ".obj") sketch = read_obj_polylines(file, warnings);
    else if (ext == ".json") sketch = read_json(file, warnings);
    else
      throw Error::usage(file.string() + ": unknown sketch extension '" + ext + "' (readable: " +
                         join(readable_sketch_extensions()) + ")");
  }
  // The same rule for every format: the text readers cannot parse NaN or Inf, a .tilt holds raw
  // floats.
  check_coordinates(sketch, file, std::numeric_limits<double>::infinity());
  return sketch;
}

void check_extent(const Sketch& sketch, const std::filesystem::path& file) {
  check_coordinates(sketch, file, kMaxCoordinate);
}

void write_sketch(const Sketch& sketch, const std::filesystem::path& file) {
  const auto ext = lower_extension(file);
  if (ext == ".json") return write_json(sketch, file);
  if (ext == ".tilt") return write_tilt(sketch, file);
  if (ext == ".obj") return write_obj_polylines(sketch, file);
  if (ext == ".curves") return write_curves(sketch, file);
  throw Error::usage(file.string() + ": unknown sketch extension '" + ext + "' (writable: " +
                     join(writable_sketch_extensions()) + ")");
}

}  // namespace sketchsurf
