// A corrected interpolated frame (`--temporal-mode correct`; temporal::correctedPixel states the
// rule and is its CPU reference): pass 1 and pass 3 (or pass 3 alone, below) rendered at the new camera, no pass 2, no
// inference, no search. What lies behind the fresh nearest layer is the closed form of the fresh
// sums plus the network's correction of the last real frame, resampled where the fresh nearest
// point lay in that frame: bilinearly over the texels whose kept nearest surface is the same one
// (inverse view depth within STARNT_TEMPORAL_SAME_SURFACE). Where none is (the surface was hidden
// or off screen), the closed form alone. With STARNT_PACKED_NEAREST (one geometry pass, no pass 1):
// the nearest fragment and its depth come from pass 3's MIN-blended target (packed_nearest.glsl).
// With STARNT_ORDERED_BEHIND (the tail-moment methods) the closed form weighs what lies behind the
// nearest layer by depth (ordered_behind.glsl), from pass 3's moments; the transmittance then comes
// as an optical depth beside sum a u^2 in one target (pass3_accumulate.frag.glsl), unit 6, and unit
// 3 is not read.
#include "methods/neural/temporal/reprojection_constants.h"
#include "methods/neural/temporal/closed_form_behind.glsl"
#include "methods/neural/half_targets.glsl"

#if defined(STARNT_PACKED_TWO_LAYERS)
// The tail-moment methods where framebuffer fetch exists: the nearest two layers, packed
// (packed_nearest.h), and what lies behind the second weighed by depth.
#include "methods/neural/temporal/packed_nearest.glsl"
layout(binding = 0) uniform highp usampler2D u_packedLayers;  // fresh pass 3: the nearest two fragments, packed
#ifdef STARNT_PACKED_THREE_LAYERS
// And the third (an RGBA32UI target of its own, beside the reference depth: packed_nearest.h): what
// lies behind it weighed by depth. The real frames keep no correction then (u_useCorrection false;
// docs/DESIGN.md, "Corrected frames: three layers and no correction").
layout(binding = 1) uniform highp usampler2D u_thirdLayer;  // fresh pass 3: the third nearest fragment, packed
#endif
#elif defined(STARNT_PACKED_NEAREST)
#include "methods/neural/temporal/packed_nearest.glsl"
layout(binding = 0) uniform highp sampler2D u_packedNearest;  // fresh pass 3: the nearest fragment, packed
#else
layout(binding = 0) uniform highp sampler2D u_nearest;        // fresh pass 1: C1, a1
layout(binding = 1) uniform highp sampler2D u_depth;          // fresh pass-1 window depth
#endif
layout(binding = 2) uniform highp sampler2D u_sumAlphaColor;  // fresh pass 3: sum a C, sum a
layout(binding = 3) uniform highp sampler2D u_transmittance;  // fresh pass 3: prod (1 - a)
layout(binding = 4) uniform highp sampler2D u_correction;     // reprojection_behind.frag.glsl, STARNT_BEHIND_CORRECTION
#ifdef STARNT_ORDERED_BEHIND
// The tail-moment methods: what lies behind the nearest layer weighted by depth (ordered_behind.glsl).
#include "methods/neural/temporal/ordered_behind.glsl"
layout(binding = 5) uniform highp sampler2D u_behindMoment1;  // fresh pass 3: sum a C u, sum a u
layout(binding = 6) uniform highp sampler2D u_behindMoment2;  // fresh pass 3: sum a u^2, sum -ln(1 - a)
layout(binding = 7) uniform highp sampler2D u_reference;      // reference_depth.frag.glsl, one texel a tile
#endif
uniform ivec2 u_size;
uniform mat4 u_newToOld;        // oldViewProj * inverse(newViewProj)
uniform vec4 u_sourceScale;     // row 3 of inverse(oldViewProj)
#include "methods/common/background.glsl"
uniform bool u_halfOutput;
uniform bool u_useCorrection;  // false: the last real frame kept no correction (pass 3 ran reduced)
uniform bool u_filteredCorrection;  // u_correction filters linearly (not RGBA32F on ES without OES_texture_float_linear)

