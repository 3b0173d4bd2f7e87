#include "engine/render/sheet.h"

#include <cmath>

#include "engine/render/headless.h"
#include "surfacing/error.h"

namespace sketchsurf::render {

RgbaImage tile_images(const std::vector<RgbaImage>& pictures, int columns, int gap,
                      std::array<std::uint8_t, 4> gap_color) {
  if (pictures.empty() || columns < 1) throw Error::usage("tile_images: no picture or no column");
  const int w = pictures.front().width, h = pictures.front().height;
  for (const RgbaImage& p : pictures)
    if (p.width != w || p.height != h) throw Error::usage("tile_images: pictures of different sizes");
  const int n = static_cast<int>(pictures.size());
  const int cols = std::min(columns, n), rows = (n + cols - 1) / cols;
  RgbaImage out;
  out.width = cols * w + (cols - 1) * gap;
  out.height = rows * h + (rows - 1) * gap;
  out.pixels.resize(std::size_t(out.width) * out.height * 4);
  for (std::size_t i = 0; i < out.pixels.size(); i += 4)
    for (int c = 0; c < 4; ++c) out.pixels[i + c] = gap_color[c];
  for (int k = 0; k < n; ++k) {
    const int x0 = (k % cols) * (w + gap), y0 = (k / cols) * (h + gap);
    for (int y = 0; y < h; ++y)
      std::copy_n(pictures[k].pixels.begin() + std::ptrdiff_t(y) * w * 4, std::size_t(w) * 4,
                  out.pixels.begin() + (std::ptrdiff_t(y0 + y) * out.width + x0) * 4);
  }
  return out;
}

RgbaImage contact_sheet(const vk::Context& context, const Sketch& sketch, const TriMesh* mesh,
                        const MeshAttributes& attributes, const SheetOptions& options) {
  SceneOptions scene_options;
  scene_options.sharp_angle = options.sharp_angle;
  const SceneGeometry strokes = build_scene(sketch, nullptr, nullptr, scene_options);
  HeadlessRenderer renderer(context, options.tile, options.tile,
                            static_cast<VkSampleCountFlagBits>(options.samples));
  // Every picture framed on the strokes and the surface together, so they line up.
  BoundingBox bounds = strokes.bounds;
  std::optional<SceneGeometry> surface, regions;
  if (mesh) {
    MeshAttributes plain = attributes;
    plain.labels.clear();
    surface = build_scene(sketch, mesh, &plain, scene_options);
    scene_options.regions = true;
    regions = build_scene(sketch, mesh, &attributes, scene_options);
    bounds = surface->bounds;
  }
  const Camera front = fit_camera(bounds, View::Iso, 1.0);
  const Camera back = orbit(front, M_PI);
  DrawOptions with_strokes, alone;
  alone.strokes = false;
  alone.hidden_strokes = false;

  std::vector<RgbaImage> pictures;
  renderer.set_scene(strokes);
  pictures.push_back(renderer.render(front, with_strokes));
  pictures.push_back(renderer.render(back, with_strokes));
  if (mesh) {
    renderer.set_scene(*surface);
    pictures.push_back(renderer.render(front, with_strokes));
    renderer.set_scene(*regions);
    pictures.push_back(renderer.render(front, alone));
    renderer.set_scene(*surface);
    pictures.push_back(renderer.render(front, alone));
    pictures.push_back(renderer.render(back, alone));
  }
  return tile_images(pictures, 3);
}

}  // namespace sketchsurf::render
