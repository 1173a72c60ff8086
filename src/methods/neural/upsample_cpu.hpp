// CPU reference of the resolution changes around passes 2 and 3 (SPEC 2, 5): the max depth
// downsample pass 2 peels against, and the bilinear upsample the inference reads through
// (upsample.glsl). Images are row-major, rows bottom-first (GL order).
#pragma once
#include <vector>

#include <glm/glm.hpp>

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
float reducedViewportOffset(int reduced, int full);

// The texel of an image of size `to` whose sample lies nearest to the sample of texel t of an image
// of size `from` (both aligned as above, full pixels are the size-F case): round(t to / from),
// in integer arithmetic, clamped to the image.
int nearestSampleTexel(int t, int from, int to);

// First full pixel covered by reduced pixel i: the full pixels whose centres fall inside the
// reduced pixel's footprint [i F/R + 0.5 - F/2R, i F/R + 0.5 + F/2R) (the end of pixel i is
// coverBegin(i + 1)).
int coverBegin(int i, int full, int reduced);

// Max of the covered full-resolution depths for every reduced pixel.
std::vector<float> maxDownsampleDepth(const std::vector<float>& depth, Size2 full, Size2 reduced);

// Full-resolution bilinear upsample of a reduced image: full pixel p reads it at the continuous
// texel position u = p R / F (texel i's sample at u = i), from the two texels around u per axis,
// clamped to the image. alphaWeighted: (rgb, a) is a straight
// colour with alpha, interpolated as premultiplied and divided back (0 where alpha is 0).
std::vector<glm::vec4> bilinearUpsample(const std::vector<glm::vec4>& reduced, Size2 reducedSize, Size2 full,
                                        bool alphaWeighted);

// What passes 1-3 leave, as the inference reads it: pass 1 at full size, passes 2 and 3 at their
// (possibly reduced) sizes. Rows bottom-first.
struct PassTargets {
    Size2 full, pass2, pass3;
    std::vector<glm::vec4> nearest;       // full: C1, a1 (a1 = 0: no fragment)
    std::vector<glm::vec4> second;        // pass2: C2, a2
    std::vector<glm::vec4> alphaColor;    // pass3: sum a C, sum a
    std::vector<glm::vec4> colorCount;    // pass3: sum C, N
    std::vector<float> transmittance;     // pass3: prod (1 - a)
};

// One full-resolution pixel's sums after upsampling (readPixelSums in neural_inputs.glsl).
struct UpsampledSums {
    glm::vec4 nearest{0.0f}, second{0.0f}, alphaColor{0.0f}, colorCount{0.0f};
    float transmittance = 1.0f;
};

// The inference's view of every full-resolution pixel. A pixel without a pass-1 fragment is
// background (all zero, transmittance 1). With both passes at full size: plain reads. Otherwise
// pass 2 is upsampled alpha-weighted, and pass 3 TAIL-FIRST: each pass-3 texel's tail (its sums
// minus the nearest fragment at its sample, read from the full-size pass-1 pixel nearest to it, and
// the pass-2 texel whose sample is nearest to it; transmittance divided by theirs, guarded by `transmittanceEpsilon` -> 1) is
// interpolated bilinearly, and the pixel adds back its own two layers. Interpolating the sums and
// subtracting the pixel's own layers instead would remove fragments the neighbours never had.
std::vector<UpsampledSums> upsamplePassSums(const PassTargets& targets, float transmittanceEpsilon);

}  // namespace starnt
