// One Jacobi iteration of the neighbour balance (docs/DESIGN.md, "Adaptive tiles and tile-guided resolution"): a tile whose finest 4-neighbour is more
// than one level finer is split uniformly to that level minus one. Reads one mask buffer, writes
// the other (ping-pong). Mirrors tiles::balanceOnce.
#include "starnt/bindings.h"
#include "methods/neural/tiles/tile_masks.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = STARNT_SSBO_TILE_MASKS_IN) readonly buffer Source { uint source[]; };
layout(std430, binding = STARNT_SSBO_TILE_MASKS_OUT) writeonly buffer Destination { uint destination[]; };
uniform ivec2 u_tiles;

int levelAt(ivec2 t) { return maskLevel(source[t.y * u_tiles.x + t.x]); }

void main() {
    ivec2 tile = ivec2(gl_GlobalInvocationID.xy);
    if (tile.x >= u_tiles.x || tile.y >= u_tiles.y) return;
    int index = tile.y * u_tiles.x + tile.x;
    int finest = 0;
    if (tile.x > 0) finest = max(finest, levelAt(tile - ivec2(1, 0)));
    if (tile.x + 1 < u_tiles.x) finest = max(finest, levelAt(tile + ivec2(1, 0)));
    if (tile.y > 0) finest = max(finest, levelAt(tile - ivec2(0, 1)));
    if (tile.y + 1 < u_tiles.y) finest = max(finest, levelAt(tile + ivec2(0, 1)));
    uint mask = source[index];
    if (maskLevel(mask) < finest - 1) mask |= uniformMask(finest - 1);
    destination[index] = mask;
}
