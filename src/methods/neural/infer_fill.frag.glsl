// Stage "infer", spatially selective, step 2 of 2: each pixel where the network applies takes the
// bilinear interpolation of its leaf's corner outputs, weighted to the corners where the network
// applied; with no such corner it evaluates the network itself. Then the method's composite.
#include "starnt/bindings.h"
#include "methods/neural/tiles/tile_masks.glsl"

layout(std430, binding = STARNT_SSBO_TILE_MASKS_IN) readonly buffer Masks { uint masks[]; };
layout(binding = STARNT_UNIT_CORNER_NETWORK) uniform sampler2D u_cornerNetwork;
uniform ivec2 u_tiles;
#include "methods/neural/half_targets.glsl"
#include "methods/neural/network_hdr.glsl"
layout(location = 0) out vec4 outColor;

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    PixelSums s = readPixelSums(p);
    vec3 network = vec3(0.0);
    if (networkApplies(s)) {
        ivec2 tile = p / STARNT_TILE_SIZE;
        ivec4 c = leafCorners(leafOf(masks[tile.y * u_tiles.x + tile.x], p), u_fullSize);
        float u = c.z > c.x ? float(p.x - c.x) / float(c.z - c.x) : 0.0;
        float v = c.w > c.y ? float(p.y - c.y) / float(c.w - c.y) : 0.0;
        vec4 n00 = texelFetch(u_cornerNetwork, c.xy, 0), n10 = texelFetch(u_cornerNetwork, ivec2(c.z, c.y), 0);
        vec4 n01 = texelFetch(u_cornerNetwork, ivec2(c.x, c.w), 0), n11 = texelFetch(u_cornerNetwork, c.zw, 0);
        vec4 w = vec4((1.0 - u) * (1.0 - v) * n00.a, u * (1.0 - v) * n10.a, (1.0 - u) * v * n01.a, u * v * n11.a);
        float weight = w.x + w.y + w.z + w.w;
        if (weight > 0.0) {
            network = (w.x * n00.rgb + w.y * n10.rgb + w.z * n01.rgb + w.w * n11.rgb) / weight;
        } else {
            network = evaluateNetwork(s);
        }
    }
    outColor = targetValue(vec4(compositePixel(s, network), outputAlpha(s.transmittance)));
}
