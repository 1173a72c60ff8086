// The search seeds of the reprojection, made once per real frame (see reprojection_cpu.hpp):
// per block of STARNT_TEMPORAL_SEED_BLOCK^2 pixels the (min, max) pass-1 depth, then the same over
// the 3x3 blocks around each block. One fetch per output pixel then replaces a window of fetches
// at every interpolated frame.
#include "methods/neural/temporal/reprojection_constants.h"

layout(binding = 0) uniform highp sampler2D u_source;  // BLOCK: the depth; else the block (min, max)
uniform ivec2 u_sourceSize;

out vec2 o_minMax;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec2 minMax = vec2(uintBitsToFloat(0x7F800000u), uintBitsToFloat(0xFF800000u));  // (+inf, -inf)
#ifdef STARNT_SEEDS_BLOCK
    ivec2 origin = p * STARNT_TEMPORAL_SEED_BLOCK;
    for (int y = 0; y < STARNT_TEMPORAL_SEED_BLOCK; ++y) {
        for (int x = 0; x < STARNT_TEMPORAL_SEED_BLOCK; ++x) {
            float z = texelFetch(u_source, min(origin + ivec2(x, y), u_sourceSize - 1), 0).r;
            minMax = vec2(min(minMax.x, z), max(minMax.y, z));
        }
    }
#else
    for (int y = -1; y <= 1; ++y) {
        for (int x = -1; x <= 1; ++x) {
            vec2 m = texelFetch(u_source, clamp(p + ivec2(x, y), ivec2(0), u_sourceSize - 1), 0).rg;
            minMax = vec2(min(minMax.x, m.x), max(minMax.y, m.y));
        }
    }
#endif
    o_minMax = minMax;
}
