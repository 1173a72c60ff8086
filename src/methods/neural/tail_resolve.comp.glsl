// Stage "upsample", first half: when pass 2 or 3 ran at a reduced size, every pass-3 texel's sums
// become its TAIL in place: minus the nearest fragment seen at the texel's own sample point (the
// full-resolution pass-1 pixel under its centre) and the second (the pass-2 texel under its
// centre), its transmittance divided by theirs. The inference then interpolates tails and adds
// each pixel's own two layers (neural_inputs.glsl). Interpolating the sums and subtracting the
// pixel's own layers instead would remove fragments its neighbours never had, at every thin edge.
// CPU reference: upsamplePassSums in upsample_cpu.hpp.
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D u_nearest;  // C1, a1 (full resolution)
layout(binding = 1) uniform sampler2D u_second;   // C2, a2 (u_pass2Size)
layout(binding = 0, rgba32f) uniform highp image2D u_alphaColor;     // sum a C, sum a -> tail
layout(binding = 1, rgba32f) uniform highp image2D u_colorCount;     // sum C, N -> tail
layout(binding = 2, r32f) uniform highp image2D u_transmittance;     // prod (1 - a) -> tail
uniform ivec2 u_fullSize;
uniform ivec2 u_pass2Size;
uniform ivec2 u_pass3Size;

void main() {
    ivec2 t = ivec2(gl_GlobalInvocationID.xy);
    if (t.x >= u_pass3Size.x || t.y >= u_pass3Size.y) return;
    vec2 centre = vec2(t) + 0.5;
    ivec2 full = clamp(ivec2(centre * vec2(u_fullSize) / vec2(u_pass3Size)), ivec2(0), u_fullSize - 1);
    ivec2 second = clamp(ivec2(centre * vec2(u_pass2Size) / vec2(u_pass3Size)), ivec2(0), u_pass2Size - 1);
    vec4 f1 = texelFetch(u_nearest, full, 0), f2 = texelFetch(u_second, second, 0);
    float has1 = f1.a > 0.0 ? 1.0 : 0.0, has2 = f2.a > 0.0 ? 1.0 : 0.0;
    vec4 ac = imageLoad(u_alphaColor, t), cn = imageLoad(u_colorCount, t);
    float transmittance = imageLoad(u_transmittance, t).r;
    imageStore(u_alphaColor, t, max(ac - vec4(f1.rgb * f1.a, f1.a) - vec4(f2.rgb * f2.a, f2.a), vec4(0.0)));
    imageStore(u_colorCount, t, max(cn - vec4(f1.rgb, 1.0) * has1 - vec4(f2.rgb, 1.0) * has2, vec4(0.0)));
    float t2 = (1.0 - f1.a) * (1.0 - f2.a);
    float tail = t2 > STARNT_EPS_TRANSMITTANCE ? clamp(transmittance / t2, 0.0, 1.0) : 1.0;
    imageStore(u_transmittance, t, vec4(tail, 0.0, 0.0, 0.0));
}
