#pragma once
// Reading and writing sketches in every supported format, chosen by file extension.

#include <filesystem>
#include <string>
#include <vector>

#include "surfacing/sketch/sketch.h"

namespace sketchsurf {

/// Non-fatal findings of a reader (skipped strokes, ignored faces), one line each.
using Warnings = std::vector<std::string>;

/// Reads a sketch from .tilt (file or directory form), .curves, .obj or .json.
/// Throws Error (Input) naming the file and what is wrong (a point with a NaN or infinite
/// coordinate: its stroke and index); Error (Usage) for an unknown extension. Files over the
/// limits of InputLimits::from_environment() are refused before they are read.
Sketch read_sketch(const std::filesystem::path& file, Warnings* warnings = nullptr);

/// Largest |coordinate| that surfacing accepts: far beyond any real sketch, whatever its units,
/// and small enough that bounding-box diagonals and squared distances stay finite.
constexpr double kMaxCoordinate = 1e12;

/// Throws Error (Input) naming `file`, the stroke and the point when a point of `sketch` is not
/// finite or has a coordinate beyond +-kMaxCoordinate. The readers keep any finite value (formats
/// round-trip exactly); the commands that compute geometry call this first.
void check_extent(const Sketch& sketch, const std::filesystem::path& file);

/// Writes a sketch as .json, .tilt or .obj (polylines), chosen by extension, atomically
/// (temporary file + rename). Throws Error (Usage) for an unknown extension, Error (Processing)
/// when the file cannot be written.
void write_sketch(const Sketch& sketch, const std::filesystem::path& file);

/// Extensions accepted by read_sketch / write_sketch, e.g. {".tilt", ".curves", ".obj", ".json"}.
std::vector<std::string> readable_sketch_extensions();
std::vector<std::string> writable_sketch_extensions();

}  // namespace sketchsurf
