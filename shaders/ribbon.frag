#version 450
// Shades a ribbon like a tube seen from the front: brightest along its middle, darker at the rims.
#extension GL_GOOGLE_include_directive : require
#include "frame.glsl"

layout(location = 0) in vec4 in_color;
layout(location = 1) in float in_side;
layout(location = 0) out vec4 out_color;

void main() {
  float facing = sqrt(max(0.0, 1.0 - in_side * in_side));  // cosine of the tube normal to the eye
  float shade = 0.55 + 0.45 * facing;
  out_color = vec4(in_color.rgb * shade, in_color.a * frame.params.x);
}
