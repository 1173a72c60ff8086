// Tile evaluation (docs/DESIGN.md, "Adaptive tiles and tile-guided resolution"), one invocation per 16x16 tile, after a real frame's composite:
// top-down split/merge with hysteresis against the previous mask, then the one-level-per-frame
// limit; also records whether the tile is occupied (any pass-1 fragment). Mirrors
// tiles::evaluateTileMask + tiles::limitLevelChange.
#include "starnt/bindings.h"
#include "methods/neural/tiles/tile_masks.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D u_composite;  // linear RGB, full resolution
layout(binding = 1) uniform sampler2D u_nearest;    // pass-1 colour + alpha
layout(std430, binding = STARNT_SSBO_TILE_MASKS_IN) readonly buffer PreviousMasks { uint previousMasks[]; };
layout(std430, binding = STARNT_SSBO_TILE_MASKS_OUT) writeonly buffer NextMasks { uint nextMasks[]; };
layout(std430, binding = STARNT_SSBO_TILE_OCCUPANCY) writeonly buffer Occupancy { uint occupancy[]; };

uniform ivec2 u_size;   // image size
uniform ivec2 u_tiles;  // tile grid size
uniform int u_backSignal;  // 1: D on C - a1 C1 (tiles::TileSignal::Back); 0: on the composite

vec3 colorAt(ivec2 p) {
    vec3 c = texelFetch(u_composite, p, 0).rgb;
    if (u_backSignal != 0) {
        vec4 n = texelFetch(u_nearest, p, 0);
        c -= n.a * n.rgb;
    }
    return c;
}

float nodeVariation(ivec2 origin, int size) {
    ivec2 far = min(origin + size - 1, u_size - 1);
    vec3 c0 = colorAt(origin);
    vec3 c1 = colorAt(ivec2(far.x, origin.y));
    vec3 c2 = colorAt(ivec2(origin.x, far.y));
    vec3 c3 = colorAt(far);
    float sum = distance(c0, c1) + distance(c0, c2) + distance(c0, c3) + distance(c1, c2) + distance(c1, c3) +
                distance(c2, c3);
    return sum / 6.0;
}

bool nodeSplits(float variation, bool wasSplit, float split, float merge) {
    return variation > split || (wasSplit && variation >= merge);
}

void main() {
    ivec2 tile = ivec2(gl_GlobalInvocationID.xy);
    if (tile.x >= u_tiles.x || tile.y >= u_tiles.y) return;
    uint index = uint(tile.y * u_tiles.x + tile.x);
    uint previous = previousMasks[index];
    ivec2 origin = tile * STARNT_TILE_SIZE;

    uint mask = 0u;
    if (nodeSplits(nodeVariation(origin, 16), maskBit(previous, 0u), float(STARNT_TILE_SPLIT_16),
                   float(STARNT_TILE_MERGE_16))) {
        mask = 1u;
        for (uint q = 0u; q < 4u; ++q) {
            ivec2 qOrigin = origin + ivec2(int(q & 1u), int(q >> 1)) * 8;
            if (qOrigin.x >= u_size.x || qOrigin.y >= u_size.y) continue;  // outside a partial tile
            uint qBit = STARNT_TILE_BIT_QUADRANT0 + q;
            if (!nodeSplits(nodeVariation(qOrigin, 8), maskBit(previous, qBit), float(STARNT_TILE_SPLIT_8),
                            float(STARNT_TILE_MERGE_8))) continue;
            mask |= 1u << qBit;
            for (uint c = 0u; c < 4u; ++c) {
                ivec2 cOrigin = qOrigin + ivec2(int(c & 1u), int(c >> 1)) * 4;
                if (cOrigin.x >= u_size.x || cOrigin.y >= u_size.y) continue;
                uint cBit = STARNT_TILE_BIT_CHILD0 + 4u * q + c;
                if (nodeSplits(nodeVariation(cOrigin, 4), maskBit(previous, cBit), float(STARNT_TILE_SPLIT_4),
                               float(STARNT_TILE_MERGE_4))) mask |= 1u << cBit;
            }
        }
    }

    // At most one level of change per frame.
    int level = maskLevel(mask), previousLevel = maskLevel(previous);
    if (level > previousLevel + 1) mask &= uniformMask(previousLevel + 1);
    else if (level < previousLevel - 1) mask |= uniformMask(previousLevel - 1);
    nextMasks[index] = mask;

    // Occupied: any pixel of the tile had a transparent fragment (pass-1 alpha > 0).
    ivec2 end = min(origin + STARNT_TILE_SIZE, u_size);
    uint occupied = 0u;
    for (int y = origin.y; y < end.y && occupied == 0u; ++y) {
        for (int x = origin.x; x < end.x; ++x) {
            if (texelFetch(u_nearest, ivec2(x, y), 0).a > 0.0) {
                occupied = 1u;
                break;
            }
        }
    }
    occupancy[index] = occupied;
}
