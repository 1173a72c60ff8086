// Pass 2 at scale s2 < 1 peels against a downsampled pass-1 depth: the maximum over the full
// pixels whose centres fall inside the reduced pixel (docs/DESIGN.md, "Pipeline and formats"). Reduced pixel i along an axis of
// full size F and reduced size R samples at i F/R + 0.5 (upsample_cpu.hpp) and covers full pixels
// j with (j + 0.5) in [i F/R + 0.5 - F/2R, i F/R + 0.5 + F/2R), i.e. j from ceil((2 i - 1) F / 2R)
// up to ceil((2 i + 1) F / 2R), exclusive; integer arithmetic, so the CPU reference
// (maxDownsampleDepth in upsample_cpu.cpp) matches exactly.
// Pass 2 computes it per fragment (2x2 or 4x4 reads, 3x3 or 5x5 at edges of odd sizes) instead of
// reading a downsampled target: a reduced pass 2 shades a quarter or a sixteenth of the fragments,
// so it reads no more than a full-resolution pass 2 does, and no target or dispatch is needed.
int peelCeilDiv(int a, int b) { return a <= 0 ? 0 : (a + b - 1) / b; }

ivec2 peelCoverBegin(ivec2 i, ivec2 fullSize, ivec2 reducedSize) {
    return ivec2(peelCeilDiv((2 * i.x - 1) * fullSize.x, 2 * reducedSize.x),
                 peelCeilDiv((2 * i.y - 1) * fullSize.y, 2 * reducedSize.y));
}

float reducedPeelDepth(sampler2D fullDepth, ivec2 i, ivec2 fullSize, ivec2 reducedSize) {
    ivec2 begin = peelCoverBegin(i, fullSize, reducedSize);
    ivec2 end = min(peelCoverBegin(i + 1, fullSize, reducedSize), fullSize);
    float depth = 0.0;
    for (int y = begin.y; y < end.y; ++y) {
        for (int x = begin.x; x < end.x; ++x) depth = max(depth, texelFetch(fullDepth, ivec2(x, y), 0).r);
    }
    return depth;
}
