// GLSL side of the tile masks (mirrors tiles_cpu.hpp): levels, uniform splits and the quadtree
// leaf that contains a pixel. GL window coordinates, tiles row-major from the bottom-left.
#include "methods/neural/tiles/tile_constants.h"

int maskLevel(uint mask) {
    if ((mask & (STARNT_TILE_MASK_LEVEL3 & ~STARNT_TILE_MASK_LEVEL2)) != 0u) return 3;
    if ((mask & (STARNT_TILE_MASK_LEVEL2 & ~STARNT_TILE_MASK_LEVEL1)) != 0u) return 2;
    if ((mask & STARNT_TILE_MASK_LEVEL1) != 0u) return 1;
    return 0;
}

uint uniformMask(int level) {
    if (level <= 0) return 0u;
    if (level == 1) return STARNT_TILE_MASK_LEVEL1;
    if (level == 2) return STARNT_TILE_MASK_LEVEL2;
    return STARNT_TILE_MASK_LEVEL3;
}

bool maskBit(uint mask, uint bit) { return ((mask >> bit) & 1u) != 0u; }

// The leaf containing pixel p of a tile with `mask`: xy = lower-left pixel, z = edge (16/8/4/2).
ivec3 leafOf(uint mask, ivec2 p) {
    ivec2 origin = (p / STARNT_TILE_SIZE) * STARNT_TILE_SIZE;
    if (!maskBit(mask, STARNT_TILE_BIT_ROOT)) return ivec3(origin, 16);
    ivec2 local = p - origin;
    ivec2 qxy = local / 8;
    uint q = uint(qxy.y * 2 + qxy.x);
    origin += qxy * 8;
    if (!maskBit(mask, STARNT_TILE_BIT_QUADRANT0 + q)) return ivec3(origin, 8);
    ivec2 cxy = (local - qxy * 8) / 4;
    uint c = uint(cxy.y * 2 + cxy.x);
    origin += cxy * 4;
    if (!maskBit(mask, STARNT_TILE_BIT_CHILD0 + 4u * q + c)) return ivec3(origin, 4);
    return ivec3(origin + ((p - origin) / 2) * 2, 2);
}

// The leaf's corner pixels: lower-left and upper-right, clamped to the image.
ivec4 leafCorners(ivec3 leaf, ivec2 imageSize) {
    return ivec4(leaf.xy, min(leaf.xy + leaf.z - 1, imageSize - 1));
}
