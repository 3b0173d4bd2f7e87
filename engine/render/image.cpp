#include "engine/render/image.h"

#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <cstdlib>
#include <memory>
#include <ostream>

#include "surfacing/error.h"
#include "surfacing/sketch/io/atomic_file.h"

namespace sketchsurf::render {

namespace {

int channel_difference(const RgbaImage& a, const RgbaImage& b, std::size_t pixel) {
  int worst = 0;
  for (int c = 0; c < 4; ++c)
    worst = std::max(worst, std::abs(int(a.pixels[pixel * 4 + c]) - int(b.pixels[pixel * 4 + c])));
  return worst;
}

}  // namespace

void write_png(const RgbaImage& image, const std::filesystem::path& file) {
  if (image.width <= 0 || image.height <= 0 ||
      image.pixels.size() != std::size_t(image.width) * image.height * 4)
    throw Error::processing(file.string() + ": cannot write an empty or malformed picture");
  std::vector<char> png;
  const auto append = [](void* context, void* data, int size) {
    auto* out = static_cast<std::vector<char>*>(context);
    out->insert(out->end(), static_cast<char*>(data), static_cast<char*>(data) + size);
  };
  if (!stbi_write_png_to_func(append, &png, image.width, image.height, 4, image.pixels.data(),
                              image.width * 4))
    throw Error::processing(file.string() + ": PNG encoding failed");
  write_atomically(file, [&](std::ostream& out) { out.write(png.data(), std::streamsize(png.size())); });
}

RgbaImage read_png(const std::filesystem::path& file) {
  int w = 0, h = 0, channels = 0;
  const std::unique_ptr<stbi_uc, decltype(&stbi_image_free)> data(
      stbi_load(file.string().c_str(), &w, &h, &channels, 4), &stbi_image_free);
  if (!data) throw Error::input(file, std::string("cannot read PNG: ") + stbi_failure_reason());
  RgbaImage image{w, h, {}};
  image.pixels.assign(data.get(), data.get() + std::size_t(w) * h * 4);
  return image;
}

ImageComparison compare_images(const RgbaImage& a, const RgbaImage& b, int tolerance) {
  ImageComparison result;
  if (a.width != b.width || a.height != b.height) return result;
  result.same_size = true;
  const std::size_t n = std::size_t(a.width) * a.height;
  for (std::size_t i = 0; i < n; ++i) {
    const int d = channel_difference(a, b, i);
    result.max_difference = std::max(result.max_difference, d);
    if (d > tolerance) ++result.differing;
  }
  result.fraction = n > 0 ? double(result.differing) / double(n) : 0.0;
  return result;
}

RgbaImage difference_image(const RgbaImage& expected, const RgbaImage& actual, int tolerance) {
  if (expected.width != actual.width || expected.height != actual.height) return actual;
  RgbaImage out = expected;
  const std::size_t n = std::size_t(expected.width) * expected.height;
  for (std::size_t i = 0; i < n; ++i) {
    std::uint8_t* p = &out.pixels[i * 4];
    if (channel_difference(expected, actual, i) > tolerance) {
      p[0] = 255, p[1] = 0, p[2] = 0;
    } else {
      const auto grey = static_cast<std::uint8_t>(160 + (int(p[0]) + p[1] + p[2]) / 8);
      p[0] = p[1] = p[2] = grey;
    }
    p[3] = 255;
  }
  return out;
}

}  // namespace sketchsurf::render
