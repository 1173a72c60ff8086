// CPU reference of the resolution changes around passes 2 and 3 (docs/DESIGN.md, "Pipeline and formats", 5): the max depth
// downsample pass 2 peels against, and the bilinear upsample the inference reads through
// (upsample.glsl). Images are row-major, rows bottom-first (GL order).
#pragma once
#include <vector>

#include <glm/glm.hpp>

#include "methods/neural/reduced_grid.hpp"

namespace starnt {


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
    // Joint upsampling only: pass-1 window depth at full size (1 = no fragment), and rows 2 and 3
    // of the inverse projection, z and w columns (m22, m32, m23, m33), to turn it into view distance.
    std::vector<float> nearestDepth;
    glm::vec4 depthUnproject{0.0f};
};

// How reduced images come back to full resolution (NeuralOptions::Upsample).
enum class UpsampleFilter { Bilinear, Joint };

// Joint bilateral tap weights of full pixel (x, y) in a reduced image of size `r` (upsample.glsl,
// jointTaps): the bilinear weights of the taps (x0,y0), (x1,y0), (x0,y1), (x1,y1), each times
// exp(-((d_tap - d) / (STARNT_UPSAMPLE_SIGMA d))^2), d the view distance of the pass-1 surface at
// the pixel and d_tap at the tap's sample (0 where the tap's sample has none), normalised. When every
// tap agrees to STARNT_UPSAMPLE_PLAIN_AGREEMENT, or the kept weight is below
// STARNT_UPSAMPLE_MIN_WEIGHT, the plain bilinear weights; `plain` says the former.
struct JointTapWeights {
    glm::vec4 weights{0.0f};
    bool plain = false;
};
JointTapWeights jointTapWeights(const PassTargets& targets, int x, int y, Size2 r);

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
// Joint: the same, with the four taps of pass 2 and of the tails weighted by jointTapWeights.
std::vector<UpsampledSums> upsamplePassSums(const PassTargets& targets, float transmittanceEpsilon,
                                            UpsampleFilter filter = UpsampleFilter::Bilinear);

}  // namespace starnt
