// Reprojection, step 0: no target has a splat yet.
#include "methods/neural/temporal/reprojection_bindings.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = STARNT_SSBO_TEMPORAL_WINNER_KEY) writeonly buffer WinnerKey { uint winnerKey[]; };
layout(std430, binding = STARNT_SSBO_TEMPORAL_WINNER_SOURCE) writeonly buffer WinnerSource { uint winnerSource[]; };

uniform ivec2 u_size;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= u_size.x || p.y >= u_size.y) return;
    uint index = uint(p.y) * uint(u_size.x) + uint(p.x);
    winnerKey[index] = STARNT_TEMPORAL_NONE;
    winnerSource[index] = STARNT_TEMPORAL_NONE;
}
