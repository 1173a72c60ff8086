// Corrected frames of the tail-moment methods (hybrid-moments, starnt-d; docs/DESIGN.md, "Corrected
// frames: depth order behind the nearest layer"; CPU reference temporal::orderedClosedFormBehind,
// the same float operations): what lies behind the nearest layer weighted by where its opacity lies
// in depth, as hybrid-moments weighs its tail, instead of the order-free mean of closed_form_behind.glsl.
// Pass 3 sums, over every fragment, depth moments in u = ln(1 + max(z - r, 0) / (s (1 - r))) (sum a C u,
// sum a u and sum a u^2: the weight is at most linear here, which reads no sum a C u^2), the
// tail moments' logarithmic depth (tail_moments_constants.h) taken behind a reference depth r that
// the last real frame gives (CorrectedFrames: the nearest depth over the pixels around, so at or
// before the fresh nearest layer where the view moved less than that neighbourhood); the composite
// recentres them at the nearest fragment's u1. z is the middle of its packed key's interval
// (packed_nearest.glsl: keyedDepth) in both, so that the nearest fragment's terms vanish exactly
// whether it comes from the packed layer or from pass 1.
#ifndef STARNT_ORDERED_BEHIND_GLSL
#define STARNT_ORDERED_BEHIND_GLSL
#include "methods/neural/temporal/reprojection_constants.h"
#include "methods/neural/temporal/packed_nearest.glsl"
#include "methods/hybrid_moments/moment_weighted_color.glsl"

// An interpolated frame sums the transmittance as an optical depth, so that it shares one additive
// two-channel target with sum a u^2 (pass3_accumulate.frag.glsl): a target fewer than a product
// beside it needs, 0.4-0.8 ms less an interpolated frame at 720p on llvmpipe (docs/DESIGN.md,
// "Corrected frames: depth order behind the nearest layer").
float opticalDepthOf(float alpha) { return -log(max(1.0 - alpha, float(STARNT_ORDERED_MIN_OPENNESS))); }
float transmittanceOfOpticalDepth(float depth) { return exp(-depth); }

// u of a fragment at window depth z behind the reference r, and mirrored (negative) in front of it:
// a reference the view has moved past (new surfaces in front of it, or r = 1 where the frame it
// came from had nothing) still orders every fragment, where u = 0 in front of it collapsed them
// onto one depth (docs/DESIGN.md, "Corrected frames: the reference depth follows the interpolated
// frames").
float depthBehindReference(float z, float reference) {
    float scale = float(STARNT_TAIL_MOMENT_DEPTH_SCALE) * max(1.0 - reference, float(STARNT_ORDERED_MIN_REFERENCE_GAP));
    float d = keyedDepth(z) - reference;
    return d >= 0.0 ? log(1.0 + d / scale) : -log(1.0 - d / scale);
}

// `nearest` = C1, a1 (a1 < 1 - STARNT_TEMPORAL_MIN_TRANSMITTANCE), `sums` = (sum a C, sum a), `t` =
// prod (1 - a), all over every fragment; `m1`, `m2` = (sum a C v, sum a v), sum a v^2 with v = u - u1
// the depth behind the nearest fragment's (whose own terms are then 0), as orderedClosedFormBehind
// recentres the sums over every fragment (both kinds of frame sum those, the same float operations
// per fragment, so a still camera gives the same closed form). Centred so, a rounding of a1 in sum a - a1 moves
// the spread by the mean's distance behind the nearest fragment, not by the reference's.
vec3 orderedClosedFormBehindFromMoments(vec4 nearest, vec4 sums, float t, vec4 m1, float m2, vec3 background) {
    float behindT = clamp(t / (1.0 - nearest.a), 0.0, 1.0);
    float behindAlpha = sums.a - nearest.a;
    if (!(behindAlpha > float(STARNT_TEMPORAL_MIN_BEHIND_ALPHA))) return background;
    vec3 alphaColor = sums.rgb - nearest.rgb * nearest.a;
    // sum a - a1 carries a1's rounding (the layer's 16-bit or 11-bit alpha), which alone makes one
    // fragment behind look spread over |mean| sqrt(error / (sum a - a1)): below that, the plain mean.
    float mean = m1.a / behindAlpha;
    bool spread = m2 / behindAlpha - mean * mean > float(STARNT_ORDERED_ALPHA_ROUNDING) / behindAlpha * mean * mean;
    vec3 color = spread ? momentWeightedColor(alphaColor, behindAlpha, m1, vec4(0.0, 0.0, 0.0, m2), behindT, false)
                        : max(alphaColor / behindAlpha, vec3(0.0));
    return (1.0 - behindT) * color + behindT * background;
}

