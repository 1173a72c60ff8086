// Reprojection, step A (see reprojection_reference.hpp, which does the same on the CPU): every
// source pixel becomes a point at its centre and pass-1 depth, is carried to the new camera by
// u_reprojection = newViewProj * inverse(oldViewProj), and competes for the pixel it lands in with
// its new view depth: the nearest key wins by atomicMin. The product gives clip coordinates scaled
// by 1 / (old view depth) = dot(u_sourceScale, ndc) (row 3 of inverse(oldViewProj)), so the
// depth is clip.w divided by that. The (target, key) pair is stored so that step B compares the
// very same bits instead of recomputing them in another program.
#include "methods/neural/temporal/reprojection_bindings.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = STARNT_SSBO_TEMPORAL_DEPTH) readonly buffer HistoryDepth { float historyDepth[]; };
layout(std430, binding = STARNT_SSBO_TEMPORAL_SPLATS) writeonly buffer Splats { uvec2 splats[]; };
layout(std430, binding = STARNT_SSBO_TEMPORAL_WINNER_KEY) buffer WinnerKey { uint winnerKey[]; };

uniform ivec2 u_size;
uniform mat4 u_reprojection;
uniform vec4 u_sourceScale;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= u_size.x || p.y >= u_size.y) return;
    uint source = uint(p.y) * uint(u_size.x) + uint(p.x);

    vec2 size = vec2(u_size);
    vec2 centre = (vec2(p) + 0.5) / size * 2.0 - 1.0;
    vec4 ndc = vec4(centre, historyDepth[source] * 2.0 - 1.0, 1.0);
    vec4 clip = u_reprojection * ndc;
    uvec2 splat = uvec2(STARNT_TEMPORAL_NONE, STARNT_TEMPORAL_NONE);
    if (clip.w > 0.0) {  // behind the new camera (or NaN): dropped
        vec2 window = (clip.xy / clip.w * 0.5 + 0.5) * size;
        // Off-screen (or NaN): dropped.
        if (window.x >= 0.0 && window.y >= 0.0 && window.x < size.x && window.y < size.y) {
            ivec2 target = ivec2(window);  // floor: window >= 0
            uint targetIndex = uint(target.y) * uint(u_size.x) + uint(target.x);
            // The view depth along the new camera's axis, > 0: positive floats order like their
            // bits. (New NDC z misordered far points by ~1e-4 from float cancellation.)
            uint key = floatBitsToUint(clip.w / dot(u_sourceScale, ndc));
            splat = uvec2(targetIndex, key);
            atomicMin(winnerKey[targetIndex], key);
        }
    }
    splats[source] = splat;
}
