#include "reference/upsample_cpu.hpp"

#include <algorithm>
#include <cmath>

#include "methods/neural/upsample_constants.h"

namespace starnt {

int nearestSampleTexel(int t, int from, int to) {
    const long long x = (2LL * t * to + from) / (2LL * from);  // floor(t to / from + 1/2), t >= 0
    return std::clamp(int(x), 0, to - 1);
}

int coverBegin(int i, int full, int reduced) {
    // ceil((2 i - 1) F / 2R): the first j with j + 0.5 >= i F/R + 0.5 - F/2R.
    const long long a = (2LL * i - 1) * full, b = 2LL * reduced;
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

namespace {

// The four reduced texels around full pixel (x, y) and the weights of the second ones, as
// upsample.glsl's bilinearTaps computes them.
struct Taps {
    int x0, x1, y0, y1;
    float fx, fy;
};

Taps bilinearTaps(int x, int y, Size2 r, Size2 full) {
    const float ux = float(x) * float(r.width) / float(full.width);
    const float uy = float(y) * float(r.height) / float(full.height);
    const float bx = std::floor(ux), by = std::floor(uy);
    return {std::clamp(int(bx), 0, r.width - 1), std::clamp(int(bx) + 1, 0, r.width - 1),
            std::clamp(int(by), 0, r.height - 1), std::clamp(int(by) + 1, 0, r.height - 1), ux - bx, uy - by};
}

template <class T, class At>
T interpolate(const Taps& t, At at) {
    return glm::mix(glm::mix(at(t.x0, t.y0), at(t.x1, t.y0), t.fx), glm::mix(at(t.x0, t.y1), at(t.x1, t.y1), t.fx), t.fy);
}

// Weighted sum of the four taps in jointTapWeights' order.
template <class T, class At>
T weightedSum(const Taps& t, glm::vec4 w, At at) {
    return w.x * at(t.x0, t.y0) + w.y * at(t.x1, t.y0) + w.z * at(t.x0, t.y1) + w.w * at(t.x1, t.y1);
}

float viewDistance(float windowDepth, glm::vec4 unproject) {
    const float ndc = 2.0f * windowDepth - 1.0f;
    return -(unproject.x * ndc + unproject.y) / (unproject.z * ndc + unproject.w);
}

}  // namespace

JointTapWeights jointTapWeights(const PassTargets& t, int x, int y, Size2 r) {
    const Taps taps = bilinearTaps(x, y, r, t.full);
    const glm::vec4 bilinear((1.0f - taps.fx) * (1.0f - taps.fy), taps.fx * (1.0f - taps.fy), (1.0f - taps.fx) * taps.fy,
                             taps.fx * taps.fy);
    auto depthAt = [&](int px, int py) { return t.nearestDepth[size_t(py) * size_t(t.full.width) + size_t(px)]; };
    const float distance = viewDistance(depthAt(x, y), t.depthUnproject);
    auto agreement = [&](int tx, int ty) {
        const float z = depthAt(nearestSampleTexel(tx, r.width, t.full.width), nearestSampleTexel(ty, r.height, t.full.height));
        if (z >= 1.0f) return 0.0f;
        const float q = (viewDistance(z, t.depthUnproject) - distance) / (float(STARNT_UPSAMPLE_SIGMA) * distance);
        return std::exp(-q * q);
    };
    const glm::vec4 agree(agreement(taps.x0, taps.y0), agreement(taps.x1, taps.y0), agreement(taps.x0, taps.y1),
                          agreement(taps.x1, taps.y1));
    JointTapWeights out;
    out.plain = glm::all(glm::greaterThanEqual(agree, glm::vec4(float(STARNT_UPSAMPLE_PLAIN_AGREEMENT))));
    const glm::vec4 w = bilinear * agree;
    const float total = w.x + w.y + w.z + w.w;
    out.weights = !out.plain && total > float(STARNT_UPSAMPLE_MIN_WEIGHT) ? w / total : bilinear;
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
            if (r == full) {  // the taps fall on texel centres: the texel itself
                v = reduced[size_t(y) * size_t(r.width) + size_t(x)];
                if (alphaWeighted && v.a == 0.0f) v = glm::vec4(0.0f);
            } else {
                v = interpolate<glm::vec4>(bilinearTaps(x, y, r, full), at);
                if (alphaWeighted) v = v.a > 0.0f ? glm::vec4(glm::vec3(v) / v.a, v.a) : glm::vec4(0.0f);
            }
            out[size_t(y) * size_t(full.width) + size_t(x)] = v;
        }
    }
    return out;
}

