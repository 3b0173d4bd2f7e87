#pragma once
// RGBA8 pictures: PNG files and tolerant comparison for golden-image tests.

#include <array>
#include <cstdint>
#include <filesystem>
#include <vector>

namespace sketchsurf::render {

/// An RGBA picture, 8 bits per channel, rows from the top, tightly packed.
struct RgbaImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;  ///< width * height * 4 bytes

  std::array<std::uint8_t, 4> at(int x, int y) const {
    const std::size_t i = (std::size_t(y) * width + x) * 4;
    return {pixels[i], pixels[i + 1], pixels[i + 2], pixels[i + 3]};
  }
};

/// Writes `image` as PNG, atomically. Throws Error (Processing) when it cannot be written.
void write_png(const RgbaImage& image, const std::filesystem::path& file);
/// Reads a PNG (any channel count, converted to RGBA). Throws Error (Input) naming the file.
RgbaImage read_png(const std::filesystem::path& file);

/// How two pictures differ.
struct ImageComparison {
  bool same_size = false;      ///< false: the counts below are meaningless
  std::size_t differing = 0;   ///< pixels with a channel differing by more than the tolerance
  double fraction = 1.0;       ///< differing / pixel count
  int max_difference = 0;      ///< largest channel difference anywhere, 0..255
};

/// Compares pixel by pixel; a pixel differs when any channel differs by more than `tolerance`.
ImageComparison compare_images(const RgbaImage& a, const RgbaImage& b, int tolerance = 8);
/// A picture for humans: `expected` dimmed to grey, differing pixels (as in compare_images) in
/// red. Requires equal sizes (else returns `actual`).
RgbaImage difference_image(const RgbaImage& expected, const RgbaImage& actual, int tolerance = 8);

}  // namespace sketchsurf::render
