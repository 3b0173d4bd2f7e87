#pragma once
// Open Brush / Tilt Brush .tilt files, exactly as ../shared/docs/tilt-format.md describes them.

#include <cstdint>
#include <filesystem>
#include <span>

#include "surfacing/sketch/io/sketch_io.h"

namespace sketchsurf {

/// Reads a .tilt file or a directory-form .tilt folder. Positions are converted to right-handed
/// metres with the scene and layer transforms applied; `Mirror` becomes the sketch's mirror plane.
Sketch read_tilt(const std::filesystem::path& file, Warnings* warnings = nullptr);
/// Same, from the bytes of a .tilt file; `name` is used in error messages.
Sketch read_tilt_bytes(std::span<const std::uint8_t> bytes, const std::filesystem::path& name,
                       Warnings* warnings = nullptr);

/// Writes a .tilt that Open Brush loads (format doc section 4), atomically.
void write_tilt(const Sketch& sketch, const std::filesystem::path& file);

}  // namespace sketchsurf
