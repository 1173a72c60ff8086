// Reads what passes 1-3 left for this pixel (the GPU side of nn::PixelSums), passes 2 and 3
// upsampled to full resolution when they ran at a reduced scale (CPU reference:
// upsamplePassSums in upsample_cpu.hpp), and computes the guarded quantities both networks use. STARNT_EPS_TRANSMITTANCE and STARNT_EPS_TAIL_ALPHA are
// defined from nn::kTransmittanceEpsilon / nn::kTailAlphaEpsilon when the program is built, so the
// CPU reference and the shader share one definition.
#include "starnt/bindings.h"
layout(binding = STARNT_UNIT_NEAREST) uniform sampler2D u_nearest;        // C1, a1
layout(binding = STARNT_UNIT_SECOND) uniform sampler2D u_second;         // C2, a2
layout(binding = STARNT_UNIT_ALPHA_COLOR) uniform sampler2D u_alphaColor;     // sum a C, sum a
layout(binding = STARNT_UNIT_COLOR_COUNT) uniform sampler2D u_colorCount;     // sum C, N (N in .r with STARNT_COUNT_ONLY)
layout(binding = STARNT_UNIT_TRANSMITTANCE) uniform sampler2D u_transmittance;  // prod (1 - a)
#ifdef STARNT_SPLIT_ALPHA
// DFAOIT's narrow layers: C1 and C2 in RGB10_A2, their alphas here (a1, a2). Full resolution only.
layout(binding = STARNT_UNIT_LAYER_ALPHA) uniform sampler2D u_layerAlpha;
#include "methods/neural/half_targets.glsl"  // narrowLayerColor
#ifndef STARNT_INPUTS_FULL_RESOLUTION
#error "narrow layers need every pass at full resolution"
#endif
#endif
#include "methods/neural/upsample.glsl"

struct PixelSums {
    vec3 c1;
    float a1;
    vec3 c2;
    float a2;
    float count;
    float sumAlpha;
    vec3 sumAlphaColor;
    vec3 sumColor;
    float transmittance;
};

PixelSums readPixelSums(ivec2 p) {
    PixelSums s;
    vec4 f1 = texelFetch(u_nearest, p, 0);
#ifdef STARNT_SPLIT_ALPHA
    vec2 layerAlpha = texelFetch(u_layerAlpha, p, 0).rg;
    f1 = vec4(narrowLayerColor(f1), layerAlpha.r);
#endif
    if (f1.a == 0.0) {
        // Pass 1 runs at full resolution: no nearest fragment means no fragment at all. Without
        // this, reduced passes 2/3 would leak their neighbours' sums into background pixels
        // (halos at every silhouette).
        s.c1 = s.c2 = s.sumAlphaColor = s.sumColor = vec3(0.0);
        s.a1 = s.a2 = s.count = s.sumAlpha = 0.0;
        s.transmittance = 1.0;
        return s;
    }
#if defined(STARNT_INPUTS_FULL_RESOLUTION)
    vec4 f2 = texelFetch(u_second, p, 0);
#ifdef STARNT_SPLIT_ALPHA
    f2 = vec4(narrowLayerColor(f2), layerAlpha.g);
#endif
#else
    // Pass 2 at full resolution (pass 3 reduced): its own pixel only. The inference may write the
    // output in place over pass 2's target then (NeuralPasses::outputSlot), so no neighbour may be
    // read, not even with weight 0. (A texel without a fragment reads as zero, as the alpha-weighted
    // upsampling gives.)
#ifdef STARNT_UPSAMPLE_JOINT
    // The tap weights depend on the image size only: pass 2 reuses pass 3's when they match.
    JointTaps taps3 = jointTaps(p, u_pass3Size);
#endif
    vec4 f2;
    if (u_pass2Size == u_fullSize) {
        f2 = texelFetch(u_second, p, 0);
        f2 = f2.a > 0.0 ? f2 : vec4(0.0);
    } else {
#ifdef STARNT_UPSAMPLE_JOINT
        f2 = upsampleJointAlphaWeighted(u_second, u_pass2Size == u_pass3Size ? taps3 : jointTaps(p, u_pass2Size));
#else
        f2 = upsampleAlphaWeighted(u_second, p, u_pass2Size);
#endif
    }
#endif
    s.c1 = f1.rgb;
    s.a1 = f1.a;
    s.c2 = f2.rgb;
    s.a2 = f2.a;
#ifndef STARNT_INPUTS_FULL_RESOLUTION
    // Reduced passes: the pass-3 targets hold each texel's tail (tail_resolve.frag.glsl). The tails
    // are interpolated, and the pixel adds back its own two layers.
#ifdef STARNT_UPSAMPLE_JOINT
    vec4 tailAc = upsampleJoint(u_alphaColor, p, u_pass3Size, taps3);
    vec4 tailCn = upsampleJoint(u_colorCount, p, u_pass3Size, taps3);
    float tailT = upsampleJoint(u_transmittance, p, u_pass3Size, taps3).r;
#else
    vec4 tailAc = upsampleFiltered(u_alphaColor, p, u_pass3Size);
    vec4 tailCn = upsampleFiltered(u_colorCount, p, u_pass3Size);
    float tailT = upsampleFiltered(u_transmittance, p, u_pass3Size).r;
#endif
    float has1 = s.a1 > 0.0 ? 1.0 : 0.0, has2 = s.a2 > 0.0 ? 1.0 : 0.0;
    s.sumAlphaColor = tailAc.rgb + s.a1 * s.c1 + s.a2 * s.c2;
    s.sumAlpha = tailAc.a + s.a1 + s.a2;
#ifdef STARNT_COUNT_ONLY
    s.sumColor = vec3(0.0);  // not kept: only DFAOIT reads it
    s.count = tailCn.r + has1 + has2;
#else
    s.sumColor = tailCn.rgb + has1 * s.c1 + has2 * s.c2;
    s.count = tailCn.a + has1 + has2;
#endif
    s.transmittance = tailT * (1.0 - s.a1) * (1.0 - s.a2);
#else
    vec4 ac = upsampleLinear(u_alphaColor, p, u_pass3Size);
    vec4 cn = upsampleLinear(u_colorCount, p, u_pass3Size);
    s.sumAlphaColor = ac.rgb;
    s.sumAlpha = ac.a;
#ifdef STARNT_COUNT_ONLY
    s.sumColor = vec3(0.0);
    s.count = cn.r;
#else
    s.sumColor = cn.rgb;
    s.count = cn.a;
#endif
    s.transmittance = upsampleLinear(u_transmittance, p, u_pass3Size).r;
#endif
    return s;
}

