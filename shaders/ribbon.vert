#version 450
// Strokes and highlighted edges as camera-facing ribbons of constant world width: each point of a
// polyline is two vertices (side -1 and +1) pushed apart across the tangent, facing the eye.
#extension GL_GOOGLE_include_directive : require
#include "frame.glsl"

layout(location = 0) in vec3 in_position;
layout(location = 1) in float in_side;
layout(location = 2) in vec3 in_tangent;
layout(location = 3) in float in_half_width;
layout(location = 4) in vec4 in_color;

layout(location = 0) out vec4 out_color;
layout(location = 1) out float out_side;

void main() {
  vec3 to_eye = normalize(frame.eye.xyz - in_position);
  vec3 across = cross(in_tangent, to_eye);
  float len = length(across);
  if (len < 1e-6) {
    // Looking straight down the tangent: any direction across the view will do.
    vec3 helper = abs(to_eye.y) < 0.9 ? vec3(0.0, 1.0, 0.0) : vec3(1.0, 0.0, 0.0);
    across = normalize(cross(helper, to_eye));
  } else {
    across /= len;
  }
  // The lift moves the ribbon towards the eye so that strokes lying on a surface are not cut in
  // half by it (a depth bias in world units, proportional to the ribbon width).
  vec3 p = in_position + across * (in_side * in_half_width) +
           to_eye * (in_half_width * frame.params.y);
  gl_Position = frame.view_proj * vec4(p, 1.0);
  out_color = in_color;
  out_side = in_side;
}
