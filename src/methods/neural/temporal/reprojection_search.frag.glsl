// Reprojection of the last real frame to the current camera by a backward search (gather), one
// full-screen pass. reprojection_cpu.hpp states the algorithm and runs the same float
// operations on the CPU; read it first.
//
// Why a gather: a forward splat needs a clear, an atomic depth test per source, a tie-break pass
// and a hole fill, four passes through storage buffers; on llvmpipe they cost ~90 ms at 1280x720.
// Here every output pixel solves for its own source with a few depth fetches (~31-40 ms there).
#include "methods/neural/temporal/reprojection_constants.h"
#include "methods/neural/half_targets.glsl"
#include "methods/common/background.glsl"
// The history holds the layers over black and their transmittance (history_premultiplied.frag.glsl:
// the frame has an opaque scene), composited here over this frame's background.
uniform bool u_premultipliedHistory;
// A 16-bit float output (compact targets): values rounded to the nearest one here, as the real
// frames' inference does (half_targets.glsl), so a refresh frame equals a real one bit for bit
// where it should.
uniform bool u_halfOutput;

layout(binding = 0) uniform highp sampler2D u_color;  // last real frame's composite, linear RGBA
layout(binding = 1) uniform highp sampler2D u_depth;  // its pass-1 window depth, 1 = nothing drawn
layout(binding = 2) uniform highp sampler2D u_seeds;  // (min, max) depth around each pixel block

uniform ivec2 u_size;
// Rows 0, 1 and 3 of R = newViewProj * inverse(oldViewProj), and row 3 of inverse(oldViewProj).
uniform vec4 u_row0, u_row1, u_row3, u_sourceScale;
uniform vec4 u_row2;  // row 2 of R: the source point's new window depth, against the opaque depth

#ifdef STARNT_REFRESH
// Refresh frames: the kept frame's pass-1 colour, and pass 1 rendered at the new camera.
layout(binding = 3) uniform highp sampler2D u_keptNearest;
layout(binding = 4) uniform highp sampler2D u_nearest;
layout(binding = 5) uniform highp sampler2D u_behind;  // reprojection_behind.frag.glsl: (B, 1 / view depth)

// temporal::refreshComposite (reprojection_cpu.hpp states it): the fresh nearest layer over
// what lay behind the kept frame's nearest layer at the source texel.
vec3 refreshComposite(vec3 keptComposite, vec4 keptNearest, vec4 nearest, vec3 background) {
    if (!(nearest.a > 0.0)) return background;
    vec3 front = nearest.a * nearest.rgb;
    float keptOpen = 1.0 - keptNearest.a;
    if (!(keptOpen > float(STARNT_TEMPORAL_MIN_TRANSMITTANCE))) return front + (1.0 - nearest.a) * background;
    float r = (1.0 - nearest.a) / keptOpen;
    return max(r * keptComposite + (front - r * (keptNearest.a * keptNearest.rgb)), vec3(0.0));
}

// The same from a premultiplied history (kept = layers over black, transmittance): the layers over
// black and the transmittance of the refreshed pixel. What lay behind the kept nearest layer lets
// T_kept / (1 - a_kept) of the background through; the fresh layer then (1 - a) of that.
vec4 refreshPremultiplied(vec4 kept, vec4 keptNearest, vec4 nearest) {
    if (!(nearest.a > 0.0)) return vec4(0.0, 0.0, 0.0, 1.0);
    vec3 front = nearest.a * nearest.rgb;
    float keptOpen = 1.0 - keptNearest.a;
    if (!(keptOpen > float(STARNT_TEMPORAL_MIN_TRANSMITTANCE))) return vec4(front, 1.0 - nearest.a);
    float r = (1.0 - nearest.a) / keptOpen;
    return vec4(max(r * kept.rgb + (front - r * (keptNearest.a * keptNearest.rgb)), vec3(0.0)), r * kept.a);
}
#else
layout(binding = 6) uniform highp sampler2D u_opaqueDepth;  // this frame's (FrameDesc::opaqueDepth)
uniform bool u_opaqueClip;
uniform bool u_opaqueReversed;  // that depth is reversed (DepthConvention): canonical = 1 - d
#endif


