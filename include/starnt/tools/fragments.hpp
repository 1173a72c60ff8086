// Per-pixel fragment lists and the exact CPU compositor every GPU method is checked against.
//
// Colours are linear and straight (not premultiplied). "Over" compositing front to back:
//   C = sum_p a_p C_p prod_{q<p} (1 - a_q) + prod_all (1 - a) * C_bg
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace starnt {

struct Fragment {
    glm::vec3 color{0.0f};  // linear, straight
    float alpha = 0.0f;
    float depth = 0.0f;     // window depth in [0, 1], smaller is nearer
    uint32_t order = 0;     // submission order key (draw index << 24 | primitive id); used by `unsorted`
};
using FragmentList = std::vector<Fragment>;

// Sorts by depth, ties broken by submission order (so the result is deterministic).
void sortByDepth(FragmentList& fragments);
// Sorts by submission order: the order in which the GPU blends them in a single-pass method.
void sortBySubmission(FragmentList& fragments);

// Composites an already ordered list with "over", front (index 0) to back, over `background`.
glm::vec3 compositeOver(const FragmentList& ordered, const glm::vec3& background);
// Transmittance prod (1 - a_i) of every fragment in the list.
float totalTransmittance(const FragmentList& fragments);

}  // namespace starnt