// True where texel t of the kept correction holds the same surface as the source point, whose
// inverse view depth is `reference` (d.a: the texel's, <= 0 where it kept none).
bool sameSurface(float keptInverseDepth, float reference) {
    return keptInverseDepth > 0.0 && abs(keptInverseDepth / reference - 1.0) <= float(STARNT_TEMPORAL_SAME_SURFACE);
}

#ifdef STARNT_CLEARS_TARGETS
// Three layers on a software rasteriser (NeuralPasses::compositeClearsTargets; docs/DESIGN.md,
// "Corrected frames: the composite clears pass 3's targets"): having read them at its own pixel,
// the composite writes back the values pass 3 clears them to, so the next pass 3 need not clear
// them. Each texel is read and written by this invocation alone (texelFetch at gl_FragCoord), the
// exception GL 4.5 makes for a texture read while it is a render target (section 9.3.1).
layout(location = 0) out vec4 o_color;
layout(location = 1) out highp uvec4 o_clearPackedLayers;
layout(location = 2) out highp uvec4 o_clearThirdLayer;
layout(location = 3) out vec4 o_clearSumAlphaColor;
layout(location = 4) out vec4 o_clearBehindMoment1;
layout(location = 5) out vec4 o_clearBehindMoment2;
#else
out vec4 o_color;
#endif

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
#if defined(STARNT_PACKED_TWO_LAYERS)
    uvec4 layers = texelFetch(u_packedLayers, p, 0);
    float depth, secondDepth;
    vec4 fresh = unpackLayer(layers.xy, depth);
    vec4 second = unpackLayer(layers.zw, secondDepth);
#ifdef STARNT_PACKED_THREE_LAYERS
    float thirdDepth;
    uvec4 thirdTexel = texelFetch(u_thirdLayer, p, 0);  // the third layer, and the reference depth beside it
    vec4 third = unpackLayer(thirdTexel.xy, thirdDepth);
#endif
#elif defined(STARNT_PACKED_NEAREST)
    float depth;
    vec4 fresh = unpackNearest(texelFetch(u_packedNearest, p, 0), depth);
#else
    vec4 fresh = texelFetch(u_nearest, p, 0);
    float depth = texelFetch(u_depth, p, 0).r;
