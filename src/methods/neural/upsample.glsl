// Stage "upsample" (docs/DESIGN.md, "Pipeline and formats", step 4): passes 2 and 3 may render at a reduced size into the
// lower-left corner of their full-size targets; the inference passes read them back at full
// resolution through these bilinear lookups. Fusing the upsample into the reads saves writing and
// re-reading four full-resolution float targets; upsample_cpu.hpp is the CPU reference.
//
// The reduced passes sample the full window at i * fullSize / size + 0.5 (neural_passes.cpp moves
// their viewport; upsample_cpu.hpp says why), so full pixel p maps to the continuous texel position
// u = p * size / fullSize, texel i's sample being at u = i. The two texels around u per axis are
// clamped to the reduced rectangle (edge texels extend outwards).
uniform ivec2 u_fullSize;
uniform ivec2 u_pass2Size;
uniform ivec2 u_pass3Size;

#ifdef STARNT_INPUTS_FULL_RESOLUTION
// Passes 2 and 3 ran at full resolution: plain reads. A separate program variant, because a
// per-pixel size test measurably slowed the inference pass on llvmpipe.
vec4 upsampleLinear(sampler2D source, ivec2 p, ivec2 size) { return texelFetch(source, p, 0); }
vec4 upsampleAlphaWeighted(sampler2D source, ivec2 p, ivec2 size) { return texelFetch(source, p, 0); }
#else
struct BilinearTaps {
    ivec2 p0;  // lower-left texel
    ivec2 p1;  // upper-right texel
    vec2 f;    // weights of p1 along x and y
};

BilinearTaps bilinearTaps(ivec2 p, ivec2 size) {
    vec2 u = vec2(p) * vec2(size) / vec2(u_fullSize);
    vec2 base = floor(u);
    BilinearTaps t;
    t.f = u - base;
    t.p0 = clamp(ivec2(base), ivec2(0), size - 1);
    t.p1 = clamp(ivec2(base) + 1, ivec2(0), size - 1);
    return t;
}

// Plain bilinear (sums, counts, transmittance).
vec4 upsampleLinear(sampler2D source, ivec2 p, ivec2 size) {
    BilinearTaps t = bilinearTaps(p, size);
    vec4 bottom = mix(texelFetch(source, t.p0, 0), texelFetch(source, ivec2(t.p1.x, t.p0.y), 0), t.f.x);
    vec4 top = mix(texelFetch(source, ivec2(t.p0.x, t.p1.y), 0), texelFetch(source, t.p1, 0), t.f.x);
    return mix(bottom, top, t.f.y);
}

// The same as upsampleLinear through the texture unit's bilinear filter: one filtered fetch instead
// of four. The source must use GL_LINEAR filtering; the position is clamped so that the filter never
// reaches outside the reduced rectangle (edge texels extend outwards, as with the clamped taps).
vec4 upsampleFiltered(sampler2D source, ivec2 p, ivec2 size) {
    vec2 u = clamp(vec2(p) * vec2(size) / vec2(u_fullSize), vec2(0.0), vec2(size - 1));
    return textureLod(source, (u + 0.5) / vec2(textureSize(source, 0)), 0.0);
}

#ifdef STARNT_UPSAMPLE_JOINT
#include "methods/neural/upsample_constants.h"
// Joint bilateral upsampling guided by the full-resolution pass-1 depth (upsample_cpu.hpp,
// jointTapWeights): each of the four bilinear taps is weighted down by how far the nearest surface
// at its sample (full pixel nearestSampleTexel(tap)) lies from the nearest surface at this pixel,
// in view distance relative to this pixel's. A tap on another surface (a silhouette, a piece in
// front of the board) carries another surface's layers behind it. All four rejected: plain bilinear.
#include "starnt/bindings.h"
layout(binding = STARNT_UNIT_NEAREST_DEPTH) uniform sampler2D u_nearestDepth;  // window depth, 1 where no fragment
uniform vec4 u_depthUnproject;  // inverse projection (m22, m32, m23, m33): view z = (a n + b) / (c n + d)

float viewDistance(float windowDepth) {
    float ndc = 2.0 * windowDepth - 1.0;
    return -(u_depthUnproject.x * ndc + u_depthUnproject.y) / (u_depthUnproject.z * ndc + u_depthUnproject.w);
}

ivec2 sampleOfTexel(ivec2 t, ivec2 size) { return clamp((2 * t * u_fullSize + size) / (2 * size), ivec2(0), u_fullSize - 1); }

