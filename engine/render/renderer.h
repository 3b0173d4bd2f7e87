#pragma once
// The renderer: uploads a scene once (GpuScene) and records its draws into any render pass
// compatible with the one it was built for (the offscreen target today, a swapchain later).

#include <array>

#include "engine/render/camera.h"
#include "engine/render/scene.h"
#include "engine/vk/buffer.h"
#include "engine/vk/context.h"

namespace sketchsurf::render {

/// What to draw of an uploaded scene, per frame.
struct DrawOptions {
  std::array<float, 4> background{1.0f, 1.0f, 1.0f, 1.0f};  ///< RGBA in [0, 1]
  bool strokes = true;          ///< draw the strokes
  bool hidden_strokes = true;   ///< draw strokes hidden by the surface faintly (depth-aware overlay)
  float hidden_alpha = 0.2f;    ///< opacity of hidden strokes, in [0, 1]
  bool mesh = true;             ///< draw the mesh and its outlines
  bool translucent_strokes = false; ///< strokes blended by their colours' alpha, writing no depth
  bool occluders_drawn = false; ///< an opaque surface was drawn earlier in this pass (another
                                ///< scene's): draw this scene's hidden strokes faintly even when it
                                ///< has no mesh of its own
};

/// A scene's geometry in device-local buffers. Move-only.
class GpuScene {
 public:
  GpuScene() = default;
  /// Uploads `geometry` (waits for the copies). Throws VulkanError.
  GpuScene(const vk::Context& context, const SceneGeometry& geometry);

  const Eigen::Vector3d& origin() const { return origin_; }
  const BoundingBox& bounds() const { return bounds_; }

 private:
  friend class Renderer;
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  BoundingBox bounds_;
  vk::Buffer ribbon_vertices_, ribbon_indices_, mesh_vertices_, mesh_indices_;
  std::uint32_t stroke_indices_ = 0, edge_indices_ = 0, mesh_index_count_ = 0;
  bool mesh_closed_ = false;
};

/// Pipelines for meshes and ribbons, built for one render pass and sample count.
class Renderer {
 public:
  /// Throws VulkanError when a pipeline cannot be created.
  Renderer(const vk::Context& context, VkRenderPass render_pass, VkSampleCountFlagBits samples);

  /// Records the draws of `scene` as seen by `camera` into the render pass currently begun on
  /// `cmd` (viewport and scissor set by the caller). Order: mesh (back faces culled when it is
  /// closed and outward: the same picture, half the triangles for a CPU rasteriser), outlines,
  /// hidden strokes (depth test GREATER, faint, no depth write), visible strokes.
  void record(VkCommandBuffer cmd, const GpuScene& scene, const Camera& camera, double aspect,
              const DrawOptions& options) const;

 private:
  const vk::Context* context_;
  vk::UniquePipelineLayout layout_;
  vk::UniquePipeline mesh_, mesh_culled_, ribbon_, ribbon_hidden_, ribbon_translucent_;
};

}  // namespace sketchsurf::render
