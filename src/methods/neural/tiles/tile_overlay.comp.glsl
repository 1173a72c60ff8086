// Debug view: the composite with each occupied tile tinted by its level (0 blue, 1 green,
// 2 yellow, 3 red) and the quadtree leaf borders darkened.
#include "starnt/bindings.h"
#include "methods/neural/tiles/tile_masks.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D u_composite;
layout(binding = 0, rgba32f) writeonly uniform highp image2D u_overlay;
layout(std430, binding = STARNT_SSBO_TILE_MASKS_IN) readonly buffer Masks { uint masks[]; };
layout(std430, binding = STARNT_SSBO_TILE_OCCUPANCY) readonly buffer Occupancy { uint occupancy[]; };
uniform ivec2 u_size;
uniform ivec2 u_tiles;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= u_size.x || p.y >= u_size.y) return;
    vec3 color = texelFetch(u_composite, p, 0).rgb;
    ivec2 tile = p / STARNT_TILE_SIZE;
    int index = tile.y * u_tiles.x + tile.x;
    if (occupancy[index] != 0u) {
        uint mask = masks[index];
        const vec3 tint[4] = vec3[4](vec3(0.1, 0.3, 1.0), vec3(0.1, 0.9, 0.2), vec3(1.0, 0.9, 0.1), vec3(1.0, 0.15, 0.1));
        color = mix(color, tint[maskLevel(mask)], 0.45);
        ivec3 leaf = leafOf(mask, p);
        ivec2 local = p - leaf.xy;
        if (local.x == 0 || local.y == 0) color *= 0.5;
    }
    imageStore(u_overlay, p, vec4(color, 1.0));
}
