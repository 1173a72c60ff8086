// The reference depth of the ordered closed form behind the nearest layer (ordered_behind.glsl; CPU
// reference temporal::referenceDepthOnCpu), one texel per tile of STARNT_ORDERED_REFERENCE_TILE
// pixels squared: the nearest depth a real frame's pass 1 kept over the tile, at every
// STARNT_ORDERED_REFERENCE_STRIDE-th pixel of its rows and columns (first pass, from that depth),
// then over the tile and its eight neighbours (STARNT_REFERENCE_AROUND, from the first).
// With STARNT_REFERENCE_FROM_PACKED (three layers: each interpolated frame keeps the reference for
// the next one, docs/DESIGN.md, "Corrected frames: the reference depth follows the interpolated
// frames"), the first pass reads the nearest layer's depth from pass 3's packed layers (RGBA32UI,
// packed_nearest.h: 1 where there is none) instead of from a depth texture.
#include "methods/neural/temporal/reprojection_constants.h"

#ifdef STARNT_REFERENCE_FROM_PACKED
#define STARNT_PACKED_TWO_LAYERS
#include "methods/neural/temporal/packed_nearest.glsl"
layout(binding = 0) uniform highp usampler2D u_source;
float depthAt(ivec2 p) {
    uint key = texelFetch(u_source, p, 0).x >> kLayerLowBits;
    return key == kLayerMaxKey ? 1.0 : depthOfLayerKey(key);
}
#else
layout(binding = 0) uniform highp sampler2D u_source;
float depthAt(ivec2 p) { return texelFetch(u_source, p, 0).r; }
#endif
uniform ivec2 u_sourceSize;

out vec4 o_reference;

void main() {
    ivec2 t = ivec2(gl_FragCoord.xy);
    float nearest = 1.0;
#ifdef STARNT_REFERENCE_AROUND
    for (int dy = -1; dy <= 1; ++dy) {
        for (int dx = -1; dx <= 1; ++dx) {
            nearest = min(nearest, depthAt(clamp(t + ivec2(dx, dy), ivec2(0), u_sourceSize - 1)));
        }
    }
#else
    ivec2 base = t * STARNT_ORDERED_REFERENCE_TILE;
    for (int y = 0; y < STARNT_ORDERED_REFERENCE_TILE; y += STARNT_ORDERED_REFERENCE_STRIDE) {
        for (int x = 0; x < STARNT_ORDERED_REFERENCE_TILE; x += STARNT_ORDERED_REFERENCE_STRIDE) {
            nearest = min(nearest, depthAt(min(base + ivec2(x, y), u_sourceSize - 1)));
        }
    }
#endif
    o_reference = vec4(nearest, 0.0, 0.0, 1.0);
}
