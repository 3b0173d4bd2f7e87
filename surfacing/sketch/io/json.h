#pragma once
// sketchsurf's own sketch format (.json), versioned; the schema is documented in the README.

#include <filesystem>
#include <string_view>

#include "surfacing/sketch/io/sketch_io.h"

namespace sketchsurf {

Sketch read_json(const std::filesystem::path& file, Warnings* warnings = nullptr);
/// Parses the text of a .json sketch; `name` is used in error messages.
Sketch read_json_text(std::string_view text, const std::filesystem::path& name,
                      Warnings* warnings = nullptr);
void write_json(const Sketch& sketch, const std::filesystem::path& file);

}  // namespace sketchsurf
