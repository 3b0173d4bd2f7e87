#include "engine/render/headless.h"

#include "surfacing/error.h"

namespace sketchsurf::render {

namespace {

VkExtent2D extent_of(int width, int height) {
  if (width < 1 || height < 1)
    throw Error::usage("image size must be at least 1x1, got " + std::to_string(width) + "x" +
                       std::to_string(height));
  return {static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height)};
}

}  // namespace

HeadlessRenderer::HeadlessRenderer(const vk::Context& context, int width, int height,
                                   VkSampleCountFlagBits samples)
    : context_(&context),
      target_(context, extent_of(width, height), samples),
      renderer_(context, target_.render_pass(), target_.samples()) {}

void HeadlessRenderer::set_scene(const SceneGeometry& geometry) {
  scene_ = GpuScene(*context_, geometry);
}

RgbaImage HeadlessRenderer::render(const Camera& camera, const DrawOptions& options) const {
  context_->submit_and_wait([&](VkCommandBuffer cmd) {
    target_.begin(cmd, options.background);
    renderer_.record(cmd, scene_, camera, double(width()) / double(height()), options);
    target_.end_and_copy(cmd);
  });
  return {width(), height(), target_.read_pixels()};
}

}  // namespace sketchsurf::render
