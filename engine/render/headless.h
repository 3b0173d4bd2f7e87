#pragma once
// Headless rendering in one object: an offscreen target, the renderer and an uploaded scene.
// Upload once with set_scene(), then render() as many frames (cameras) as wanted.

#include <memory>

#include "engine/render/image.h"
#include "engine/render/renderer.h"
#include "engine/vk/offscreen.h"

namespace sketchsurf::render {

/// Renders pictures of one scene at a time into memory. Borrows the Context (which must outlive
/// it). Not copyable.
class HeadlessRenderer {
 public:
  /// A width x height target (pixels, each >= 1) with up to `samples` MSAA samples (fewer when
  /// the device cannot). Throws VulkanError, or Error (Usage) for a size the device cannot render.
  HeadlessRenderer(const vk::Context& context, int width, int height,
                   VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_4_BIT);

  int width() const { return int(target_.extent().width); }
  int height() const { return int(target_.extent().height); }
  VkSampleCountFlagBits samples() const { return target_.samples(); }

  /// Uploads `geometry`, replacing the previous scene.
  void set_scene(const SceneGeometry& geometry);
  /// The bounds of the current scene (for fitting cameras).
  const BoundingBox& bounds() const { return scene_.bounds(); }
  /// Renders the current scene seen by `camera` and reads the picture back.
  RgbaImage render(const Camera& camera, const DrawOptions& options = {}) const;

 private:
  const vk::Context* context_;
  vk::OffscreenTarget target_;
  Renderer renderer_;
  GpuScene scene_;
};

}  // namespace sketchsurf::render
