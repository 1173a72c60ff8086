// Pass 3: statistics over ALL fragments, no depth test.
//   target 0 (RGBA32F, blend ONE/ONE):                 sum a_i C_i, sum a_i
//   target 1 (RGBA32F, blend ONE/ONE):                 sum C_i, N
//            (R32F: N alone, with STARNT_COUNT_ONLY: the STAR-NT inputs need no sum of C_i,
//            which only DFAOIT reads; 12 bytes a pixel less; RG32F for the tail-moment methods, below)
//   target 2 (R32F,    blend ZERO/ONE_MINUS_SRC_ALPHA): prod (1 - a_i)
//   with STARNT_TAIL_MOMENTS (hybrid-moments, full resolution), over the fragments behind pass 2's
//   layer only, u a logarithmic depth behind z2 (tail_moments_constants.h; CPU reference
//   nn::tailMomentsFromFragments):
//   target 3 (RGBA32F, blend ONE/ONE):                 sum a_i C_i u_i, sum a_i u_i
//   target 4 (RGBA32F, blend ONE/ONE):                 sum a_i C_i u_i^2, sum a_i u_i^2
//   with STARNT_SUMS_ONLY (corrected interpolated frames: the closed form behind the nearest layer
//   reads nothing else): target 0 as above, target 1 the transmittance; no count, no moments.
//   and with STARNT_PACKED_NEAREST (corrected frames in one geometry pass, no pass 1):
//   target 2 (RGBA32F, blend equation GL_MIN):        the nearest fragment (packed_nearest.glsl)
//   or with STARNT_PACKED_TWO_LAYERS (framebuffer fetch, the tail-moment methods):
//   target 2 (RGBA32UI, read and rewritten):          the nearest two fragments (packed_nearest.h)
//   and with STARNT_PACKED_THREE_LAYERS:
//   target 4 (RGBA32UI, read and rewritten):          the third nearest (insertThreeLayers), the
//                                                      reference depth and the pivot (packed_nearest.h)
//   and with STARNT_BEHIND_MOMENTS (corrected frames of the tail-moment methods), u a fragment's
//   depth behind the reference depth (ordered_behind.glsl), over every fragment:
//   target 1 (the count's, RG32F, blend ONE/ONE):      sum a u^2, sum -ln(1 - a) (the optical
//                                                      depth in place of prod (1 - a): both added)
//   the next target (2, or 3 after the packed layer) (RGBA32F, blend ONE/ONE): sum a C u, sum a u
//   With STARNT_BEHIND_SECOND (real frames whose interpolated frames find two layers,
//   STARNT_PACKED_TWO_LAYERS) the same over the fragments behind pass 2's layer only, in v = u - u2.
//   Their real frames (with the tail moments, not STARNT_SUMS_ONLY) sum the same over every
//   fragment, the same float operations, so that their composite recentres them as the
//   interpolated frames' does (STARNT_BEHIND_BESIDE_COUNT): sum a u^2 beside the count in target 1
//   (RG32F: N, sum a u^2) and (sum a C u, sum a u) in target 5 (RGBA32F, blend ONE/ONE).
layout(location = 0) out vec4 outAlphaColor;
#ifdef STARNT_SUMS_ONLY
layout(location = 1) out vec4 outTransmittance;
#if defined(STARNT_PACKED_TWO_LAYERS)
// The nearest two fragments, by reading and rewriting the target in draw order
// (EXT_shader_framebuffer_fetch; packed_nearest.h): target 2 is RGBA32UI, not blended.
#include "methods/neural/temporal/packed_nearest.glsl"
layout(location = 2) inout highp uvec4 outPackedLayers;
#ifdef STARNT_PACKED_THREE_LAYERS
layout(location = 4) inout highp uvec4 outThirdLayer;
#endif
#define STARNT_BEHIND_MOMENT1_LOCATION 3
#elif defined(STARNT_PACKED_NEAREST)
#include "methods/neural/temporal/packed_nearest.glsl"
layout(location = 2) out vec4 outPackedNearest;
#define STARNT_BEHIND_MOMENT1_LOCATION 3
#else
#define STARNT_BEHIND_MOMENT1_LOCATION 2
#endif
#else
layout(location = 1) out vec4 outColorCount;
layout(location = 2) out vec4 outTransmittance;
#define STARNT_BEHIND_MOMENT1_LOCATION 5
#define STARNT_BEHIND_BESIDE_COUNT
#if defined(STARNT_BEHIND_MOMENTS) && !defined(STARNT_COUNT_ONLY)
#error "the moments behind pass 1's fragment share the count's target: count only"
#endif
#endif
#ifdef STARNT_BEHIND_MOMENTS
#include "methods/neural/temporal/ordered_behind.glsl"
layout(location = STARNT_BEHIND_MOMENT1_LOCATION) out vec4 outBehindMoment1;
#ifndef STARNT_PACKED_THREE_LAYERS  // (there the reference comes with the third layer's texel)
layout(binding = 1) uniform highp sampler2D u_reference;  // reference_depth.frag.glsl, one texel a tile
#endif
#endif
#ifdef STARNT_TAIL_MOMENTS
layout(location = 3) out vec4 outTailMoment1;
layout(location = 4) out vec4 outTailMoment2;
layout(binding = 0) uniform highp sampler2D u_secondDepth;  // pass 2's depth, 1 where it drew nothing
#include "methods/hybrid_moments/tail_moments_constants.h"
#endif

