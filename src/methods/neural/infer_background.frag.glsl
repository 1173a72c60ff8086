// The empty pixels of a neural composite (empty_pixels.hpp): the background, exactly as the
// composites write it there (rounded to the nearest 16-bit float for a 16-bit output).
#include "methods/neural/half_targets.glsl"
uniform vec3 u_background;
uniform bool u_halfOutput;
layout(location = 0) out vec4 outColor;

void main() { outColor = outputValue(vec4(u_background, 1.0), u_halfOutput); }
