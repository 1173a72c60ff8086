// Stage "infer", spatially selective (beyond the paper, docs/DESIGN.md, "Adaptive tiles and tile-guided resolution"), step 1 of 2: the network only at
// the corner pixels of the quadtree leaves of the last real frame's tiles. Writes (f(x), 1) where
// the network applies and (0, 0) where it does not; other pixels are discarded (left stale: the
// fill pass reads corners only).
#include "starnt/bindings.h"
#include "methods/neural/tiles/tile_masks.glsl"

layout(std430, binding = STARNT_SSBO_TILE_MASKS_IN) readonly buffer Masks { uint masks[]; };
uniform ivec2 u_tiles;
#include "methods/neural/network_hdr.glsl"
layout(location = 0) out vec4 outNetwork;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    ivec2 tile = p / STARNT_TILE_SIZE;
    ivec4 corners = leafCorners(leafOf(masks[tile.y * u_tiles.x + tile.x], p), u_fullSize);
    if ((p.x != corners.x && p.x != corners.z) || (p.y != corners.y && p.y != corners.w)) discard;
    PixelSums s = readPixelSums(p);
    if (!networkApplies(s)) {
        outNetwork = vec4(0.0);
        return;
    }
    outNetwork = vec4(evaluateNetwork(s), 1.0);
}
