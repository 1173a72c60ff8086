// Scale guard, per tile (tile_constants.h says what it predicts; CPU reference: scaleGuardSums in
// tiles_cpu.hpp, which follows these steps in the same order). One workgroup per 16x16 tile, one
// invocation per pixel; run on frames whose passes 2 and 3 ran at full resolution.
#include "starnt/bindings.h"
#include "methods/neural/tiles/tile_constants.h"

layout(local_size_x = 8, local_size_y = 8) in;  // one invocation per 2x2 block of the 16x16 tile
layout(binding = 0) uniform highp sampler2D u_composite;  // linear RGB, full resolution
layout(binding = 1) uniform highp sampler2D u_nearest;    // pass 1: C1, a1
layout(binding = 2) uniform highp sampler2D u_second;     // pass 2 (full resolution): C2, a2
layout(std430, binding = STARNT_SSBO_TILE_GUARD) writeonly buffer TileSums { float tileSums[]; };
uniform ivec2 u_size;
uniform ivec2 u_tiles;

shared float s_values[STARNT_GUARD_VALUES][64];

float srgbEncode(float linear) {
    float c = clamp(linear, 0.0, 1.0);
    return c <= 0.0031308 ? 12.92 * c : 1.055 * pow(c, 1.0 / 2.4) - 0.055;
}

float srgbSquaredError(vec3 a, vec3 b) {
    vec3 d = vec3(srgbEncode(a.r), srgbEncode(a.g), srgbEncode(a.b)) - vec3(srgbEncode(b.r), srgbEncode(b.g), srgbEncode(b.b));
    return (d.r * d.r + d.g * d.g + d.b * d.b) / 3.0;
}

// What passes 2 and 3 add at a pixel, divided by the transmittance in front of them.
struct Shares {
    vec3 behind1, behind2;
    bool valid1, valid2;
};

Shares sharesAt(ivec2 p) {
    vec3 c = texelFetch(u_composite, p, 0).rgb;
    vec4 n = texelFetch(u_nearest, p, 0), sec = texelFetch(u_second, p, 0);
    vec3 s2 = c - n.a * n.rgb;
    vec3 s3 = s2 - (1.0 - n.a) * sec.a * sec.rgb;
    float t1 = 1.0 - n.a, t2 = t1 * (1.0 - sec.a);
    Shares s;
    s.valid1 = t1 > float(STARNT_GUARD_MIN_TRANSMITTANCE);
    s.valid2 = t2 > float(STARNT_GUARD_MIN_TRANSMITTANCE);
    s.behind1 = s.valid1 ? s2 / t1 : vec3(0.0);
    s.behind2 = s.valid2 ? s3 / t2 : vec3(0.0);
    return s;
}

// tiles::guardPixelOfBlock: the one pixel of each 2x2 block the guard evaluates, picked by an
// integer hash of the block (every invocation works: no idle lanes).
ivec2 guardPixelOfBlock(ivec2 block) {
    uint h = uint(block.x) * 0x8da6b343u ^ uint(block.y) * 0xd8163841u;
    h ^= h >> 13;
    h *= 0x165667b1u;
    h ^= h >> 16;
    return block * 2 + ivec2(int(h & 1u), int((h >> 1) & 1u));
}

void main() {
    ivec2 p = guardPixelOfBlock(ivec2(gl_GlobalInvocationID.xy));
    uint local = gl_LocalInvocationIndex;
    for (int i = 0; i < STARNT_GUARD_VALUES; ++i) s_values[i][local] = 0.0;
    if (p.x < u_size.x && p.y < u_size.y) {
        vec4 n = texelFetch(u_nearest, p, 0), sec = texelFetch(u_second, p, 0);
        if (n.a > 0.0) {
            vec3 c = texelFetch(u_composite, p, 0).rgb;
            vec3 front1 = n.a * n.rgb, front2 = front1 + (1.0 - n.a) * sec.a * sec.rgb;
            float t1 = 1.0 - n.a, t2 = t1 * (1.0 - sec.a);
            s_values[STARNT_GUARD_OCCUPIED][local] = 1.0;
            s_values[STARNT_GUARD_ENERGY_PASS2][local] = srgbSquaredError(c, front1);
            s_values[STARNT_GUARD_ENERGY_PASS3][local] = srgbSquaredError(c, front2);
            Shares own = sharesAt(p);
            for (int k = 0; k < 2; ++k) {
                int step = k == 0 ? 2 : 4;
                ivec2 last = (u_size - 1) / step * step;
                ivec2 p0 = p / step * step;
                ivec2 p1 = min(p0 + step, last);
                float fx = p1.x > p0.x ? float(p.x - p0.x) / float(step) : 0.0;
                float fy = p1.y > p0.y ? float(p.y - p0.y) / float(step) : 0.0;
                ivec2 samples[4] = ivec2[4](p0, ivec2(p1.x, p0.y), ivec2(p0.x, p1.y), p1);
                float w[4] = float[4]((1.0 - fx) * (1.0 - fy), fx * (1.0 - fy), (1.0 - fx) * fy, fx * fy);
                vec3 sum1 = vec3(0.0), sum2 = vec3(0.0);
                float weight1 = 0.0, weight2 = 0.0;
                for (int i = 0; i < 4; ++i) {
                    Shares s = sharesAt(samples[i]);
                    if (s.valid1) { sum1 += w[i] * s.behind1; weight1 += w[i]; }
                    if (s.valid2) { sum2 += w[i] * s.behind2; weight2 += w[i]; }
                }
                vec3 behind1 = weight1 > 0.0 ? sum1 / weight1 : own.behind1;
                vec3 behind2 = weight2 > 0.0 ? sum2 / weight2 : own.behind2;
                vec3 rebuilt2 = own.valid1 ? front1 + t1 * behind1 : c;
                vec3 rebuilt3 = own.valid2 ? front2 + t2 * behind2 : c;
                s_values[STARNT_GUARD_LOSS_PASS2_HALF + k][local] = srgbSquaredError(c, rebuilt2);
                s_values[STARNT_GUARD_LOSS_PASS3_HALF + k][local] = srgbSquaredError(c, rebuilt3);
            }
        }
    }
    barrier();
    // One invocation per value sums the tile in pixel order (the CPU reference's order).
    if (local < uint(STARNT_GUARD_VALUES)) {
        float sum = 0.0;
        for (int i = 0; i < 64; ++i) sum += s_values[local][i];
        uint tile = gl_WorkGroupID.y * uint(u_tiles.x) + gl_WorkGroupID.x;
        tileSums[tile * uint(STARNT_GUARD_VALUES) + local] = sum;
    }
}
