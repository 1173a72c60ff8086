// The nearest fragment found by MIN blending (packed_nearest.h states the layout; CPU reference
// temporal::packNearest / unpackNearest, the same float and integer operations).
#ifndef STARNT_PACKED_NEAREST_GLSL
#define STARNT_PACKED_NEAREST_GLSL
#include "methods/neural/temporal/packed_nearest.h"

const uint kPackedMaxKey = (1u << STARNT_PACKED_KEY_BITS) - 1u;  // the empty pixel's
const uint kPackedPayloadMask = (1u << STARNT_PACKED_PAYLOAD_BITS) - 1u;
const uint kPackedOne = 0x3F800000u;  // the bits of 1.0

uint packedDepthKey(float z) {
    uint w = floatBitsToUint(clamp(1.0 - z, 0.0, 1.0));
    return min((kPackedOne - w) >> STARNT_PACKED_KEY_SHIFT, kPackedMaxKey - 1u);
}

uint packedColour(float c) {
    float r = sqrt(max(c, 0.0));
    return uint(floor(r / (1.0 + r) * float(STARNT_PACKED_STEPS) + 0.5));
}

float unpackedColour(uint p) {
    float x = float(p) / float(STARNT_PACKED_STEPS);
    float r = x / (1.0 - x);
    return r * r;
}

float packedBits(uint key, uint payload) {
    return uintBitsToFloat(0x40000000u | (key << STARNT_PACKED_PAYLOAD_BITS) | payload);
}

// The window depth a key stands for: the middle of its depth interval.
float depthOfKey(uint key) {
    return 1.0 - uintBitsToFloat(kPackedOne - (key << STARNT_PACKED_KEY_SHIFT) - (1u << (STARNT_PACKED_KEY_SHIFT - 1)));
}

// The window depth z stands for in the packed layer (what unpackNearest returns for the fragment).
float keyedDepth(float z) { return depthOfKey(packedDepthKey(z)); }

// What a fragment at window depth z with colour and alpha `c` blends in.
vec4 packNearest(float z, vec4 c) {
    uint key = packedDepthKey(z);
    uint alpha = uint(floor(clamp(c.a, 0.0, 1.0) * float(STARNT_PACKED_STEPS) + 0.5));
    return vec4(packedBits(key, packedColour(c.r)), packedBits(key, packedColour(c.g)), packedBits(key, packedColour(c.b)),
                packedBits(key, alpha));
}

// C1, a1 of the nearest fragment (all 0 for an empty pixel) and its window depth (1 for an empty
// pixel), at the middle of its key's depth interval.
vec4 unpackNearest(vec4 encoded, out float z) {
    uvec4 bits = floatBitsToUint(encoded);
    uint key = (bits.a >> STARNT_PACKED_PAYLOAD_BITS) & kPackedMaxKey;
    if (key == kPackedMaxKey) {
        z = 1.0;
        return vec4(0.0);
    }
    z = depthOfKey(key);
    uvec4 payload = bits & uvec4(kPackedPayloadMask);
    return vec4(unpackedColour(payload.r), unpackedColour(payload.g), unpackedColour(payload.b),
                float(payload.a) / float(STARNT_PACKED_STEPS));
}
#endif
