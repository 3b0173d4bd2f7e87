#pragma once
// CASSIE .curves files: per stroke a line `v N` then N lines `x y z` (metres).

#include <filesystem>

#include "surfacing/sketch/io/sketch_io.h"

namespace sketchsurf {

Sketch read_curves(const std::filesystem::path& file, Warnings* warnings = nullptr);
void write_curves(const Sketch& sketch, const std::filesystem::path& file);

}  // namespace sketchsurf
