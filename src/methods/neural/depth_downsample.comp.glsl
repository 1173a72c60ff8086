// Pass 2 at scale s2 < 1 peels against a downsampled pass-1 depth: the maximum over the full
// pixels whose centres fall inside the reduced pixel (SPEC 2). Reduced pixel i along an axis of
// full size F and reduced size R samples at i F/R + 0.5 (upsample_cpu.hpp) and covers full pixels
// j with (j + 0.5) in [i F/R + 0.5 - F/2R, i F/R + 0.5 + F/2R), i.e. j from ceil((2 i - 1) F / 2R)
// up to ceil((2 i + 1) F / 2R), exclusive; integer arithmetic, so the CPU reference
// (upsample_cpu.cpp) matches exactly.
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0) uniform sampler2D u_nearestDepth;  // full resolution
layout(binding = 0, r32f) writeonly uniform highp image2D u_reducedDepth;
uniform ivec2 u_fullSize;
uniform ivec2 u_reducedSize;

int ceilDiv(int a, int b) { return a <= 0 ? 0 : (a + b - 1) / b; }

ivec2 coverBegin(ivec2 i) {
    return ivec2(ceilDiv((2 * i.x - 1) * u_fullSize.x, 2 * u_reducedSize.x),
                 ceilDiv((2 * i.y - 1) * u_fullSize.y, 2 * u_reducedSize.y));
}

void main() {
    ivec2 i = ivec2(gl_GlobalInvocationID.xy);
    if (i.x >= u_reducedSize.x || i.y >= u_reducedSize.y) return;
    ivec2 begin = coverBegin(i);
    ivec2 end = min(coverBegin(i + 1), u_fullSize);
    float depth = 0.0;
    for (int y = begin.y; y < end.y; ++y) {
        for (int x = begin.x; x < end.x; ++x) depth = max(depth, texelFetch(u_nearestDepth, ivec2(x, y), 0).r);
    }
    imageStore(u_reducedDepth, i, vec4(depth, 0.0, 0.0, 0.0));
}
