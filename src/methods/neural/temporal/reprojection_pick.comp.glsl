// Reprojection, step B: among the sources that reached a target with the winning (nearest) key,
// the lowest source index wins, so equal depths resolve the same way on every run and on the CPU.
#include "methods/neural/temporal/reprojection_bindings.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = STARNT_SSBO_TEMPORAL_SPLATS) readonly buffer Splats { uvec2 splats[]; };
layout(std430, binding = STARNT_SSBO_TEMPORAL_WINNER_KEY) readonly buffer WinnerKey { uint winnerKey[]; };
layout(std430, binding = STARNT_SSBO_TEMPORAL_WINNER_SOURCE) buffer WinnerSource { uint winnerSource[]; };

uniform ivec2 u_size;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= u_size.x || p.y >= u_size.y) return;
    uint source = uint(p.y) * uint(u_size.x) + uint(p.x);
    uvec2 splat = splats[source];
    if (splat.x != STARNT_TEMPORAL_NONE && winnerKey[splat.x] == splat.y) atomicMin(winnerSource[splat.x], source);
}
