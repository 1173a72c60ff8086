// The reference depth of the ordered closed form behind the nearest layer (ordered_behind.glsl; CPU
// reference temporal::referenceDepthOnCpu), one texel per tile of STARNT_ORDERED_REFERENCE_TILE
// pixels squared: the nearest depth a real frame's pass 1 kept over the tile, at every
// STARNT_ORDERED_REFERENCE_STRIDE-th pixel of its rows and columns (first pass, from that depth),
// then over the tile and its eight neighbours (STARNT_REFERENCE_AROUND, from the first).
#include "methods/neural/temporal/reprojection_constants.h"

layout(binding = 0) uniform highp sampler2D u_source;
uniform ivec2 u_sourceSize;

out vec4 o_reference;

void main() {
    ivec2 t = ivec2(gl_FragCoord.xy);
    float nearest = 1.0;
#ifdef STARNT_REFERENCE_AROUND
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            nearest = min(nearest, texelFetch(u_source, clamp(t + ivec2(dx, dy), ivec2(0), u_sourceSize - 1), 0).r);
        }
    }
#else
    ivec2 base = t * STARNT_ORDERED_REFERENCE_TILE;
    for (int y = 0; y < STARNT_ORDERED_REFERENCE_TILE; y += STARNT_ORDERED_REFERENCE_STRIDE) {
        for (int x = 0; x < STARNT_ORDERED_REFERENCE_TILE; x += STARNT_ORDERED_REFERENCE_STRIDE) {
            nearest = min(nearest, texelFetch(u_source, min(base + ivec2(x, y), u_sourceSize - 1), 0).r);
        }
    }
#endif
    o_reference = vec4(nearest, 0.0, 0.0, 1.0);
}