void main() {
    // A fragment on the far plane (window depth 1: beyond it too, under an engine's depth clamp) is
    // one that passes 1 and 2 drop by their depth test (LESS against the cleared 1); every pass 3
    // drops it too, real and interpolated, so that no frame shows what the others do not, and no
    // sums stand where pass 1 left the pixel empty: the inference neither reads those nor writes 0
    // back there for the interpolated frames' pass 3 (NeuralPasses::sharedSumsClearedByInference).
    if (gl_FragCoord.z >= 1.0) discard;
    vec4 s = fetchSurfaceOrDiscard();
    outAlphaColor = vec4(s.rgb * s.a, s.a);
#if defined(STARNT_SUMS_ONLY)
#elif defined(STARNT_COUNT_ONLY)
    outColorCount = vec4(1.0, 0.0, 0.0, 0.0);  // an R32F target keeps .r (RG32F: .g below)
#else
    outColorCount = vec4(s.rgb, 1.0);
#endif
    outTransmittance = vec4(0.0, 0.0, 0.0, s.a);
#if defined(STARNT_PACKED_TWO_LAYERS)
#ifdef STARNT_PACKED_THREE_LAYERS
    // The depth target only marks the pixels a fragment reached, for the composite's early test
    // (GREATER than its far-plane triangle): a fragment on the far plane marks its pixel too, so
    // that a composite that writes back the clear values (NeuralPasses::compositeClearsTargets)
    // reaches every pixel this pass wrote.
    gl_FragDepth = min(gl_FragCoord.z, uintBitsToFloat(0x3F7FFFFFu));
    uvec4 layers = outPackedLayers;
    uvec4 thirdTexel = outThirdLayer;  // the third layer, and the reference depth beside it
    uvec2 third = thirdTexel.xy;
#ifdef STARNT_BEHIND_MOMENTS
    // The moments are summed about the u of the pixel's first fragment (the pivot, kept in .w, where
    // the composite reads it): near the pixel's own fragments, so that their recentring at the third
    // layer keeps the spread of a thin stack that lies far behind the reference (ordered_behind.glsl;
    // docs/DESIGN.md, "Far from the reference: the moments about the pixel's first fragment"). No
    // layer yet: this is the pixel's first fragment.
    float reference = uintBitsToFloat(thirdTexel.z);
    float u = depthBehindReference(gl_FragCoord.z, reference);
    float pivot = (layers.x >> kLayerLowBits) == kLayerMaxKey ? u : uintBitsToFloat(thirdTexel.w);
#endif
    insertThreeLayers(layers, third, gl_FragCoord.z, s);
    outPackedLayers = layers;
#ifdef STARNT_BEHIND_MOMENTS
    outThirdLayer = uvec4(third, thirdTexel.z, floatBitsToUint(pivot));
#else
    outThirdLayer = uvec4(third, thirdTexel.zw);
#endif
#else
    outPackedLayers = insertLayer(outPackedLayers, packLayer(gl_FragCoord.z, s));
#endif
#elif defined(STARNT_PACKED_NEAREST)
    outPackedNearest = packNearest(gl_FragCoord.z, s);
#endif
#ifdef STARNT_TAIL_MOMENTS
    float second = texelFetch(u_secondDepth, ivec2(gl_FragCoord.xy), 0).r;
#endif
#ifdef STARNT_BEHIND_MOMENTS
#ifndef STARNT_PACKED_THREE_LAYERS
    float reference = texelFetch(u_reference, ivec2(gl_FragCoord.xy) / STARNT_ORDERED_REFERENCE_TILE, 0).r;
#endif
#if defined(STARNT_PACKED_THREE_LAYERS)
    float behind = u - pivot;
#elif defined(STARNT_BEHIND_SECOND)
    // Behind pass 2's layer only, in v = u - u2 (ordered_behind.glsl: orderedClosedFormBehindSecondFromMoments).
    float behind = gl_FragCoord.z > second ? depthBehindReference(gl_FragCoord.z, reference) - depthBehindReference(second, reference)
                                           : 0.0;
#else
    float behind = depthBehindReference(gl_FragCoord.z, reference);
#endif
    outBehindMoment1 = vec4(s.rgb * s.a, s.a) * behind;
#ifdef STARNT_BEHIND_BESIDE_COUNT
    outColorCount.g = outBehindMoment1.a * behind;
#else
    outTransmittance = vec4(outBehindMoment1.a * behind, opticalDepthOf(s.a), 0.0, 0.0);
#endif
#endif
#ifdef STARNT_TAIL_MOMENTS
    // tail_moments_constants.h: a logarithmic depth behind z2 (1 - second > 0 wherever z > second).
    float u = gl_FragCoord.z > second
                  ? log(1.0 + (gl_FragCoord.z - second) / (float(STARNT_TAIL_MOMENT_DEPTH_SCALE) * (1.0 - second)))
                  : 0.0;
    outTailMoment1 = vec4(s.rgb * s.a, s.a) * u;
    outTailMoment2 = outTailMoment1 * u;
#endif
}
