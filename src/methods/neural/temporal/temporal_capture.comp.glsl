// Keeps a real frame for later reprojection: copies its composite and its pass-1 depth into the
// history buffers (the method overwrites its own targets on the next real frame). Reading both
// through texelFetch accepts a DEPTH_COMPONENT32F or an R32F depth texture alike.
#include "methods/neural/temporal/reprojection_bindings.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = STARNT_SSBO_TEMPORAL_COLOR) writeonly buffer HistoryColor { vec4 historyColor[]; };
layout(std430, binding = STARNT_SSBO_TEMPORAL_DEPTH) writeonly buffer HistoryDepth { float historyDepth[]; };
layout(binding = 0) uniform highp sampler2D u_composite;
layout(binding = 1) uniform highp sampler2D u_depth;

uniform ivec2 u_size;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= u_size.x || p.y >= u_size.y) return;
    uint index = uint(p.y) * uint(u_size.x) + uint(p.x);
    historyColor[index] = texelFetch(u_composite, p, 0);
    historyDepth[index] = texelFetch(u_depth, p, 0).r;
}
