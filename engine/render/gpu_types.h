#pragma once
// Structs shared with the shaders (vertex layouts and push constants). Every size and offset is
// pinned by a static_assert: a change here must be mirrored in shaders/*.vert and frame.glsl.

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>

namespace sketchsurf::render {

/// Push constants of every pipeline (shaders/frame.glsl).
struct FrameConstants {
  glm::mat4 view_proj{1.0f};  ///< scene-relative world -> Vulkan clip space
  glm::vec4 eye{0.0f};        ///< xyz: eye position, scene-relative
  glm::vec4 light{0.0f};      ///< xyz: unit direction towards the key light
  glm::vec4 params{1.0f, 0.0f, 0.0f, 0.0f};  ///< x: alpha multiplier, y: ribbon lift (half widths)
};
static_assert(sizeof(FrameConstants) == 112, "push constants must match shaders/frame.glsl");
static_assert(offsetof(FrameConstants, eye) == 64);
static_assert(offsetof(FrameConstants, light) == 80);
static_assert(offsetof(FrameConstants, params) == 96);

/// One side of a ribbon point (shaders/ribbon.vert). Colour is RGBA8 with R in the low byte.
struct RibbonVertex {
  glm::vec3 position{0.0f};  ///< polyline point, scene-relative
  float side = 0.0f;         ///< -1 or +1: which edge of the ribbon
  glm::vec3 tangent{0.0f};   ///< unit tangent of the polyline at the point
  float half_width = 0.0f;   ///< half the ribbon width, scene units
  std::uint32_t color = 0;   ///< RGBA8
};
static_assert(sizeof(RibbonVertex) == 36, "vertex layout must match shaders/ribbon.vert");
static_assert(offsetof(RibbonVertex, side) == 12);
static_assert(offsetof(RibbonVertex, tangent) == 16);
static_assert(offsetof(RibbonVertex, half_width) == 28);
static_assert(offsetof(RibbonVertex, color) == 32);

/// A mesh vertex (shaders/mesh.vert).
struct MeshVertex {
  glm::vec3 position{0.0f};  ///< scene-relative
  glm::vec3 normal{0.0f};    ///< unit, outward for closed meshes
  std::uint32_t color = 0;   ///< RGBA8
};
static_assert(sizeof(MeshVertex) == 28, "vertex layout must match shaders/mesh.vert");
static_assert(offsetof(MeshVertex, normal) == 12);
static_assert(offsetof(MeshVertex, color) == 24);

/// Packs an RGBA colour with components in [0, 1] (clamped) into RGBA8, R in the low byte.
inline std::uint32_t pack_rgba(float r, float g, float b, float a = 1.0f) {
  auto byte = [](float v) {
    return static_cast<std::uint32_t>(glm::clamp(v, 0.0f, 1.0f) * 255.0f + 0.5f);
  };
  return byte(r) | (byte(g) << 8) | (byte(b) << 16) | (byte(a) << 24);
}

}  // namespace sketchsurf::render
