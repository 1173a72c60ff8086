// The empty pixels of a neural composite (empty_pixels.hpp): the background, exactly as the
// composites write it there (rounded to the nearest 16-bit float for a 16-bit output), and, where a
// second target is bound (the fused capture of corrected frames), the kept correction "hidden"
// (alpha -1: no surface there), so that nothing needs clearing first.
#include "methods/neural/half_targets.glsl"
#include "methods/common/background.glsl"
uniform bool u_halfOutput;
layout(location = 0) out vec4 outColor;
layout(location = 1) out vec4 outHidden;

void main() {
    outColor = outputValue(vec4(background(), outputAlpha(1.0)), u_halfOutput);
    outHidden = vec4(0.0, 0.0, 0.0, -1.0);
}
