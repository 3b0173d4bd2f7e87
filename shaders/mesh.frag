#version 450
// Two-sided lighting: a key light, a headlight fill, ambient and a soft specular highlight.
// Back faces (open surfaces seen from behind) get the flipped normal and are slightly darker.
#extension GL_GOOGLE_include_directive : require
#include "frame.glsl"

layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec4 in_color;
layout(location = 0) out vec4 out_color;

void main() {
  vec3 n = normalize(in_normal);
  vec3 v = normalize(frame.eye.xyz - in_position);
  if (dot(n, v) < 0.0) n = -n;
  float back = gl_FrontFacing ? 1.0 : 0.85;
  vec3 l = frame.light.xyz;
  float key = max(dot(n, l), 0.0);
  float fill = max(dot(n, v), 0.0);
  float spec = pow(max(dot(n, normalize(l + v)), 0.0), 40.0);
  vec3 c = in_color.rgb * (0.22 + 0.55 * key + 0.3 * fill) * back + vec3(0.18 * spec);
  out_color = vec4(min(c, vec3(1.0)), in_color.a * frame.params.x);
}
