// Reprojection, step C: each target pixel shows its winning source's colour. Holes (no splat: a
// crack between magnified splats or a disocclusion) take the colour of the FARTHEST winner within
// STARNT_TEMPORAL_FILL_RADIUS pixels (a 5x5 window), so a disoccluded area shows what lies behind
// rather than smearing the occluder; the first in row-major order wins on equal keys. With no winner around either (content
// entering at the border), the fallback is the real frame's colour at the same pixel.
#include "methods/neural/temporal/reprojection_bindings.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = STARNT_SSBO_TEMPORAL_COLOR) readonly buffer HistoryColor { vec4 historyColor[]; };
layout(std430, binding = STARNT_SSBO_TEMPORAL_WINNER_KEY) readonly buffer WinnerKey { uint winnerKey[]; };
layout(std430, binding = STARNT_SSBO_TEMPORAL_WINNER_SOURCE) readonly buffer WinnerSource { uint winnerSource[]; };
layout(binding = 0, rgba32f) writeonly uniform highp image2D u_output;

uniform ivec2 u_size;

void main() {
    ivec2 p = ivec2(gl_GlobalInvocationID.xy);
    if (p.x >= u_size.x || p.y >= u_size.y) return;
    uint target = uint(p.y) * uint(u_size.x) + uint(p.x);
    uint source = winnerSource[target];
    if (source == STARNT_TEMPORAL_NONE) {
        uint farthestKey = 0u;
        for (int dy = -STARNT_TEMPORAL_FILL_RADIUS; dy <= STARNT_TEMPORAL_FILL_RADIUS; ++dy) {
            for (int dx = -STARNT_TEMPORAL_FILL_RADIUS; dx <= STARNT_TEMPORAL_FILL_RADIUS; ++dx) {
                ivec2 q = p + ivec2(dx, dy);
                if (q.x < 0 || q.y < 0 || q.x >= u_size.x || q.y >= u_size.y) continue;
                uint neighbour = uint(q.y) * uint(u_size.x) + uint(q.x);
                uint candidate = winnerSource[neighbour];
                if (candidate == STARNT_TEMPORAL_NONE) continue;
                if (source == STARNT_TEMPORAL_NONE || winnerKey[neighbour] > farthestKey) {
                    source = candidate;
                    farthestKey = winnerKey[neighbour];
                }
            }
        }
    }
    imageStore(u_output, p, historyColor[source == STARNT_TEMPORAL_NONE ? target : source]);
}
