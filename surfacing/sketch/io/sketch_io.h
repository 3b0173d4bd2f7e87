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
/// Throws Error (Input) naming the file and what is wrong; Error (Usage) for an unknown extension.
Sketch read_sketch(const std::filesystem::path& file, Warnings* warnings = nullptr);

/// Writes a sketch as .json, .tilt or .obj (polylines), chosen by extension, atomically
/// (temporary file + rename). Throws Error (Usage) for an unknown extension, Error (Processing)
/// when the file cannot be written.
void write_sketch(const Sketch& sketch, const std::filesystem::path& file);

/// Extensions accepted by read_sketch / write_sketch, e.g. {".tilt", ".curves", ".obj", ".json"}.
std::vector<std::string> readable_sketch_extensions();
std::vector<std::string> writable_sketch_extensions();

}  // namespace sketchsurf
