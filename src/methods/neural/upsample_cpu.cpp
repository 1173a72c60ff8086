#include "methods/neural/upsample_cpu.hpp"

#include <algorithm>
#include <cmath>

namespace starnt {

int coverBegin(int i, int full, int reduced) {
    const long long a = 2LL * i * full - reduced, b = 2LL * reduced;
    return a <= 0 ? 0 : int((a + b - 1) / b);
}

std::vector<float> maxDownsampleDepth(const std::vector<float>& depth, Size2 full, Size2 reduced) {
    std::vector<float> out(size_t(reduced.width) * size_t(reduced.height), 0.0f);
    for (int y = 0; y < reduced.height; ++y) {
        const int y0 = coverBegin(y, full.height, reduced.height);
        const int y1 = std::min(coverBegin(y + 1, full.height, reduced.height), full.height);
        for (int x = 0; x < reduced.width; ++x) {
            const int x0 = coverBegin(x, full.width, reduced.width);
            const int x1 = std::min(coverBegin(x + 1, full.width, reduced.width), full.width);
            float d = 0.0f;
            for (int j = y0; j < y1; ++j) {
                for (int i = x0; i < x1; ++i) d = std::max(d, depth[size_t(j) * size_t(full.width) + size_t(i)]);
            }
            out[size_t(y) * size_t(reduced.width) + size_t(x)] = d;
        }
    }
    return out;
}

std::vector<glm::vec4> bilinearUpsample(const std::vector<glm::vec4>& reduced, Size2 r, Size2 full, bool alphaWeighted) {
    std::vector<glm::vec4> out(size_t(full.width) * size_t(full.height));
    auto at = [&](int x, int y) {
        glm::vec4 v = reduced[size_t(y) * size_t(r.width) + size_t(x)];
        return alphaWeighted ? glm::vec4(glm::vec3(v) * v.a, v.a) : v;
    };
    for (int y = 0; y < full.height; ++y) {
        for (int x = 0; x < full.width; ++x) {
            glm::vec4 v;
            if (r == full) {
                v = reduced[size_t(y) * size_t(r.width) + size_t(x)];
            } else {
                const float ux = (float(x) + 0.5f) * float(r.width) / float(full.width) - 0.5f;
                const float uy = (float(y) + 0.5f) * float(r.height) / float(full.height) - 0.5f;
                const float bx = std::floor(ux), by = std::floor(uy);
                const float fx = ux - bx, fy = uy - by;
                const int x0 = std::clamp(int(bx), 0, r.width - 1), x1 = std::clamp(int(bx) + 1, 0, r.width - 1);
                const int y0 = std::clamp(int(by), 0, r.height - 1), y1 = std::clamp(int(by) + 1, 0, r.height - 1);
                const glm::vec4 bottom = glm::mix(at(x0, y0), at(x1, y0), fx);
                const glm::vec4 top = glm::mix(at(x0, y1), at(x1, y1), fx);
                v = glm::mix(bottom, top, fy);
                if (alphaWeighted) v = v.a > 0.0f ? glm::vec4(glm::vec3(v) / v.a, v.a) : glm::vec4(0.0f);
            }
            out[size_t(y) * size_t(full.width) + size_t(x)] = v;
        }
    }
    return out;
}

}  // namespace starnt
