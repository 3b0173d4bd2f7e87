// Per-frame constants shared by every pipeline (push constants). Mirrors
// sketchsurf::render::FrameConstants in engine/render/gpu_types.h: keep both in sync.
layout(push_constant) uniform Frame {
  mat4 view_proj;  // world (relative to the scene origin) -> clip, Vulkan conventions
  vec4 eye;        // xyz: camera position, same frame as the vertices
  vec4 light;      // xyz: unit direction towards the key light
  vec4 params;     // x: alpha multiplier, y: ribbon lift towards the eye (in half widths)
} frame;
