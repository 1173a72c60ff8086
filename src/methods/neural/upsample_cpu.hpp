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

// First full pixel covered by reduced pixel i (the end of pixel i is coverBegin(i + 1)).
int coverBegin(int i, int full, int reduced);

// Max of the covered full-resolution depths for every reduced pixel.
std::vector<float> maxDownsampleDepth(const std::vector<float>& depth, Size2 full, Size2 reduced);

// Full-resolution bilinear upsample of a reduced image. alphaWeighted: (rgb, a) is a straight
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
// minus the nearest fragment under its centre, read from full-size pass 1, and the pass-2 texel
// under its centre; transmittance divided by theirs, guarded by `transmittanceEpsilon` -> 1) is
// interpolated bilinearly, and the pixel adds back its own two layers. Interpolating the sums and
// subtracting the pixel's own layers instead would remove fragments the neighbours never had.
std::vector<UpsampledSums> upsamplePassSums(const PassTargets& targets, float transmittanceEpsilon);

}  // namespace starnt
