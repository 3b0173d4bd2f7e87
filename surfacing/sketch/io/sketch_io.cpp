#include "surfacing/sketch/io/sketch_io.h"

#include <algorithm>
#include <cctype>

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

}  // namespace

std::vector<std::string> readable_sketch_extensions() { return {".tilt", ".curves", ".obj", ".json"}; }
std::vector<std::string> writable_sketch_extensions() { return {".json", ".tilt", ".obj", ".curves"}; }

Sketch read_sketch(const std::filesystem::path& file, Warnings* warnings) {
  const auto ext = lower_extension(file);
  std::error_code ec;
  if (!std::filesystem::exists(file, ec))
    throw Error::input(file, "no such file");
  if (ext == ".tilt") return read_tilt(file, warnings);
  if (std::filesystem::is_directory(file, ec))
    throw Error::input(file, "is a directory (only the .tilt format has a directory form)");
  if (ext == ".curves") return read_curves(file, warnings);
  if (ext == ".obj") return read_obj_polylines(file, warnings);
  if (ext == ".json") return read_json(file, warnings);
  throw Error::usage(file.string() + ": unknown sketch extension '" + ext + "' (readable: " +
                     join(readable_sketch_extensions()) + ")");
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