out vec4 o_color;

// The old window position whose point at old window depth z lands on the new NDC point c, and that
// point's view depth along the new camera's axis (<= 0 or NaN: behind the new camera, or no
// solution). Two linear equations: (row0 - c.x row3) . v = 0 and (row1 - c.y row3) . v = 0 with
// v = (old ndc xy, old ndc z, 1).
vec2 sourceFor(vec2 c, float z, out float newViewDepth) {
    float zn = z * 2.0 - 1.0;
    vec4 a = u_row0 - c.x * u_row3;
    vec4 b = u_row1 - c.y * u_row3;
    float det = a.x * b.y - a.y * b.x;
    vec2 rhs = -vec2(a.z * zn + a.w, b.z * zn + b.w);
    vec2 ndc = vec2(rhs.x * b.y - a.y * rhs.y, a.x * rhs.y - rhs.x * b.x) / det;
    vec4 v = vec4(ndc, zn, 1.0);
    newViewDepth = dot(u_row3, v) / dot(u_sourceScale, v);
    return (ndc * 0.5 + 0.5) * vec2(u_size);
}

// The search state of one pixel: the nearest consistent source so far, and the farthest texel
// any search visited (the fallback for a disoccluded pixel). main() resets them; they are
// initialised here too so that the compiler sees no read before a write (Mesa warns, and debug
// contexts turn the warning into an error).
ivec2 bestTexel = ivec2(-1);
vec2 bestPosition = vec2(0.0);  // the consistent source's old window position (continuous)
float bestViewDepth = uintBitsToFloat(0x7F800000u);  // +infinity
ivec2 farTexel = ivec2(-1);
float farDepth = -1.0;

void search(vec2 c, float z) {
    for (int step = 0; step < STARNT_TEMPORAL_SEARCH_STEPS; ++step) {
        float viewDepth;
        vec2 q = sourceFor(c, z, viewDepth);
        if (!(viewDepth > 0.0)) return;
        // A seed whose point is not clearly nearer than the source already found cannot win.
        if (step == 0 && !(viewDepth < bestViewDepth * STARNT_TEMPORAL_NEARER)) return;
        // Off the old image (or NaN): the source was not seen.
        if (!(q.x >= 0.0 && q.y >= 0.0 && q.x < float(u_size.x) && q.y < float(u_size.y))) return;
        ivec2 t = ivec2(q);
        float found = texelFetch(u_depth, t, 0).r;
        if (found > farDepth) {
            farDepth = found;
            farTexel = t;
        }
        if (found == z) {  // consistent: the point at depth z lies in a texel of depth z
            if (viewDepth < bestViewDepth) {
                bestViewDepth = viewDepth;
                bestTexel = t;
                bestPosition = q;
            }
            return;
        }
        z = found;
    }
}

void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    vec2 c = (vec2(p) + 0.5) / vec2(u_size) * 2.0 - 1.0;
    bestTexel = ivec2(-1);
    bestViewDepth = uintBitsToFloat(0x7F800000u);  // +infinity
    farTexel = ivec2(-1);
    farDepth = -1.0;

    // Seeds: the depth at the same pixel, and the nearest and farthest depth around its block, so
    // that an occluder or a background moving in from a few pixels away is found.
    float here = texelFetch(u_depth, p, 0).r;
    vec2 seeds = texelFetch(u_seeds, p / STARNT_TEMPORAL_SEED_BLOCK, 0).rg;
    float nearest = seeds.x, farthest = seeds.y;
    search(c, here);
    if (nearest != here) search(c, nearest);
    if (farthest != here && bestTexel.x < 0) search(c, farthest);  // only a disocclusion needs it

    ivec2 source = bestTexel.x >= 0 ? bestTexel : farTexel.x >= 0 ? farTexel : p;