// Zeroes moments recentred at u_c (`m2Recentred`: the tail's sum a (u - u_c)^2) that no longer hold
// the tail's spread. Each recentring subtracts terms as large as `m2` (sum a u^2 about the reference, over every
// fragment), whose float32 sums carry about N 6e-8 of m2 in rounding (N fragments); where the view
// has moved far from the reference (a cut) the difference was mostly rounding, and the weighted
// colour came out wrong in isolated pixels. Below the bound the plain mean is taken, as
// momentWeightedColor does where its own sums cannot centre (docs/DESIGN.md, "Corrected frames:
// the reference depth follows the interpolated frames").
void dropRoundedMoments(inout vec4 m1Recentred, inout float m2Recentred, float m2) {
    if (!(m2Recentred > float(STARNT_ORDERED_RECENTRED_PRECISION) * m2)) {
        m1Recentred = vec4(0.0);
        m2Recentred = 0.0;
    }
}

// The same from an interpolated frame's pass 3: `m1`, `m2` in u - `pivot` over every fragment (pivot: the
// u pass 3 took its sums about, 0 or the first fragment's: STARNT_PACKED_THREE_LAYERS), recentred at
// u1, the nearest fragment's (at window depth `depth`), with the sums over every fragment.
vec3 orderedClosedFormBehind(vec4 nearest, float depth, vec4 sums, float t, vec4 m1, float m2, float reference,
                             float pivot, vec3 background) {
    float u = depthBehindReference(depth, reference) - pivot;
    vec4 first = m1 - u * sums;
    float second2 = m2 - u * (m1.a + first.a);
    dropRoundedMoments(first, second2, m2);
    return orderedClosedFormBehindFromMoments(nearest, sums, t, first, second2, background);
}

// What lies behind the nearest layer when the second is known exactly too (C2, a2, behind the
// nearest): the second layer over the ordered closed form of what lies behind it; without a second
// layer (a2 = 0, the moments then 0 or those of fragments at the nearest's depth), the ordered
// closed form behind the nearest. `m1`, `m2` =
// (sum a C v, sum a v), sum a v^2 over the fragments behind the second layer, v = u - u2 the
// depth behind it (a real frame's pass 3 sums them so: STARNT_BEHIND_SECOND); `sums`, `t` over
// every fragment.
vec3 orderedClosedFormBehindSecondFromMoments(vec4 nearest, vec4 second, vec4 sums, float t, vec4 m1, float m2,
                                              vec3 background) {
    if (!(second.a > 0.0)) return orderedClosedFormBehindFromMoments(nearest, sums, t, m1, m2, background);
    float open2 = 1.0 - second.a;
    if (!(open2 > float(STARNT_TEMPORAL_MIN_TRANSMITTANCE))) return second.rgb;
    vec4 nearestTerms = vec4(nearest.rgb * nearest.a, nearest.a);
    vec3 behind = orderedClosedFormBehindFromMoments(second, sums - nearestTerms, t / (1.0 - nearest.a), m1, m2, background);
    return second.a * second.rgb + open2 * behind;
}