// Exact composite of the two peeled fragments: a1 C1 + (1 - a1) a2 C2.
vec3 exactTwo(PixelSums s) { return s.a1 * s.c1 + (1.0 - s.a1) * s.a2 * s.c2; }
// Transmittance through the two peeled fragments.
float twoLayerTransmittance(PixelSums s) { return (1.0 - s.a1) * (1.0 - s.a2); }
// Premultiplied colour of the tail (fragments 3..N): sum a C minus the peeled ones.
vec3 tailPremultiplied(PixelSums s) { return s.sumAlphaColor - s.a1 * s.c1 - s.a2 * s.c2; }
float tailAlphaSum(PixelSums s) { return s.sumAlpha - s.a1 - s.a2; }

// STAR-NT's tail features (docs/DESIGN.md, "Pipeline and formats") with the guards of nn::starntFeatures: the tail's own
// transmittance t_tail = T_all / T2 and its alpha-weighted mean colour C_tilde.
float tailTransmittance(PixelSums s) {
    float t2 = twoLayerTransmittance(s);
    return t2 > STARNT_EPS_TRANSMITTANCE ? clamp(s.transmittance / t2, 0.0, 1.0) : 0.0;
}
vec3 tailMeanColor(PixelSums s) {
    float tailAlpha = tailAlphaSum(s);
    return tailAlpha > STARNT_EPS_TAIL_ALPHA ? max(tailPremultiplied(s) / tailAlpha, vec3(0.0)) : vec3(0.0);
}

// STAR-NT's five network inputs in their order (nn::starntFeatures): t_tail, N, C_tilde.rgb.
void starntInputs(PixelSums s, out float x[5]) {
    vec3 cTilde = tailMeanColor(s);
    x[0] = tailTransmittance(s);
    x[1] = s.count;
    x[2] = cTilde.r;
    x[3] = cTilde.g;
    x[4] = cTilde.b;
}

// The composite of the three-pass methods (starnt, hybrid, starnt-residual; CPU reference
// compositeThreeLayersExact in src/train/features.cpp): the two peeled layers exactly, the tail exactly
// for N <= 3 (the third fragment follows from the sums), `deepTail` for N > 3, then the background.
// The tail counts the fragments the two peeled layers do not hold: N - 2 wherever depths differ, but
// more where layers are coplanar (pass 2 peels behind pass 1's depth, so it finds nothing among
// fragments at that same depth; pass 3 sums them all). There, with no second layer and two or
// more fragments left, the deep tail is the order-free closed form: `deepTail` (the network, which
// never saw a pixel without a second layer and a tail: networkApplies) does not apply
// (docs/DESIGN.md, "Coplanar layers").
float tailCount(PixelSums s) { return s.count - (s.a1 > 0.0 ? 1.0 : 0.0) - (s.a2 > 0.0 ? 1.0 : 0.0); }
vec3 threeLayerComposite(PixelSums s, vec3 deepTail, vec3 background) {
    vec3 tail;
    float n = tailCount(s);
    if (n < 0.5) tail = vec3(0.0);
    else if (n < 1.5) tail = max(tailPremultiplied(s), vec3(0.0));
    else if (s.a2 > 0.0) tail = deepTail;
    else tail = (1.0 - tailTransmittance(s)) * tailMeanColor(s);
    return exactTwo(s) + twoLayerTransmittance(s) * tail + s.transmittance * background;
}
