#version 450
// Smooth-shaded triangle mesh with per-vertex colour.
#extension GL_GOOGLE_include_directive : require
#include "frame.glsl"

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec4 in_color;

layout(location = 0) out vec3 out_position;
layout(location = 1) out vec3 out_normal;
layout(location = 2) out vec4 out_color;

void main() {
  gl_Position = frame.view_proj * vec4(in_position, 1.0);
  out_position = in_position;
  out_normal = in_normal;
  out_color = in_color;
}
