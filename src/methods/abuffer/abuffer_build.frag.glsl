// A-buffer build: every fragment is appended to its pixel's linked list.
// Node layout (uvec4): x = packHalf2x16(r, g), y = packHalf2x16(b, a), z = depth bits, w = next.
// The node counter keeps counting past the pool's capacity, so the host sees how many nodes the
// frame needed and can grow the pool and render again: no fragment is ever silently dropped.
#include "starnt/bindings.h"

// The depth test against the engine's opaque depth (OpaqueScene) must drop a fragment before it
// is appended: a late test would run after the shader's stores.
layout(early_fragment_tests) in;

layout(std430, binding = STARNT_SSBO_ABUFFER_HEADS) coherent buffer Heads { uint heads[]; };
layout(std430, binding = STARNT_SSBO_ABUFFER_NODES) writeonly buffer Nodes { uvec4 nodes[]; };
layout(std430, binding = STARNT_SSBO_ABUFFER_COUNTERS) coherent buffer Counters { uint counters[4]; };
#ifdef STARNT_ABUFFER_CAPTURE_ORDER
// Capture mode (reference tools and the trainer): node.x holds the submission order key instead
// of the half-float colour, and the full-precision colour goes to a second array. gl_PrimitiveID
// in a fragment shader needs GLSL ES 3.20 on ES; the capture is a desktop-only tool.
layout(std430, binding = STARNT_SSBO_ABUFFER_ORDERS) writeonly buffer Extras { uvec4 extras[]; };
uniform int u_drawIndex;
#endif

uniform uint u_capacity;
uniform int u_width;

void main() {
    vec4 s = fetchSurfaceOrDiscard();
    uint index = atomicAdd(counters[0], 1u);
    if (index < u_capacity) {
        uint pixel = uint(gl_FragCoord.y) * uint(u_width) + uint(gl_FragCoord.x);
        uint next = atomicExchange(heads[pixel], index);
#ifdef STARNT_ABUFFER_CAPTURE_ORDER
        uint order = (uint(u_drawIndex) << 24) | (uint(gl_PrimitiveID) & 0xFFFFFFu);
        nodes[index] = uvec4(order, packHalf2x16(s.ba), floatBitsToUint(gl_FragCoord.z), next);
        extras[index] = floatBitsToUint(s);
#else
        nodes[index] = uvec4(packHalf2x16(s.rg), packHalf2x16(s.ba), floatBitsToUint(gl_FragCoord.z), next);
#endif
    }
}
