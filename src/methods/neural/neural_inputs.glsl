// Reads what passes 1-3 left for this pixel (the GPU side of nn::PixelSums), passes 2 and 3
// upsampled to full resolution when they ran at a reduced scale (CPU reference:
// upsamplePassSums in upsample_cpu.hpp), and computes the guarded quantities both networks use. STARNT_EPS_TRANSMITTANCE and STARNT_EPS_TAIL_ALPHA are
// defined from nn::kTransmittanceEpsilon / nn::kTailAlphaEpsilon when the program is built, so the
// CPU reference and the shader share one definition.
layout(binding = 0) uniform sampler2D u_nearest;        // C1, a1
layout(binding = 1) uniform sampler2D u_second;         // C2, a2
layout(binding = 2) uniform sampler2D u_alphaColor;     // sum a C, sum a
layout(binding = 3) uniform sampler2D u_colorCount;     // sum C, N
layout(binding = 4) uniform sampler2D u_transmittance;  // prod (1 - a)
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

#ifndef STARNT_INPUTS_FULL_RESOLUTION
struct TailSums {
    vec4 alphaColor;  // tail sum a C, tail sum a
    vec4 colorCount;  // tail sum C, tail count
    float transmittance;
};

// The tail at pass-3 texel t: its sums minus the nearest fragment at the same sample point (the
// full-resolution pass-1 pixel under the texel centre) and the second (the pass-2 texel there).
TailSums tailAt(ivec2 t) {
    vec2 centre = vec2(t) + 0.5;
    ivec2 full = clamp(ivec2(centre * vec2(u_fullSize) / vec2(u_pass3Size)), ivec2(0), u_fullSize - 1);
    ivec2 second = clamp(ivec2(centre * vec2(u_pass2Size) / vec2(u_pass3Size)), ivec2(0), u_pass2Size - 1);
    vec4 f1 = texelFetch(u_nearest, full, 0), f2 = texelFetch(u_second, second, 0);
    vec4 ac = texelFetch(u_alphaColor, t, 0), cn = texelFetch(u_colorCount, t, 0);
    float has1 = f1.a > 0.0 ? 1.0 : 0.0, has2 = f2.a > 0.0 ? 1.0 : 0.0;
    TailSums tail;
    tail.alphaColor = max(ac - vec4(f1.rgb * f1.a, f1.a) - vec4(f2.rgb * f2.a, f2.a), vec4(0.0));
    tail.colorCount = max(cn - vec4(f1.rgb, 1.0) * has1 - vec4(f2.rgb, 1.0) * has2, vec4(0.0));
    float t2 = (1.0 - f1.a) * (1.0 - f2.a);
    tail.transmittance = t2 > STARNT_EPS_TRANSMITTANCE ? clamp(texelFetch(u_transmittance, t, 0).r / t2, 0.0, 1.0) : 1.0;
    return tail;
}
#endif

PixelSums readPixelSums(ivec2 p) {
    PixelSums s;
    vec4 f1 = texelFetch(u_nearest, p, 0);
    if (f1.a == 0.0) {
        // Pass 1 runs at full resolution: no nearest fragment means no fragment at all. Without
        // this, reduced passes 2/3 would leak their neighbours' sums into background pixels
        // (halos at every silhouette).
        s.c1 = s.c2 = s.sumAlphaColor = s.sumColor = vec3(0.0);
        s.a1 = s.a2 = s.count = s.sumAlpha = 0.0;
        s.transmittance = 1.0;
        return s;
    }
    vec4 f2 = upsampleAlphaWeighted(u_second, p, u_pass2Size);
    s.c1 = f1.rgb;
    s.a1 = f1.a;
    s.c2 = f2.rgb;
    s.a2 = f2.a;
#ifndef STARNT_INPUTS_FULL_RESOLUTION
    // The tail is upsampled, not the sums: each pass-3 texel first loses the two layers seen at its
    // own sample point, and the pixel then adds its own. Subtracting this pixel's layers from its
    // neighbours' sums would remove fragments those neighbours never had (thin edges).
    BilinearTaps t = bilinearTaps(p, u_pass3Size);
    TailSums t00 = tailAt(t.p0), t10 = tailAt(ivec2(t.p1.x, t.p0.y));
    TailSums t01 = tailAt(ivec2(t.p0.x, t.p1.y)), t11 = tailAt(t.p1);
    vec4 tailAc = mix(mix(t00.alphaColor, t10.alphaColor, t.f.x), mix(t01.alphaColor, t11.alphaColor, t.f.x), t.f.y);
    vec4 tailCn = mix(mix(t00.colorCount, t10.colorCount, t.f.x), mix(t01.colorCount, t11.colorCount, t.f.x), t.f.y);
    float tailT = mix(mix(t00.transmittance, t10.transmittance, t.f.x), mix(t01.transmittance, t11.transmittance, t.f.x), t.f.y);
    float has1 = s.a1 > 0.0 ? 1.0 : 0.0, has2 = s.a2 > 0.0 ? 1.0 : 0.0;
    s.sumAlphaColor = tailAc.rgb + s.a1 * s.c1 + s.a2 * s.c2;
    s.sumAlpha = tailAc.a + s.a1 + s.a2;
    s.sumColor = tailCn.rgb + has1 * s.c1 + has2 * s.c2;
    s.count = tailCn.a + has1 + has2;
    s.transmittance = tailT * (1.0 - s.a1) * (1.0 - s.a2);
#else
    vec4 ac = upsampleLinear(u_alphaColor, p, u_pass3Size);
    vec4 cn = upsampleLinear(u_colorCount, p, u_pass3Size);
    s.sumAlphaColor = ac.rgb;
    s.sumAlpha = ac.a;
    s.sumColor = cn.rgb;
    s.count = cn.a;
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
