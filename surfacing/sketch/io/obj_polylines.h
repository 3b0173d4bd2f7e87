#pragma once
// Sketches as OBJ polylines: `v` records and `l` records. Strokes are the `l` records; when every
// `l` is a 2-vertex segment, strokes are the connected chains, split at vertices of degree != 2.
// Faces are ignored with a warning.

#include <filesystem>

#include "surfacing/sketch/io/sketch_io.h"

namespace sketchsurf {

Sketch read_obj_polylines(const std::filesystem::path& file, Warnings* warnings = nullptr);
void write_obj_polylines(const Sketch& sketch, const std::filesystem::path& file);

}  // namespace sketchsurf
