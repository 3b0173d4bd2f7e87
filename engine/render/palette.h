#pragma once
// The renderer's colours, fixed so that pictures are comparable from run to run and between tools.
//
// The region colours are surfacing's (surfacing/palette.h: ColorBrewer Set3, label i -> colour
// i mod 12), shared with the mesh writers.

#include <array>
#include <cstdint>

#include "surfacing/palette.h"

namespace sketchsurf::render {

using sketchsurf::kRegionPalette;
using sketchsurf::kUnlabelledColor;
using sketchsurf::region_color;
using sketchsurf::Rgb8;

inline constexpr Rgb8 kSurfaceColor{0xb4, 0xc3, 0xd7};         ///< mesh without labels or colours
inline constexpr Rgb8 kStrokeColor{0x1f, 0x2a, 0x44};          ///< ordinary strokes
inline constexpr Rgb8 kBoundaryStrokeColor{0x1d, 0x6f, 0xd8};  ///< strokes marked boundary
inline constexpr Rgb8 kIgnoredStrokeColor{0xa0, 0xa0, 0xa0};   ///< strokes marked ignored
inline constexpr Rgb8 kSharpEdgeColor{0x14, 0x14, 0x14};       ///< creases and region boundaries
inline constexpr Rgb8 kWireColor{0x50, 0x5a, 0x6e};            ///< wireframe
inline constexpr Rgb8 kBackground{0xff, 0xff, 0xff};           ///< default background

}  // namespace sketchsurf::render
