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

}  // namespace starnt
