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
const uint kLayerMaxKey = (1u << STARNT_PACKED_LAYER_KEY_BITS) - 1u;  // the empty layer's
const uint kLayerLowBits = 32u - uint(STARNT_PACKED_LAYER_KEY_BITS);      // of the first word, below the key: alpha's top
const uint kLayerAlphaLow = uint(STARNT_PACKED_LAYER_ALPHA_BITS) - kLayerLowBits;  // alpha's bits in the second word
const uint kLayerGShift = uint(STARNT_PACKED_LAYER_R_BITS);
const uint kLayerBShift = kLayerGShift + uint(STARNT_PACKED_LAYER_G_BITS);
const uint kLayerAShift = kLayerBShift + uint(STARNT_PACKED_LAYER_B_BITS);
// The keys below STARNT_PACKED_LAYER_EXACT_DEPTH (coarse) come first.
const uint kLayerCoarseKeys = (STARNT_PACKED_LAYER_EXACT_BITS - STARNT_PACKED_LAYER_NEAREST_BITS) >> STARNT_PACKED_LAYER_COARSE_SHIFT;

float layerSteps(int bits) { return float((1 << bits) - 1); }

const float kLayerLdrShare = float(STARNT_PACKED_LAYER_LDR_SHARE);
const float kLayerHdrScale = (1.0 - kLayerLdrShare) / float(STARNT_PACKED_LAYER_HDR_LOG2_RANGE);

// log2 r for r >= 1 read off its float bits (exponent plus mantissa fraction: exact at powers of two,
// linear between) and its inverse: no transcendental function in the per-fragment pack and unpack
// (packed_nearest.h; docs/DESIGN.md, "Corrected frames: three layers and no correction").
float bitsLog2(float r) { return float(floatBitsToUint(max(r, 1.0)) - kPackedOne) * (1.0 / 8388608.0); }
float bitsExp2(float y) { return uintBitsToFloat(kPackedOne + uint(max(y, 0.0) * 8388608.0)); }

uint layerColour(float c, int bits) {
    float r = sqrt(clamp(c, 0.0, exp2(2.0 * float(STARNT_PACKED_LAYER_HDR_LOG2_RANGE))));
    float x = r <= 1.0 ? kLayerLdrShare * r : kLayerLdrShare + kLayerHdrScale * bitsLog2(r);
    return uint(floor(x * layerSteps(bits) + 0.5));
}

float unpackedLayerColour(uint word, uint shift, int bits) {
    float x = float((word >> shift) & ((1u << uint(bits)) - 1u)) / layerSteps(bits);
    float r = x <= kLayerLdrShare ? x / kLayerLdrShare : bitsExp2((x - kLayerLdrShare) / kLayerHdrScale);
    return r * r;
}

uint layerKey(float z) {
    uint bits = floatBitsToUint(clamp(z, float(STARNT_PACKED_LAYER_NEAREST_DEPTH), 1.0));
    return bits >= STARNT_PACKED_LAYER_EXACT_BITS
               ? bits - STARNT_PACKED_LAYER_EXACT_BITS + kLayerCoarseKeys
               : (bits - STARNT_PACKED_LAYER_NEAREST_BITS) >> STARNT_PACKED_LAYER_COARSE_SHIFT;
}

// The window depth of a key: z itself in the exact range, the middle of its step below.
float depthOfLayerKey(uint key) {
    return uintBitsToFloat(key >= kLayerCoarseKeys
                               ? key - kLayerCoarseKeys + STARNT_PACKED_LAYER_EXACT_BITS
                               : (key << STARNT_PACKED_LAYER_COARSE_SHIFT) + STARNT_PACKED_LAYER_NEAREST_BITS +
                                     ((1u << STARNT_PACKED_LAYER_COARSE_SHIFT) >> 1));
}

