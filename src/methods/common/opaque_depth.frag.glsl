// Writes the engine's opaque depth (FrameDesc::opaqueDepth) into the bound depth target, over the
// rectangle of a pass at u_size of a frame at u_fullSize (opaque_scene.hpp). A reduced texel i
// takes the depth at the full pixel holding its sample, floor(i F / R + 0.5) (reduced_grid.hpp):
// the pixel whose pass-1 fragments the reduced pass-3 sums hold there.
#include "starnt/bindings.h"
layout(binding = STARNT_UNIT_OPAQUE) uniform highp sampler2D u_opaqueDepth;
uniform ivec2 u_size, u_fullSize;
uniform bool u_reversed;  // the engine's depth is reversed (DepthConvention): near at 1

void main() {
    ivec2 i = ivec2(gl_FragCoord.xy);
    ivec2 p = min((2 * i * u_fullSize + u_size) / (2 * u_size), u_fullSize - 1);
    float depth = texelFetch(u_opaqueDepth, p, 0).r;
    gl_FragDepth = u_reversed ? 1.0 - depth : depth;  // the canonical window depth, as the passes see theirs
}