#ifdef STARNT_REFRESH
    vec4 fresh = texelFetch(u_nearest, p, 0);
    if (bestTexel.x >= 0 && fresh.a > 0.0) {
        // temporal::refreshPixel: the behind shares of the 2x2 texels around the source position,
        // weighted bilinearly, only those of the source's surface (depth-aware bilinear).
        vec2 f = bestPosition - 0.5;
        ivec2 base = ivec2(floor(f));
        vec2 w = f - vec2(base);
        float reference = texelFetch(u_behind, bestTexel, 0).a;
        vec3 sum = vec3(0.0);
        float weight = 0.0, own = 0.0;
        for (int k = 0; k < 4 && reference > 0.0; ++k) {
            ivec2 t = clamp(base + ivec2(k & 1, k >> 1), ivec2(0), u_size - 1);
            float wk = ((k & 1) != 0 ? w.x : 1.0 - w.x) * ((k >> 1) != 0 ? w.y : 1.0 - w.y);
            vec4 b = texelFetch(u_behind, t, 0);
            if (!(b.a > 0.0) || abs(b.a / reference - 1.0) > float(STARNT_TEMPORAL_SAME_SURFACE)) continue;
            sum += wk * b.rgb;
            weight += wk;
            if (t == bestTexel) own += wk;
        }
        if (weight > 0.0 && own < 0.999 * weight) {
            vec3 color = fresh.a * fresh.rgb + (1.0 - fresh.a) * max(sum / weight, vec3(0.0));
            float transmittance = 1.0;
            if (u_premultipliedHistory) {
                // The behind shares are over black: the background through what lay behind the kept
                // nearest layer at the source texel, then through the fresh layer.
                float keptOpen = max(1.0 - texelFetch(u_keptNearest, bestTexel, 0).a, float(STARNT_TEMPORAL_MIN_TRANSMITTANCE));
                transmittance = (1.0 - fresh.a) * clamp(texelFetch(u_color, bestTexel, 0).a / keptOpen, 0.0, 1.0);
                color += transmittance * background();
            }
            o_color = outputValue(vec4(color, outputAlpha(transmittance)), u_halfOutput);
            return;
        }
    }
    if (u_premultipliedHistory) {
        vec4 q = refreshPremultiplied(texelFetch(u_color, source, 0), texelFetch(u_keptNearest, source, 0), texelFetch(u_nearest, p, 0));
        o_color = outputValue(vec4(q.rgb + q.a * background(), outputAlpha(q.a)), u_halfOutput);
        return;
    }
    o_color = outputValue(vec4(refreshComposite(texelFetch(u_color, source, 0).rgb, texelFetch(u_keptNearest, source, 0),
                                                texelFetch(u_nearest, p, 0), background()), 1.0), u_halfOutput);
#else
    vec4 kept = texelFetch(u_color, source, 0);
    if (!u_premultipliedHistory) {
        o_color = kept;
        return;
    }
    // A source point that lies at or behind this frame's opaque surface at p is hidden by it.
    if (u_opaqueClip && bestTexel.x >= 0) {
        vec4 v = vec4(bestPosition / vec2(u_size) * 2.0 - 1.0, texelFetch(u_depth, bestTexel, 0).r * 2.0 - 1.0, 1.0);
        float newDepth = dot(u_row2, v) / dot(u_row3, v) * 0.5 + 0.5;
        float opaque = texelFetch(u_opaqueDepth, p, 0).r;
        if (!(newDepth < (u_opaqueReversed ? 1.0 - opaque : opaque))) kept = vec4(0.0, 0.0, 0.0, 1.0);
    }
    o_color = outputValue(vec4(kept.rgb + kept.a * background(), outputAlpha(kept.a)), u_halfOutput);
#endif
}