std::vector<UpsampledSums> upsamplePassSums(const PassTargets& t, float transmittanceEpsilon, UpsampleFilter filter) {
    const size_t n = size_t(t.full.width) * size_t(t.full.height);
    std::vector<UpsampledSums> out(n);
    const bool fullResolution = t.pass2 == t.full && t.pass3 == t.full;
    const std::vector<glm::vec4> second = bilinearUpsample(t.second, t.pass2, t.full, true);

    // The tail of every pass-3 texel (TailSums / tailAt in neural_inputs.glsl).
    struct Tail {
        glm::vec4 alphaColor, colorCount;
        float transmittance;
    };
    std::vector<Tail> tails(size_t(t.pass3.width) * size_t(t.pass3.height));
    for (int y = 0; y < t.pass3.height && !fullResolution; ++y) {
        for (int x = 0; x < t.pass3.width; ++x) {
            auto nearest = [&](Size2 s) {
                return glm::ivec2(nearestSampleTexel(x, t.pass3.width, s.width), nearestSampleTexel(y, t.pass3.height, s.height));
            };
            const glm::ivec2 p1 = nearest(t.full), p2 = nearest(t.pass2);
            const glm::vec4 f1 = t.nearest[size_t(p1.y) * size_t(t.full.width) + size_t(p1.x)];
            const glm::vec4 f2 = t.second[size_t(p2.y) * size_t(t.pass2.width) + size_t(p2.x)];
            const size_t i = size_t(y) * size_t(t.pass3.width) + size_t(x);
            const float has1 = f1.a > 0.0f ? 1.0f : 0.0f, has2 = f2.a > 0.0f ? 1.0f : 0.0f;
            Tail& tail = tails[i];
            tail.alphaColor = glm::max(t.alphaColor[i] - glm::vec4(glm::vec3(f1) * f1.a, f1.a) -
                                           glm::vec4(glm::vec3(f2) * f2.a, f2.a), glm::vec4(0.0f));
            tail.colorCount = glm::max(t.colorCount[i] - glm::vec4(glm::vec3(f1), 1.0f) * has1 -
                                           glm::vec4(glm::vec3(f2), 1.0f) * has2, glm::vec4(0.0f));
            const float t2 = (1.0f - f1.a) * (1.0f - f2.a);
            tail.transmittance = t2 > transmittanceEpsilon ? std::clamp(t.transmittance[i] / t2, 0.0f, 1.0f) : 1.0f;
        }
    }

    for (int y = 0; y < t.full.height; ++y) {
        for (int x = 0; x < t.full.width; ++x) {
            const size_t i = size_t(y) * size_t(t.full.width) + size_t(x);
            UpsampledSums& s = out[i];
            s.nearest = t.nearest[i];
            if (s.nearest.a == 0.0f) {
                s = UpsampledSums{};
                continue;
            }
            if (fullResolution) {
                s.second = t.second[i];
                s.alphaColor = t.alphaColor[i];
                s.colorCount = t.colorCount[i];
                s.transmittance = t.transmittance[i];
                continue;
            }
            s.second = second[i];
            const Taps taps = bilinearTaps(x, y, t.pass3, t.full);
            auto tail = [&](int tx, int ty) -> const Tail& { return tails[size_t(ty) * size_t(t.pass3.width) + size_t(tx)]; };
            auto tailAlphaColor = [&](int tx, int ty) { return tail(tx, ty).alphaColor; };
            auto tailColorCount = [&](int tx, int ty) { return tail(tx, ty).colorCount; };
            auto tailTransmittance = [&](int tx, int ty) { return tail(tx, ty).transmittance; };
            glm::vec4 tailAc, tailCn;
            float tailT;
            const JointTapWeights joint3 =
                filter == UpsampleFilter::Joint ? jointTapWeights(t, x, y, t.pass3) : JointTapWeights{glm::vec4(0.0f), true};
            if (joint3.plain) {
                tailAc = interpolate<glm::vec4>(taps, tailAlphaColor);
                tailCn = interpolate<glm::vec4>(taps, tailColorCount);
                tailT = interpolate<float>(taps, tailTransmittance);
            } else {
                tailAc = weightedSum<glm::vec4>(taps, joint3.weights, tailAlphaColor);
                tailCn = weightedSum<glm::vec4>(taps, joint3.weights, tailColorCount);
                tailT = weightedSum<float>(taps, joint3.weights, tailTransmittance);
            }
            if (filter == UpsampleFilter::Joint && !(t.pass2 == t.full)) {
                const JointTapWeights joint2 = t.pass2 == t.pass3 ? joint3 : jointTapWeights(t, x, y, t.pass2);
                const glm::vec4 p = weightedSum<glm::vec4>(bilinearTaps(x, y, t.pass2, t.full), joint2.weights, [&](int tx, int ty) {
                    const glm::vec4 v = t.second[size_t(ty) * size_t(t.pass2.width) + size_t(tx)];
                    return glm::vec4(glm::vec3(v) * v.a, v.a);
                });
                s.second = p.a > 0.0f ? glm::vec4(glm::vec3(p) / p.a, p.a) : glm::vec4(0.0f);
            }
            const glm::vec3 c1(s.nearest), c2(s.second);
            const float a1 = s.nearest.a, a2 = s.second.a;
            const float has1 = a1 > 0.0f ? 1.0f : 0.0f, has2 = a2 > 0.0f ? 1.0f : 0.0f;
            s.alphaColor = glm::vec4(glm::vec3(tailAc) + a1 * c1 + a2 * c2, tailAc.a + a1 + a2);
            s.colorCount = glm::vec4(glm::vec3(tailCn) + has1 * c1 + has2 * c2, tailCn.a + has1 + has2);
            s.transmittance = tailT * (1.0f - a1) * (1.0f - a2);
        }
    }
    return out;
}

}  // namespace starnt
