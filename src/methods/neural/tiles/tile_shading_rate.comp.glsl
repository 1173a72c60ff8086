// Per-tile pass-3 shading rates (tile_constants.h; CPU reference tiles::tileShadingRate, the same
// float arithmetic): one invocation per 16x16 tile, from this probe frame's per-tile guard sums,
// into the shading-rate image (one texel per tile) and the count of occupied tiles per rate beside
// the guard sums in the readback buffer. Runs after tile_scale_guard.comp.glsl.
#include "starnt/bindings.h"
#include "methods/neural/tiles/tile_constants.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = STARNT_SSBO_TILE_GUARD) readonly buffer TileSums { float tileSums[]; };
layout(std430, binding = STARNT_SSBO_TILE_HISTOGRAM) buffer Readback {
    uint histogram[4];
    float guard[STARNT_GUARD_VALUES];
    uint rateTiles[STARNT_SHADING_RATE_CLASSES];
};
layout(binding = 0, r8ui) writeonly uniform highp uimage2D u_rates;
uniform ivec2 u_tiles;

void main() {
    ivec2 tile = ivec2(gl_GlobalInvocationID.xy);
    if (tile.x >= u_tiles.x || tile.y >= u_tiles.y) return;
    uint base = uint(tile.y * u_tiles.x + tile.x) * uint(STARNT_GUARD_VALUES);
    float occupied = tileSums[base + uint(STARNT_GUARD_OCCUPIED)];
    uint rate = STARNT_SHADING_RATE_FULL;
    if (occupied > 0.0) {
        float allowed = float(STARNT_SCALE_GUARD_BUDGET) * occupied;
        if (tileSums[base + uint(STARNT_GUARD_LOSS_PASS3_QUARTER)] <= allowed) rate = STARNT_SHADING_RATE_QUARTER;
        else if (tileSums[base + uint(STARNT_GUARD_LOSS_PASS3_HALF)] <= allowed) rate = STARNT_SHADING_RATE_HALF;
        atomicAdd(rateTiles[rate], 1u);
    }
    imageStore(u_rates, tile, uvec4(rate));
}
