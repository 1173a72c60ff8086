// Writes what the composite goes over (background.glsl) into the bound target: the start of a
// method that blends its layers straight into the output (unsorted).
#include "methods/common/background.glsl"
layout(location = 0) out vec4 outColor;

void main() { outColor = vec4(background(), outputAlpha(1.0)); }
