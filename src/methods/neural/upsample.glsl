// Stage "upsample" (SPEC 2, step 4): passes 2 and 3 may render at a reduced size into the
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
