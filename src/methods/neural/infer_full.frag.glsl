// Stage "infer" (docs/DESIGN.md, "Pipeline and formats", step 5), full: the network at every pixel where the method uses it, then
// the method's composite. The method's features and composite (networkApplies, networkInputs,
// compositePixel) are included before this file.
#include "methods/neural/half_targets.glsl"
#include "methods/neural/network_hdr.glsl"
layout(location = 0) out vec4 outColor;
#ifdef STARNT_CAPTURE_CORRECTION
// The fused capture of corrected frames (CorrectedFrames::beginFusedCapture): what the capture
// pass would keep, written beside the output. The early empty-pixel test runs against a copy of
// pass 1's depth, so sampling the original here is no feedback loop.
#include "methods/neural/temporal/correction_capture.glsl"
layout(location = 1) out vec4 outCorrection;
layout(binding = STARNT_UNIT_NEAREST_DEPTH) uniform highp sampler2D u_captureDepth;
uniform vec4 u_sourceScale;
#ifdef STARNT_CAPTURE_ORDERED
// The tail-moment methods: pass 3 summed the moments behind the reference depth that the
// interpolated frames will use, as theirs does, so the correction is taken against the ordered
// closed form they compute, recentred at pass 1's fragment as they recentre (ordered_behind.glsl),
// and a still camera gives the real frame back: sum a u^2 beside the count, (sum a C u, sum a u)
// and the reference through image units 0 and 1, as every texture unit below the engine's is taken
// (image units: only the tiles and the A-buffer use them, neither in these methods).
#include "methods/neural/temporal/ordered_behind.glsl"
layout(binding = 0, rgba32f) uniform readonly highp image2D u_behindMoment1;
layout(binding = 1, r32f) uniform readonly highp image2D u_captureReference;  // one texel a tile
#endif
#endif

#ifdef STARNT_CLEARS_SHARED_SUMS
// Corrected frames with three layers (NeuralPasses::sharedSumTargets): 0 written back into the
// three pass-3 targets that the interpolated frames' pass 3 sums into as well, at the pixel this
// invocation read them (full-resolution inputs: its own texel, the one read-and-write GL 4.5
// allows), so that pass skips their clears.
#if defined(STARNT_CAPTURE_CORRECTION) || !defined(STARNT_INPUTS_FULL_RESOLUTION)
#error "the shared sums are written back by a composite without the fused capture, at full resolution"
#endif
layout(location = 1) out vec4 outClearedSums;
layout(location = 2) out vec4 outClearedCount;
layout(location = 3) out vec4 outClearedMoment;
#endif

void main() {
#ifdef STARNT_CLEARS_SHARED_SUMS
    outClearedSums = outClearedCount = outClearedMoment = vec4(0.0);
#endif
    PixelSums s = readPixelSums(ivec2(gl_FragCoord.xy));
    vec3 network = vec3(0.0);
    if (networkApplies(s)) network = evaluateNetwork(s);
    vec4 color = targetValue(vec4(compositePixel(s, network), outputAlpha(s.transmittance)));
    outColor = color;
#ifdef STARNT_CAPTURE_CORRECTION
    ivec2 t = ivec2(gl_FragCoord.xy);
    // The layer and sums this pixel read already (full-resolution inputs: the texels themselves).
#if defined(STARNT_CAPTURE_ORDERED) && defined(STARNT_CAPTURE_TWO_LAYERS)
    // The interpolated frames know the second layer too: pass 3 summed the moments behind it.
    vec4 captureSums = vec4(s.sumAlphaColor, s.sumAlpha);
    vec4 behindMoment1 = imageLoad(u_behindMoment1, t);
    float behindMoment2 = texelFetch(u_colorCount, t, 0).g;
    vec3 closedForm = orderedClosedFormBehindSecondFromMoments(vec4(s.c1, s.a1), vec4(s.c2, s.a2), captureSums, s.transmittance,
                                                               behindMoment1, behindMoment2, background());
#elif defined(STARNT_CAPTURE_ORDERED)
    vec3 closedForm = orderedClosedFormBehind(vec4(s.c1, s.a1), texelFetch(u_captureDepth, t, 0).r,
                                              vec4(s.sumAlphaColor, s.sumAlpha), s.transmittance, imageLoad(u_behindMoment1, t),
                                              texelFetch(u_colorCount, t, 0).g,
                                              imageLoad(u_captureReference, t / STARNT_ORDERED_REFERENCE_TILE).r, 0.0, background());
#elif defined(STARNT_ORDERED_CLOSED_FORM)
    // The tail-moment methods where pass 3 could not sum those moments (fewer than 6 draw buffers):
    // against hybrid-moments' composite, the nearest to the ordered closed form they have.
    vec3 closedForm = orderedClosedFormBehindNearest(s, background());
#else
    vec3 closedForm = closedFormBehind(vec4(s.c1, s.a1), vec4(s.sumAlphaColor, s.sumAlpha), s.transmittance, background());
#endif
    outCorrection = keptCorrection(t, u_fullSize, u_sourceScale, color.rgb, vec4(s.c1, s.a1), closedForm,
                                   texelFetch(u_captureDepth, t, 0).r);
#endif
}
