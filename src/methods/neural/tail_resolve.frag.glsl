// Stage "upsample", first half: when pass 2 or 3 ran at a reduced size, every pass-3 texel's sums
// become its TAIL in place: minus the nearest fragment seen at the texel's own sample point (the
// full-resolution pass-1 pixel nearest to that sample, which IS its sample when the full size is a
// multiple of the reduced one) and the second (the pass-2 texel whose sample is nearest), its
// transmittance divided by theirs. The inference then interpolates tails and adds
// each pixel's own two layers (neural_inputs.glsl). Interpolating the sums and subtracting the
// pixel's own layers instead would remove fragments its neighbours never had, at every thin edge.
// CPU reference: upsamplePassSums in upsample_cpu.hpp.
//
// Drawn over the pass-3 rectangle into pass 3's own targets: each fragment reads only the texel it
// writes, once, after a glTextureBarrier (GL 4.5), which makes this feedback loop defined. (A
// compute pass with image load/store took 8.4-10.6 ms against 6.1-6.6 ms for this on llvmpipe,
// chess 1280x720 at scales 50/50.)
#include "starnt/bindings.h"
#include "methods/neural/half_targets.glsl"
layout(binding = STARNT_UNIT_NEAREST) uniform sampler2D u_nearest;        // C1, a1 (full resolution)
layout(binding = STARNT_UNIT_SECOND) uniform sampler2D u_second;         // C2, a2 (u_pass2Size)
layout(binding = STARNT_UNIT_ALPHA_COLOR) uniform sampler2D u_alphaColor;     // sum a C, sum a
layout(binding = STARNT_UNIT_COLOR_COUNT) uniform sampler2D u_colorCount;     // sum C, N
layout(binding = STARNT_UNIT_TRANSMITTANCE) uniform sampler2D u_transmittance;  // prod (1 - a)
uniform ivec2 u_fullSize;
uniform ivec2 u_pass2Size;
uniform ivec2 u_pass3Size;

layout(location = 0) out vec4 o_alphaColor;     // tail sum a C, tail sum a
layout(location = 1) out vec4 o_colorCount;     // tail sum C, tail count
layout(location = 2) out vec4 o_transmittance;  // tail transmittance

// round(t * to / from) in integers, clamped: nearestSampleTexel in upsample_cpu.cpp.
ivec2 nearestSampleTexel(ivec2 t, ivec2 from, ivec2 to) {
    return clamp((2 * t * to + from) / (2 * from), ivec2(0), to - 1);
}

void main() {
    ivec2 t = ivec2(gl_FragCoord.xy);
    ivec2 full = nearestSampleTexel(t, u_pass3Size, u_fullSize);
    ivec2 second = nearestSampleTexel(t, u_pass3Size, u_pass2Size);
    vec4 f1 = texelFetch(u_nearest, full, 0), f2 = texelFetch(u_second, second, 0);
    float has1 = f1.a > 0.0 ? 1.0 : 0.0, has2 = f2.a > 0.0 ? 1.0 : 0.0;
    vec4 ac = texelFetch(u_alphaColor, t, 0), cn = texelFetch(u_colorCount, t, 0);
    float transmittance = texelFetch(u_transmittance, t, 0).r;
    o_alphaColor = targetValue(max(ac - vec4(f1.rgb * f1.a, f1.a) - vec4(f2.rgb * f2.a, f2.a), vec4(0.0)));
#ifdef STARNT_COUNT_ONLY
    o_colorCount = targetValue(vec4(max(cn.r - has1 - has2, 0.0)));  // the count alone, in .r (pass3_accumulate)
#else
    o_colorCount = targetValue(max(cn - vec4(f1.rgb, 1.0) * has1 - vec4(f2.rgb, 1.0) * has2, vec4(0.0)));
#endif
    float t2 = (1.0 - f1.a) * (1.0 - f2.a);
    o_transmittance = targetValue(vec4(t2 > STARNT_EPS_TRANSMITTANCE ? clamp(transmittance / t2, 0.0, 1.0) : 1.0));
}
