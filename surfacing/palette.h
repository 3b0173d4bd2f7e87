#pragma once
// The colours of the regions, shared by the mesh writers (PLY, OBJ, glTF) and the renderer, so
// that a file opened in a viewer and a picture of it agree.
//
// Region palette (label i -> kRegionPalette[i % 12], ColorBrewer Set3 with its grey replaced):
//   0 #8dd3c7 teal      1 #ffffb3 cream     2 #bebada lavender   3 #fb8072 salmon
//   4 #80b1d3 blue      5 #fdb462 orange    6 #b3de69 green      7 #fccde5 pink
//   8 #e5c494 sand      9 #bc80bd purple   10 #ccebc5 mint      11 #ffed6f yellow
// Negative labels (unlabelled vertices) are grey #9e9e9e.

#include <array>
#include <cstddef>
#include <cstdint>

namespace sketchsurf {

using Rgb8 = std::array<std::uint8_t, 3>;

inline constexpr std::array<Rgb8, 12> kRegionPalette{{
    {0x8d, 0xd3, 0xc7}, {0xff, 0xff, 0xb3}, {0xbe, 0xba, 0xda}, {0xfb, 0x80, 0x72},
    {0x80, 0xb1, 0xd3}, {0xfd, 0xb4, 0x62}, {0xb3, 0xde, 0x69}, {0xfc, 0xcd, 0xe5},
    {0xe5, 0xc4, 0x94}, {0xbc, 0x80, 0xbd}, {0xcc, 0xeb, 0xc5}, {0xff, 0xed, 0x6f},
}};
inline constexpr Rgb8 kUnlabelledColor{0x9e, 0x9e, 0x9e};

/// The colour of region `label`: kRegionPalette[label % 12], or kUnlabelledColor when negative.
inline Rgb8 region_color(int label) {
  return label < 0 ? kUnlabelledColor : kRegionPalette[static_cast<std::size_t>(label) % 12];
}

}  // namespace sketchsurf
