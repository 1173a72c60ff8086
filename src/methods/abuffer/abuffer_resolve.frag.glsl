// A-buffer resolve: gather the pixel's list, sort it by depth (insertion sort; ties broken by the
// packed colour so equal-depth fragments resolve the same way every run), composite front to
// back over the background. Lists longer than STARNT_ABUFFER_MAX_SORT are not truncated: the
// pixel reports its length in counters[2] and the host recompiles with a larger array and
// resolves again.
#include "shaders/shared_constants.h"

layout(std430, binding = STARNT_SSBO_ABUFFER_HEADS) readonly buffer Heads { uint heads[]; };
layout(std430, binding = STARNT_SSBO_ABUFFER_NODES) readonly buffer Nodes { uvec4 nodes[]; };
layout(std430, binding = STARNT_SSBO_ABUFFER_COUNTERS) coherent buffer Counters { uint counters[4]; };

uniform int u_width;
uniform vec3 u_background;
layout(location = 0) out vec4 outColor;

bool nearer(uvec3 a, uvec3 b) {
    if (a.x != b.x) return a.x < b.x;  // non-negative float depth: bit order == value order
    if (a.y != b.y) return a.y < b.y;
    return a.z < b.z;
}

void main() {
    uint pixel = uint(gl_FragCoord.y) * uint(u_width) + uint(gl_FragCoord.x);
    uvec3 list[STARNT_ABUFFER_MAX_SORT];  // (depth bits, rg, ba)
    uint count = 0u;
    for (uint i = heads[pixel]; i != STARNT_ABUFFER_END; i = nodes[i].w) {
        if (count < uint(STARNT_ABUFFER_MAX_SORT)) list[count] = nodes[i].zxy;
        count++;
    }
    atomicMax(counters[1], count);
    if (count > uint(STARNT_ABUFFER_MAX_SORT)) {
        atomicMax(counters[2], count);
        outColor = vec4(1.0, 0.0, 1.0, 1.0);
        return;
    }
    // Insertion sort. Written so that list[j - 1] is only read when j > 0: the form
    // `while (j > 0u && nearer(key, list[j - 1u]))` mis-sorted on llvmpipe (Mesa 22.3), which
    // evaluated the out-of-range read; caught by the CPU-reference test.
    for (uint i = 1u; i < count; ++i) {
        uvec3 key = list[i];
        uint j = i;
        for (; j > 0u; --j) {
            uvec3 other = list[j - 1u];
            if (!nearer(key, other)) break;
            list[j] = other;
        }
        list[j] = key;
    }
    vec3 color = vec3(0.0);
    float transmittance = 1.0;
    for (uint i = 0u; i < count; ++i) {
        vec4 f = vec4(unpackHalf2x16(list[i].y), unpackHalf2x16(list[i].z));
        color += transmittance * f.a * f.rgb;
        transmittance *= 1.0 - f.a;
    }
    outColor = vec4(color + transmittance * u_background, 1.0);
}
