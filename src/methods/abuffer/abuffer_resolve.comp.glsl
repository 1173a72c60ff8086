// A-buffer resolve: composite each pixel's list front to back over the background.
//
// Order: by key (depth, node index), unique per fragment, so exact duplicates are all kept.
// Fragments at exactly equal depth composite in node (arrival) order, which can vary between runs;
// only coincident overlapping surfaces are affected.
//
// The list is consumed by repeated selection: each step walks the list and takes the smallest key
// above the previous step's. O(n^2) node reads for n fragments, no length limit, no local arrays.
// This runs as a compute shader: the same code as a full-screen fragment shader lost fragments on
// llvmpipe (Mesa 22.3) at some pixels (caught by the CPU-reference test), in every formulation tried.
#include "starnt/bindings.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = STARNT_SSBO_ABUFFER_HEADS) readonly buffer Heads { uint heads[]; };
layout(std430, binding = STARNT_SSBO_ABUFFER_NODES) readonly buffer Nodes { uvec4 nodes[]; };
layout(binding = 0, rgba32f) writeonly uniform highp image2D u_output;

uniform ivec2 u_size;
#include "methods/common/background.glsl"

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= u_size.x || p.y >= u_size.y) return;
    uint head = heads[uint(p.y) * uint(u_size.x) + uint(p.x)];
    uint count = 0u;
    for (uint i = head; i != STARNT_ABUFFER_END; i = nodes[i].w) count++;

    vec3 color = vec3(0.0);
    float transmittance = 1.0;
    float previousDepth = -1.0;
    uint previousNode = 0u;
    for (uint k = 0u; k < count; ++k) {
        float bestDepth = 3.0;
        uint bestNode = STARNT_ABUFFER_END;
        for (uint i = head; i != STARNT_ABUFFER_END; i = nodes[i].w) {
            float d = uintBitsToFloat(nodes[i].z);
            bool afterPrevious = d > previousDepth || (d == previousDepth && i > previousNode);
            bool better = d < bestDepth || (d == bestDepth && i < bestNode);
            if (afterPrevious && better) {
                bestDepth = d;
                bestNode = i;
            }
        }
        uvec4 n = nodes[bestNode];
        vec4 f = vec4(unpackHalf2x16(n.x), unpackHalf2x16(n.y));
        color += transmittance * f.a * f.rgb;
        transmittance *= 1.0 - f.a;
        previousDepth = bestDepth;
        previousNode = bestNode;
    }
    imageStore(u_output, p, vec4(color + transmittance * backgroundAt(p), outputAlpha(transmittance)));
}