float depthAgreement(ivec2 tap, ivec2 size, float distance) {
    float z = texelFetch(u_nearestDepth, sampleOfTexel(tap, size), 0).r;
    if (z >= 1.0) return 0.0;  // no surface there: nothing behind it either
    float r = (viewDistance(z) - distance) / (STARNT_UPSAMPLE_SIGMA * distance);
    return exp(-r * r);
}

// The four taps of pixel p in a reduced image and their weights (p0, (p1.x, p0.y), (p0.x, p1.y),
// p1), normalised. `plain`: every tap agrees (the weights are the bilinear ones), so one filtered
// fetch serves; most pixels, and it keeps the joint upsample nearly as cheap as the bilinear one.
struct JointTaps {
    BilinearTaps t;
    vec4 w;
    bool plain;
};

JointTaps jointTaps(ivec2 p, ivec2 size) {
    JointTaps j;
    j.t = bilinearTaps(p, size);
    BilinearTaps t = j.t;
    vec4 bilinear = vec4((1.0 - t.f.x) * (1.0 - t.f.y), t.f.x * (1.0 - t.f.y), (1.0 - t.f.x) * t.f.y, t.f.x * t.f.y);
    float distance = viewDistance(texelFetch(u_nearestDepth, p, 0).r);
    vec4 agree = vec4(depthAgreement(t.p0, size, distance), depthAgreement(ivec2(t.p1.x, t.p0.y), size, distance),
                      depthAgreement(ivec2(t.p0.x, t.p1.y), size, distance), depthAgreement(t.p1, size, distance));
    j.plain = all(greaterThanEqual(agree, vec4(STARNT_UPSAMPLE_PLAIN_AGREEMENT)));
    vec4 w = bilinear * agree;
    float total = dot(w, vec4(1.0));
    j.w = !j.plain && total > STARNT_UPSAMPLE_MIN_WEIGHT ? w / total : bilinear;
    return j;
}

vec4 upsampleJoint(sampler2D source, ivec2 p, ivec2 size, JointTaps j) {
    if (j.plain) return upsampleFiltered(source, p, size);
    BilinearTaps t = j.t;
    return j.w.x * texelFetch(source, t.p0, 0) + j.w.y * texelFetch(source, ivec2(t.p1.x, t.p0.y), 0) +
           j.w.z * texelFetch(source, ivec2(t.p0.x, t.p1.y), 0) + j.w.w * texelFetch(source, t.p1, 0);
}

vec4 upsampleJointAlphaWeighted(sampler2D source, JointTaps j) {
    BilinearTaps t = j.t;
    vec4 s00 = texelFetch(source, t.p0, 0), s10 = texelFetch(source, ivec2(t.p1.x, t.p0.y), 0);
    vec4 s01 = texelFetch(source, ivec2(t.p0.x, t.p1.y), 0), s11 = texelFetch(source, t.p1, 0);
    vec4 premultiplied = j.w.x * vec4(s00.rgb * s00.a, s00.a) + j.w.y * vec4(s10.rgb * s10.a, s10.a) +
                         j.w.z * vec4(s01.rgb * s01.a, s01.a) + j.w.w * vec4(s11.rgb * s11.a, s11.a);
    return premultiplied.a > 0.0 ? vec4(premultiplied.rgb / premultiplied.a, premultiplied.a) : vec4(0.0);
}
#endif

// Bilinear of a straight (colour, alpha) fragment, alpha-weighted: alpha is interpolated, the
// colour as alpha * colour and divided back, so pixels without a fragment (alpha 0) do not darken
// their neighbours' colour.
vec4 upsampleAlphaWeighted(sampler2D source, ivec2 p, ivec2 size) {
    BilinearTaps t = bilinearTaps(p, size);
    vec4 s00 = texelFetch(source, t.p0, 0), s10 = texelFetch(source, ivec2(t.p1.x, t.p0.y), 0);
    vec4 s01 = texelFetch(source, ivec2(t.p0.x, t.p1.y), 0), s11 = texelFetch(source, t.p1, 0);
    vec4 p00 = vec4(s00.rgb * s00.a, s00.a), p10 = vec4(s10.rgb * s10.a, s10.a);
    vec4 p01 = vec4(s01.rgb * s01.a, s01.a), p11 = vec4(s11.rgb * s11.a, s11.a);
    vec4 premultiplied = mix(mix(p00, p10, t.f.x), mix(p01, p11, t.f.x), t.f.y);
    return premultiplied.a > 0.0 ? vec4(premultiplied.rgb / premultiplied.a, premultiplied.a) : vec4(0.0);
}
#endif
