// Level histogram of the occupied tiles: N_0..N_3 (docs/DESIGN.md, "Adaptive tiles and tile-guided resolution"). The buffer is cleared before.
#include "starnt/bindings.h"
#include "methods/neural/tiles/tile_masks.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = STARNT_SSBO_TILE_MASKS_IN) readonly buffer Masks { uint masks[]; };
layout(std430, binding = STARNT_SSBO_TILE_OCCUPANCY) readonly buffer Occupancy { uint occupancy[]; };
layout(std430, binding = STARNT_SSBO_TILE_HISTOGRAM) buffer Histogram { uint histogram[4]; };
uniform uint u_tileCount;

void main() {
    uint index = gl_GlobalInvocationID.x;
    if (index >= u_tileCount || occupancy[index] == 0u) return;
    atomicAdd(histogram[maskLevel(masks[index])], 1u);
}
