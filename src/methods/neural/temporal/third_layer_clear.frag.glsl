// The clear of the third layer's target before an interpolated frame's pass 3 (three layers;
// packed_nearest.h): no layer (STARNT_PACKED_LAYER_EMPTY, 0) and, beside it, the float bits of the
// pixel's reference depth, which pass 3 then reads with the layers it fetches anyway.
#include "methods/neural/temporal/packed_nearest.h"
#include "methods/neural/temporal/reprojection_constants.h"

layout(binding = 1) uniform highp sampler2D u_reference;  // reference_depth.frag.glsl, one texel a tile

layout(location = 0) out highp uvec4 o_thirdLayer;

void main() {
    float reference = texelFetch(u_reference, ivec2(gl_FragCoord.xy) / STARNT_ORDERED_REFERENCE_TILE, 0).r;
    o_thirdLayer = uvec4(STARNT_PACKED_LAYER_EMPTY, 0u, floatBitsToUint(reference), 0u);
}
