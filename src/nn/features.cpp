// CPU reference of the per-pixel sums (passes 1-3), the network features, the training targets
// and the final composites. The guards are documented in include/starnt/nn.hpp.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include "starnt/nn.hpp"

namespace starnt::nn {

FragmentList preparedFragments(FragmentList fragments, float alphaCutoff) {
    std::erase_if(fragments, [&](const Fragment& f) { return !(f.alpha >= alphaCutoff); });
    sortByDepth(fragments);
    return fragments;
}

PixelSums sumsFromFragments(FragmentList fragments, float alphaCutoff) {
    fragments = preparedFragments(std::move(fragments), alphaCutoff);
    PixelSums s;
    if (!fragments.empty()) {
        s.c1 = fragments[0].color;
        s.a1 = fragments[0].alpha;
    }
    if (fragments.size() > 1) {
        s.c2 = fragments[1].color;
        s.a2 = fragments[1].alpha;
    }
    double sumAlpha = 0.0, transmittance = 1.0;
    glm::dvec3 sumAlphaColor(0.0), sumColor(0.0);
    for (const Fragment& f : fragments) {
        const double a = f.alpha;
        const glm::dvec3 c(f.color);
        sumAlpha += a;
        sumAlphaColor += a * c;
        sumColor += c;
        transmittance *= 1.0 - a;
    }
    s.count = static_cast<float>(fragments.size());
    s.sumAlpha = static_cast<float>(sumAlpha);
    s.sumAlphaColor = glm::vec3(sumAlphaColor);
    s.sumColor = glm::vec3(sumColor);
    s.transmittance = static_cast<float>(transmittance);
    return s;
}

float roundToHalf(float v, bool towardZero) {
    _Float16 h = static_cast<_Float16>(v);  // to nearest, ties to even
    if (towardZero && std::abs(float(h)) > std::abs(v)) h = std::bit_cast<_Float16>(uint16_t(std::bit_cast<uint16_t>(h) - 1u));
    return float(h);
}
float roundToUnorm16(float v) { return std::round(std::clamp(v, 0.0f, 1.0f) * 65535.0f) / 65535.0f; }

glm::vec3 roundToUnorm10(glm::vec3 v) { return glm::round(glm::clamp(v, 0.0f, 1.0f) * 1023.0f) / 1023.0f; }

glm::vec3 roundToHalf(glm::vec3 v, bool towardZero) {
    return {roundToHalf(v.x, towardZero), roundToHalf(v.y, towardZero), roundToHalf(v.z, towardZero)};
}

PixelSums sumsInHalfTargets(FragmentList fragments, bool blendTruncates, float alphaCutoff, bool narrowLayers) {
    fragments = preparedFragments(std::move(fragments), alphaCutoff);
    PixelSums s;
    const auto layerColor = [&](glm::vec3 c) { return narrowLayers ? roundToUnorm10(c) : roundToHalf(c); };
    if (!fragments.empty()) {
        s.c1 = layerColor(fragments[0].color);
        s.a1 = roundToHalf(fragments[0].alpha);
    }
    if (fragments.size() > 1) {
        s.c2 = layerColor(fragments[1].color);
        s.a2 = roundToHalf(fragments[1].alpha);
    }
    for (const Fragment& f : fragments) {
        s.sumAlpha = roundToHalf(s.sumAlpha + f.alpha, blendTruncates);
        s.sumAlphaColor = roundToHalf(s.sumAlphaColor + f.alpha * f.color, blendTruncates);
        s.sumColor = roundToHalf(s.sumColor + f.color, blendTruncates);
        s.transmittance = roundToUnorm16(s.transmittance * roundToUnorm16(1.0f - f.alpha));
    }
    s.count = static_cast<float>(fragments.size());
    return s;
}

namespace {

float twoLayerTransmittance(const PixelSums& s) { return (1.0f - s.a1) * (1.0f - s.a2); }

glm::vec3 exactTwoLayers(const PixelSums& s) { return s.a1 * s.c1 + (1.0f - s.a1) * s.a2 * s.c2; }

// S_aC - a1 C1 - a2 C2: the premultiplied tail sum.
glm::vec3 tailAlphaColor(const PixelSums& s) { return s.sumAlphaColor - s.a1 * s.c1 - s.a2 * s.c2; }

}  // namespace

std::array<float, kStarntInputs> starntFeatures(const PixelSums& s) {
    const float t2 = twoLayerTransmittance(s);
    const float tTail = t2 > kTransmittanceEpsilon ? std::clamp(s.transmittance / t2, 0.0f, 1.0f) : 0.0f;
    const float tailAlpha = s.sumAlpha - s.a1 - s.a2;
    glm::vec3 cTilde(0.0f);
    if (tailAlpha > kTailAlphaEpsilon) cTilde = glm::max(tailAlphaColor(s) / tailAlpha, glm::vec3(0.0f));
    return {tTail, s.count, cTilde.r, cTilde.g, cTilde.b};
}

std::array<float, kDfaoitInputs> dfaoitFeatures(const PixelSums& s) {
    const float tailCount = s.count - 2.0f;
    float alphaAvg = 0.0f;
    glm::vec3 colorAvg(0.0f);
    if (tailCount > 0.5f) {
        alphaAvg = std::max(s.sumAlpha - s.a1 - s.a2, 0.0f) / tailCount;
        colorAvg = glm::max(s.sumColor - s.c1 - s.c2, glm::vec3(0.0f)) / tailCount;
    }
    const glm::vec3 exact2 = exactTwoLayers(s);
    return {alphaAvg,           colorAvg.r,         colorAvg.g,         colorAvg.b, s.sumAlphaColor.r,
            s.sumAlphaColor.g,  s.sumAlphaColor.b,  exact2.r,           exact2.g,   exact2.b};
}

glm::vec3 starntTarget(const FragmentList& sorted) {
    glm::dvec3 color(0.0);
    double transmittance = 1.0;
    for (size_t i = 2; i < sorted.size(); ++i) {
        const double a = sorted[i].alpha;
        color += transmittance * a * glm::dvec3(sorted[i].color);
        transmittance *= 1.0 - a;
    }
    return glm::vec3(color);
}

glm::vec3 starntResidualTarget(const FragmentList& sorted, const PixelSums& sums) {
    const auto x = starntFeatures(sums);
    const float tailOpacity = 1.0f - x[0];
    if (tailOpacity < kResidualMinTailOpacity) return glm::vec3(0.0f);
    return starntTarget(sorted) / tailOpacity - glm::vec3(x[2], x[3], x[4]);
}

glm::vec3 dfaoitTarget(const FragmentList& sorted) {
    glm::dvec3 color(0.0);
    double transmittance = 1.0;
    for (const Fragment& f : sorted) {
        const double a = f.alpha;
        color += transmittance * a * glm::dvec3(f.color);
        transmittance *= 1.0 - a;
    }
    return glm::vec3(color);
}

namespace {

// The composite both tail models share: the two peeled layers exactly, the tail exactly for N <= 3
// (the third fragment follows from the sums), `deepTail` for N > 3, then the background.
template <typename DeepTail>
glm::vec3 compositeThreeLayersExact(const PixelSums& s, glm::vec3 background, DeepTail deepTail) {
    glm::vec3 tail(0.0f);
    if (s.count < 2.5f) {
        tail = glm::vec3(0.0f);
    } else if (s.count < 3.5f) {
        tail = glm::max(tailAlphaColor(s), glm::vec3(0.0f));
    } else {
        tail = deepTail(starntFeatures(s));
    }
    return exactTwoLayers(s) + twoLayerTransmittance(s) * tail + s.transmittance * background;
}

}  // namespace

glm::vec3 compositeStarnt(const Network& net, const PixelSums& s, glm::vec3 background) {
    return compositeThreeLayersExact(s, background, [&](const auto& x) { return net.forward(x.data()); });
}

glm::vec3 compositeStarntResidual(const Network& net, const PixelSums& s, glm::vec3 background) {
    return compositeThreeLayersExact(s, background, [&](const auto& x) {
        const glm::vec3 cTilde(x[2], x[3], x[4]);
        return (1.0f - x[0]) * glm::max(cTilde + net.forward(x.data()), glm::vec3(0.0f));
    });
}

glm::vec3 compositeHybrid(const PixelSums& s, glm::vec3 background) {
    // x = (t_tail, N, C_tilde): the alpha-weighted mean tail colour under the tail's opacity.
    return compositeThreeLayersExact(s, background,
                                     [](const auto& x) { return (1.0f - x[0]) * glm::vec3(x[2], x[3], x[4]); });
}

glm::vec3 compositeDfaoit(const Network& net, const PixelSums& s, glm::vec3 background) {
    glm::vec3 transparent(0.0f);
    if (s.count > 0.5f) {
        const auto x = dfaoitFeatures(s);
        transparent = net.forward(x.data());
    }
    return transparent + s.transmittance * background;
}

glm::vec3 compositeNetwork(const Network& net, const PixelSums& s, glm::vec3 background) {
    switch (net.kind) {
        case NetworkKind::StarNT: return compositeStarnt(net, s, background);
        case NetworkKind::StarNTResidual: return compositeStarntResidual(net, s, background);
        case NetworkKind::DFAOIT: return compositeDfaoit(net, s, background);
    }
    return background;
}

}  // namespace starnt::nn