#endif
    vec3 color = background();
    float transmittance = 1.0;
    if (fresh.a > 0.0) {
        float open = 1.0 - fresh.a;
#ifdef STARNT_ORDERED_BEHIND
        vec2 secondAndTransmittance = texelFetch(u_behindMoment2, p, 0).rg;
        transmittance = transmittanceOfOpticalDepth(secondAndTransmittance.y);
#else
        transmittance = texelFetch(u_transmittance, p, 0).r;
#endif
        vec3 behind = background();
        if (open > float(STARNT_TEMPORAL_MIN_TRANSMITTANCE)) {
#if defined(STARNT_PACKED_TWO_LAYERS)
#ifdef STARNT_PACKED_THREE_LAYERS
            behind = orderedClosedFormBehindThreeLayers(fresh, depth, second, secondDepth, third, thirdDepth, texelFetch(u_sumAlphaColor, p, 0),
                                                      transmittance, texelFetch(u_behindMoment1, p, 0), secondAndTransmittance.x,
                                                      uintBitsToFloat(thirdTexel.z), uintBitsToFloat(thirdTexel.w),
                                                      background());
#else
            behind = orderedClosedFormBehindTwoLayers(fresh, depth, second, secondDepth, texelFetch(u_sumAlphaColor, p, 0),
                                                      transmittance, texelFetch(u_behindMoment1, p, 0), secondAndTransmittance.x,
                                                      texelFetch(u_reference, p / STARNT_ORDERED_REFERENCE_TILE, 0).r, 0.0,
                                                      background());
#endif
#elif defined(STARNT_ORDERED_BEHIND)
            behind = orderedClosedFormBehind(fresh, depth, texelFetch(u_sumAlphaColor, p, 0), transmittance,
                                             texelFetch(u_behindMoment1, p, 0), secondAndTransmittance.x,
                                             texelFetch(u_reference, p / STARNT_ORDERED_REFERENCE_TILE, 0).r, 0.0, background());
#else
            behind = closedFormBehind(fresh, texelFetch(u_sumAlphaColor, p, 0), transmittance, background());
#endif
#ifndef STARNT_PACKED_THREE_LAYERS
            // (Three layers: the real frames keep no correction, u_useCorrection is false.)
            vec2 c = (vec2(p) + 0.5) / vec2(u_size) * 2.0 - 1.0;
            vec4 old = u_newToOld * vec4(c, depth * 2.0 - 1.0, 1.0);
            if (u_useCorrection && old.w > 0.0) {
                vec3 ndc = old.xyz / old.w;
                float reference = dot(u_sourceScale, vec4(ndc, 1.0));
                vec2 f = (ndc.xy * 0.5 + 0.5) * vec2(u_size) - 0.5;
                if (reference > 0.0 && f.x > -1.0 && f.y > -1.0 && f.x < float(u_size.x) && f.y < float(u_size.y)) {
                    ivec2 base = ivec2(floor(f));
                    vec2 w = f - vec2(base);
                    // Where all four taps lie inside and hold the source's surface (most pixels), the
                    // weights are plain bilinear: one gather of their depths and one filtered fetch
                    // instead of four fetches (docs/DESIGN.md, "Corrected frames"). The gather at
                    // the taps' shared corner returns (i0, j1), (i1, j1), (i1, j0), (i0, j0).
                    bool inside = base.x >= 0 && base.y >= 0 && base.x + 1 < u_size.x && base.y + 1 < u_size.y;
                    bool bilinear = false;
                    if (u_filteredCorrection && inside) {
                        vec4 kept = textureGather(u_correction, (vec2(base) + 1.0) / vec2(u_size), 3);
                        bilinear = sameSurface(kept.x, reference) && sameSurface(kept.y, reference) &&
                                   sameSurface(kept.z, reference) && sameSurface(kept.w, reference);
                    }
                    if (bilinear) {
                        behind += texture(u_correction, (f + 0.5) / vec2(u_size)).rgb;
                    } else {
                        vec3 sum = vec3(0.0);
                        float weight = 0.0;
                        for (int k = 0; k < 4; ++k) {
                            ivec2 t = base + ivec2(k & 1, k >> 1);
                            if (t.x < 0 || t.y < 0 || t.x >= u_size.x || t.y >= u_size.y) continue;
                            vec4 d = texelFetch(u_correction, t, 0);
                            if (!sameSurface(d.a, reference)) continue;
                            float wk = ((k & 1) != 0 ? w.x : 1.0 - w.x) * ((k >> 1) != 0 ? w.y : 1.0 - w.y);
                            sum += wk * d.rgb;
                            weight += wk;
                        }
                        if (weight > 0.0) behind += sum / weight;
                    }
                }
            }
#endif
        }
        color = fresh.a * fresh.rgb + open * max(behind, vec3(0.0));
    }
    o_color = outputValue(vec4(color, outputAlpha(transmittance)), u_halfOutput);
#ifdef STARNT_CLEARS_TARGETS
    const uvec4 emptyLayers = uvec4(STARNT_PACKED_LAYER_EMPTY, 0u, STARNT_PACKED_LAYER_EMPTY, 0u);
    o_clearPackedLayers = emptyLayers;
    // Beside the empty layer, the next frame's reference depth (made from this frame's layers).
    o_clearThirdLayer = uvec4(emptyLayers.xy, floatBitsToUint(texelFetch(u_reference, p / STARNT_ORDERED_REFERENCE_TILE, 0).r), 0u);
    o_clearSumAlphaColor = vec4(0.0);
    o_clearBehindMoment1 = vec4(0.0);
    o_clearBehindMoment2 = vec4(0.0);
#endif
}