// One layer's two words (packed_nearest.h), at `key` (layerKey).
uvec2 packLayerAtKey(uint key, vec4 c) {
    uint alpha = uint(floor(clamp(c.a, 0.0, 1.0) * layerSteps(STARNT_PACKED_LAYER_ALPHA_BITS) + 0.5));
    return uvec2((key << kLayerLowBits) | (alpha >> kLayerAlphaLow),
                 (alpha << kLayerAShift) | layerColour(c.r, STARNT_PACKED_LAYER_R_BITS) |
                     (layerColour(c.g, STARNT_PACKED_LAYER_G_BITS) << kLayerGShift) |
                     (layerColour(c.b, STARNT_PACKED_LAYER_B_BITS) << kLayerBShift));
}
uvec2 packLayer(float z, vec4 c) { return packLayerAtKey(layerKey(z), c); }

// The two layers after fragment `f` (packLayer) met them: the nearest, then the nearest with a
// larger key; on equal keys the layer already kept stays.
uvec4 insertLayer(uvec4 layers, uvec2 f) {
    uint key = f.x >> kLayerLowBits;
    uint first = layers.x >> kLayerLowBits;
    if (key < first) return uvec4(f, layers.xy);
    if (key > first && key < (layers.z >> kLayerLowBits)) return uvec4(layers.xy, f);
    return layers;
}

#ifdef STARNT_PACKED_THREE_LAYERS
// The nearest three keys after a fragment at window depth z, of straight colour and alpha c, met
// them: `layers` the nearest two, `third` the next. A fragment whose key equals a kept layer's is
// merged into it, behind it (the layer over the fragment: coplanar fragments composite in draw
// order, as the A-buffer's stable sort keeps them; left to the closed form they would lie behind
// the third layer: chess's board, docs/DESIGN.md, "Corrected frames: three layers and no
// correction"). Written for a core that runs both sides of a branch under a mask (llvmpipe): one
// unpack and one pack serve every case, the merge's inputs chosen by selects, so a fragment pays
// for one merge whatever it meets.
vec4 unpackLayer(uvec2 layer, out float z);
void insertThreeLayers(inout uvec4 layers, inout uvec2 third, float z, vec4 c) {
    uint key = layerKey(z);
    uint first = layers.x >> kLayerLowBits;
    uint second = layers.z >> kLayerLowBits;
    uint k3 = third.x >> kLayerLowBits;
    bool tie = key == first || key == second || key == k3;
    float keptDepth;
    vec4 kept = unpackLayer(key == first ? layers.xy : key == second ? layers.zw : third, keptDepth);
    vec4 behind = vec4(clamp(c.rgb, vec3(0.0), vec3(exp2(2.0 * float(STARNT_PACKED_LAYER_HDR_LOG2_RANGE)))), clamp(c.a, 0.0, 1.0));
    float alpha = kept.a + (1.0 - kept.a) * behind.a;
    vec3 merged = alpha > 0.0 ? (kept.a * kept.rgb + (1.0 - kept.a) * behind.a * behind.rgb) / alpha : kept.rgb;
    uvec2 f = packLayerAtKey(key, tie ? vec4(merged, alpha) : c);  // a tie shares the kept layer's key
    if (tie) {
        if (key == first) layers.xy = f;
        else if (key == second) layers.zw = f;
        else third = f;
    } else if (key < first) {
        third = layers.zw;
        layers = uvec4(f, layers.xy);
    } else if (key < second) {
        third = layers.zw;
        layers.zw = f;
    } else if (key < k3) {
        third = f;
    }
}
#endif

// C, a of a layer (all 0 where there is none) and its window depth (1 where there is none).
vec4 unpackLayer(uvec2 layer, out float z) {
    uint key = layer.x >> kLayerLowBits;
    if (key == kLayerMaxKey) {
        z = 1.0;
        return vec4(0.0);
    }
    z = depthOfLayerKey(key);
    uint alpha = ((layer.x & ((1u << kLayerLowBits) - 1u)) << kLayerAlphaLow) | (layer.y >> kLayerAShift);
    return vec4(unpackedLayerColour(layer.y, 0u, STARNT_PACKED_LAYER_R_BITS),
                unpackedLayerColour(layer.y, kLayerGShift, STARNT_PACKED_LAYER_G_BITS),
                unpackedLayerColour(layer.y, kLayerBShift, STARNT_PACKED_LAYER_B_BITS),
                float(alpha) / layerSteps(STARNT_PACKED_LAYER_ALPHA_BITS));
}
#endif
#endif
