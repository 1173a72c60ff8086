// The empty pixels of a neural composite (empty_pixels.hpp): the background, exactly as the
// composites write it there (rounded to the nearest 16-bit float for a 16-bit output).
#include "methods/neural/half_targets.glsl"
#include "methods/common/background.glsl"
uniform bool u_halfOutput;
layout(location = 0) out vec4 outColor;

void main() { outColor = outputValue(vec4(background(), outputAlpha(1.0)), u_halfOutput); }
