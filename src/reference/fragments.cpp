#include "starnt/tools/fragments.hpp"

#include <algorithm>

namespace starnt {

void sortByDepth(FragmentList& fragments) {
    std::stable_sort(fragments.begin(), fragments.end(), [](const Fragment& a, const Fragment& b) {
        if (a.depth != b.depth) return a.depth < b.depth;
        return a.order < b.order;
    });
}

void sortBySubmission(FragmentList& fragments) {
    std::stable_sort(fragments.begin(), fragments.end(),
                     [](const Fragment& a, const Fragment& b) { return a.order < b.order; });
}

glm::vec3 compositeOver(const FragmentList& ordered, const glm::vec3& background) {
    glm::vec3 color(0.0f);
    float transmittance = 1.0f;
    for (const Fragment& f : ordered) {
        color += transmittance * f.alpha * f.color;
        transmittance *= 1.0f - f.alpha;
    }
    return color + transmittance * background;
}

float totalTransmittance(const FragmentList& fragments) {
    float t = 1.0f;
    for (const Fragment& f : fragments) t *= 1.0f - f.alpha;
    return t;
}

}  // namespace starnt
