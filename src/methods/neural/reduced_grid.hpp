// Where the reduced passes 2 and 3 sample the full-resolution window (docs/DESIGN.md, "Pipeline and formats", 5). Runtime
// (neural_passes.cpp) and the CPU reference (upsample_cpu.*) share it.
#pragma once

namespace starnt {

struct Size2 {
    int width = 0, height = 0;
    bool operator==(const Size2&) const = default;
};

// Sample alignment of the reduced passes. Along an axis of full size F, reduced texel i (of R)
// samples the full window at x = i F / R + 0.5, so when F = k R every reduced sample is the centre
// of full pixel k i: the pass-3 sums there hold exactly the fragments pass 1 saw at that pixel,
// and the tail resolve subtracts the right ones. (Sampling at the reduced texel centres instead,
// x = (i + 0.5) F / R, puts every sample on a pixel corner, half a pixel from any pass-1 sample.)
// The reduced passes get this by a viewport moved by reducedViewportOffset() reduced pixels.
inline float reducedViewportOffset(int reduced, int full) { return 0.5f * (1.0f - float(reduced) / float(full)); }

}  // namespace starnt
