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

#ifdef STARNT_PACKED_TWO_LAYERS
uint packedColourSteps(float c, float steps) {
    float r = sqrt(max(c, 0.0));
    return uint(floor(r / (1.0 + r) * steps + 0.5));
}

float unpackedColourSteps(uint p, float steps) {
    float x = float(p) / steps;
    float r = x / (1.0 - x);
    return r * r;
}

// One layer's two words (packed_nearest.h).
uvec2 packLayer(float z, vec4 c) {
    uint alpha = uint(floor(clamp(c.a, 0.0, 1.0) * float(STARNT_PACKED_STEPS) + 0.5));
    return uvec2((packedDepthKey(z) << STARNT_PACKED_PAYLOAD_BITS) | alpha,
                 packedColour(c.r) | (packedColour(c.g) << 11) |
                     (packedColourSteps(c.b, float(STARNT_PACKED_BLUE_STEPS)) << 22));
}

// The two layers after fragment `f` (packLayer) met them: the nearest, then the nearest with a
// larger key; on equal keys the layer already kept stays.
uvec4 insertLayer(uvec4 layers, uvec2 f) {
    uint key = f.x >> STARNT_PACKED_PAYLOAD_BITS;
    uint first = layers.x >> STARNT_PACKED_PAYLOAD_BITS;
    if (key < first) return uvec4(f, layers.xy);
    if (key > first && key < (layers.z >> STARNT_PACKED_PAYLOAD_BITS)) return uvec4(layers.xy, f);
    return layers;
}

// C, a of a layer (all 0 where there is none) and its window depth (1 where there is none), at the
// middle of its key's depth interval.
vec4 unpackLayer(uvec2 layer, out float z) {
    uint key = layer.x >> STARNT_PACKED_PAYLOAD_BITS;
    if (key == kPackedMaxKey) {
        z = 1.0;
        return vec4(0.0);
    }
    z = depthOfKey(key);
    return vec4(unpackedColour(layer.y & kPackedPayloadMask), unpackedColour((layer.y >> 11) & kPackedPayloadMask),
                unpackedColourSteps(layer.y >> 22, float(STARNT_PACKED_BLUE_STEPS)),
                float(layer.x & kPackedPayloadMask) / float(STARNT_PACKED_STEPS));
}
#endif
#endif