// The same from an interpolated frame's pass 3 (the nearest two layers packed, the moments in u
// over every fragment): the moments recentred at u2, the second layer's (its own terms then
// vanish), less the nearest layer's, a1 (C1, 1) (u1 - u2) and a1 (u1 - u2)^2. They differ from
// what a real frame sums behind the second layer only by fragments at the nearest layer's key
// other than it (coplanar duplicates).
vec3 orderedClosedFormBehindTwoLayers(vec4 nearest, float depth, vec4 second, float secondDepth, vec4 sums, float t, vec4 m1,
                                      float m2, float reference, float pivot, vec3 background) {
    if (!(second.a > 0.0)) return orderedClosedFormBehind(nearest, depth, sums, t, m1, m2, reference, pivot, background);
    float u2 = depthBehindReference(secondDepth, reference) - pivot;
    float d = depthBehindReference(depth, reference) - pivot - u2;
    vec4 nearestTerms = vec4(nearest.rgb * nearest.a, nearest.a);
    vec4 first = m1 - u2 * sums;
    float second2 = m2 - u2 * (m1.a + first.a) - nearestTerms.a * d * d;
    vec4 behindM1 = first - nearestTerms * d;
    dropRoundedMoments(behindM1, second2, m2);
    return orderedClosedFormBehindSecondFromMoments(nearest, second, sums, t, behindM1, second2, background);
}

// The same with the nearest three layers packed (docs/DESIGN.md, "Corrected frames: three layers and
// no correction"): the second layer over the third over the ordered closed form of what lies behind
// it, the moments recentred at u3 less the nearest two layers' terms; where fewer layers were found,
// the two-layer form (recentred at u2) or the one-layer form (at u1), as
// orderedClosedFormBehindTwoLayers and orderedClosedFormBehind make them. Written as one evaluation
// chosen by selects, not as calls of those forms: llvmpipe runs every branch for every pixel, and
// the nested forms evaluated the closed form five times where one is used (docs/DESIGN.md,
// "Findings on Mesa llvmpipe"). The CPU reference keeps the nested forms (correction_cpu.cpp).
vec3 orderedClosedFormBehindThreeLayers(vec4 nearest, float depth, vec4 second, float secondDepth, vec4 third,
                                        float thirdDepth, vec4 sums, float t, vec4 m1, float m2, float reference,
                                        float pivot, vec3 background) {
    bool hasThird = third.a > 0.0, hasSecond = hasThird || second.a > 0.0;
    // The deepest layer found, whose closed form behind it is composited under the others.
    vec4 deepest = hasThird ? third : (hasSecond ? second : nearest);
    float uc = depthBehindReference(hasThird ? thirdDepth : (hasSecond ? secondDepth : depth), reference) - pivot;
    float d1 = depthBehindReference(depth, reference) - pivot - uc;
    float d2 = depthBehindReference(secondDepth, reference) - pivot - uc;
    // The layers in front of the deepest one (the deepest's own terms vanish at uc).
    vec4 nearestTerms = hasSecond ? vec4(nearest.rgb * nearest.a, nearest.a) : vec4(0.0);
    vec4 secondTerms = hasThird ? vec4(second.rgb * second.a, second.a) : vec4(0.0);
    vec4 first = m1 - uc * sums;
    float second2 = m2 - uc * (m1.a + first.a) - nearestTerms.a * d1 * d1 - secondTerms.a * d2 * d2;
    vec4 behindM1 = first - nearestTerms * d1 - secondTerms * d2;
    dropRoundedMoments(behindM1, second2, m2);
    float behindT = hasSecond ? t / (1.0 - nearest.a) : t;
    behindT = hasThird ? behindT / (1.0 - second.a) : behindT;
    vec3 behind = orderedClosedFormBehindFromMoments(deepest, (sums - nearestTerms) - secondTerms, behindT, behindM1, second2,
                                                     background);
    float open3 = 1.0 - third.a, open2 = 1.0 - second.a;
    vec3 behindSecond = !hasThird ? behind
                                  : (open3 > float(STARNT_TEMPORAL_MIN_TRANSMITTANCE) ? third.a * third.rgb + open3 * behind : third.rgb);
    return !hasSecond ? behindSecond
                      : (open2 > float(STARNT_TEMPORAL_MIN_TRANSMITTANCE) ? second.a * second.rgb + open2 * behindSecond : second.rgb);
}
#endif
