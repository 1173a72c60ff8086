// Scale guard, total: sums the per-tile values over the tiles in order, into the floats after the
// level histogram (read back with it, without a stall). One invocation per value.
#include "starnt/bindings.h"
#include "methods/neural/tiles/tile_constants.h"

layout(local_size_x = STARNT_GUARD_VALUES) in;
layout(std430, binding = STARNT_SSBO_TILE_GUARD) readonly buffer TileSums { float tileSums[]; };
layout(std430, binding = STARNT_SSBO_TILE_HISTOGRAM) buffer Readback {
    uint histogram[4];
    float guard[STARNT_GUARD_VALUES];
};
uniform uint u_tileCount;

void main() {
    uint value = gl_LocalInvocationID.x;
    float sum = 0.0;
    for (uint t = 0u; t < u_tileCount; ++t) sum += tileSums[t * uint(STARNT_GUARD_VALUES) + value];
    guard[value] = sum;
}
