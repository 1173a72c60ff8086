// After pass 1 ran against the engine's opaque depth (NeuralPasses::uncoverEmptyPixels): a pixel
// whose pass-1 depth is still the opaque depth kept no transparent fragment (pass 1 keeps only
// fragments strictly in front of it, depth test LESS), so its depth goes back to the far plane,
// the value every reader of pass-1 depth takes for "nothing here".
#include "starnt/bindings.h"
layout(binding = 0) uniform highp sampler2D u_nearestDepth;  // a copy of pass 1's depth
layout(binding = STARNT_UNIT_OPAQUE) uniform highp sampler2D u_opaqueDepth;
uniform bool u_reversed;  // as opaque_depth.frag.glsl

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    float opaque = texelFetch(u_opaqueDepth, p, 0).r;
    if (texelFetch(u_nearestDepth, p, 0).r < (u_reversed ? 1.0 - opaque : opaque)) discard;
    gl_FragDepth = 1.0;
}
