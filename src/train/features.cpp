// CPU reference of the per-pixel sums (passes 1-3), the network features, the training targets
// and the final composites. The guards are documented in include/starnt/tools/nn.hpp.
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include "starnt/error.hpp"
#include "starnt/tools/nn.hpp"
#include "methods/hybrid_moments/tail_moments_constants.h"
#include "methods/neural/network_hdr.h"

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

glm::vec3 narrowLayerColor(glm::vec3 c) {
    const float peak = std::max({c.r, c.g, c.b});
    const float edge = 1.0f + 0.5f / 1023.0f;  // half a step above each scale, as half_targets.glsl
    const float scale = peak > edge ? (peak > 16.0f * edge ? (peak > 256.0f * edge ? 4096.0f : 256.0f) : 16.0f) : 1.0f;
    return roundToUnorm10(c / scale) * scale;
}

glm::vec3 roundToHalf(glm::vec3 v, bool towardZero) {
    return {roundToHalf(v.x, towardZero), roundToHalf(v.y, towardZero), roundToHalf(v.z, towardZero)};
}

PixelSums sumsInHalfTargets(FragmentList fragments, bool blendTruncates, float alphaCutoff, bool narrowLayers) {
    fragments = preparedFragments(std::move(fragments), alphaCutoff);
    PixelSums s;
    const auto layerColor = [&](glm::vec3 c) { return narrowLayers ? narrowLayerColor(c) : roundToHalf(c); };
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
            s.sumAlphaColor.g,  s.sumAlphaColor.b,  exact2.r,           exact2.g,   exact2.b, 1.0f - twoLayerTransmittance(s), s.count};
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
// The tail's fragment count is N less the layers held (neural_inputs.glsl's tailCount): N - 2 where
// depths differ, more where layers are coplanar and pass 2 found none; then, with two or more
// left, the order-free closed form instead of `deepTail`.
template <typename DeepTail>
glm::vec3 compositeThreeLayersExact(const PixelSums& s, glm::vec3 background, DeepTail deepTail) {
    glm::vec3 tail(0.0f);
    const float n = s.count - (s.a1 > 0.0f ? 1.0f : 0.0f) - (s.a2 > 0.0f ? 1.0f : 0.0f);
    if (n < 0.5f) {
        tail = glm::vec3(0.0f);
    } else if (n < 1.5f) {
        tail = glm::max(tailAlphaColor(s), glm::vec3(0.0f));
    } else if (s.a2 > 0.0f) {
        tail = deepTail(starntFeatures(s));
    } else {
        const std::array<float, kStarntInputs> x = starntFeatures(s);  // t_tail, N, C_tilde
        tail = (1.0f - x[0]) * glm::vec3(x[2], x[3], x[4]);
    }
    return exactTwoLayers(s) + twoLayerTransmittance(s) * tail + s.transmittance * background;
}

}  // namespace

namespace {

// CPU reference of methods/neural/network_hdr.glsl (docs/DESIGN.md, "HDR"; the same float
// operations): the colour inputs from `firstColour` on divided by the pixel's scale k
// (network_hdr.h) of the largest of them outside [skipBegin, skipEnd), the output multiplied by k,
// where that largest exceeds 1 + 2^-8 (LDR pixels, 16-bit rounding included, keep their bits).
template <size_t N>
glm::vec3 forwardInColourScale(const Network& net, std::array<float, N> x, size_t firstColour, size_t skipBegin = N,
                               size_t skipEnd = N, size_t colourEnd = N) {
    float peak = 1.0f;
    for (size_t i = firstColour; i < colourEnd; ++i) {
        if (i < skipBegin || i >= skipEnd) peak = std::max(peak, x[i]);
    }
    if (!(peak > float(STARNT_NN_HDR_THRESHOLD))) return net.forward(x.data());
    const float target = float(STARNT_NN_HDR_TARGET);
    const float k = peak / (target + (1.0f - target) / peak);
    for (size_t i = firstColour; i < colourEnd; ++i) x[i] /= k;
    return k * net.forward(x.data());
}

}  // namespace

glm::vec3 compositeStarnt(const Network& net, const PixelSums& s, glm::vec3 background) {
    return compositeThreeLayersExact(s, background, [&](const auto& x) { return forwardInColourScale(net, x, 2); });
}

glm::vec3 compositeStarntResidual(const Network& net, const PixelSums& s, glm::vec3 background) {
    return compositeThreeLayersExact(s, background, [&](const auto& x) {
        const glm::vec3 cTilde(x[2], x[3], x[4]);
        return (1.0f - x[0]) * glm::max(cTilde + forwardInColourScale(net, x, 2), glm::vec3(0.0f));
    });
}

glm::vec3 compositeHybrid(const PixelSums& s, glm::vec3 background) {
    // x = (t_tail, N, C_tilde): the alpha-weighted mean tail colour under the tail's opacity.
    return compositeThreeLayersExact(s, background,
                                     [](const auto& x) { return (1.0f - x[0]) * glm::vec3(x[2], x[3], x[4]); });
}

TailMoments tailMomentsFromFragments(FragmentList fragments, float alphaCutoff) {
    fragments = preparedFragments(std::move(fragments), alphaCutoff);
    TailMoments m;
    if (fragments.size() < 3) return m;
    const float second = fragments[1].depth;
    glm::dvec4 m1(0.0), m2(0.0);
    for (size_t i = 2; i < fragments.size(); ++i) {
        const Fragment& f = fragments[i];
        if (!(f.depth > second)) continue;  // u = 0 adds nothing
        // The float operations pass 3 does (tail_moments_constants.h).
        const float behind = (f.depth - second) / (float(STARNT_TAIL_MOMENT_DEPTH_SCALE) * (1.0f - second));
        const double u = double(std::log(1.0f + behind));
        const glm::dvec4 term = glm::dvec4(glm::dvec3(f.color) * double(f.alpha), double(f.alpha)) * u;
        m1 += term;
        m2 += term * u;
    }
    m.alphaColorU = glm::vec3(m1);
    m.alphaU = float(m1.w);
    m.alphaColorU2 = glm::vec3(m2);
    m.alphaU2 = float(m2.w);
    return m;
}

namespace {
// I_k = integral over [0, 1] of x^k exp(-tau x), k = 0, 1, 2 (tail_moments.glsl, the same float
// operations).
void exponentialMoments(float tau, float integrals[3]) {
    if (tau < float(STARNT_TAIL_MOMENT_SERIES_BELOW)) {
        // sum over n of (-tau)^n / (n! (n + k + 1)); 12 terms leave < 2e-10 at tau = 1.
        for (int k = 0; k < 3; ++k) integrals[k] = 0.0f;
        float term = 1.0f;
        for (int n = 0; n < 12; ++n) {
            for (int k = 0; k < 3; ++k) integrals[k] += term / float(n + k + 1);
            term *= -tau / float(n + 1);
        }
        return;
    }
    const float e = std::exp(-tau);
    integrals[0] = (1.0f - e) / tau;
    integrals[1] = (1.0f - e * (1.0f + tau)) / (tau * tau);
    integrals[2] = (2.0f - e * (tau * tau + 2.0f * tau + 2.0f)) / (tau * tau * tau);
}
}  // namespace

glm::vec3 momentWeightedColor(const glm::vec3& alphaColor, float alpha, const TailMoments& m, float tTail, bool quadraticAllowed) {
    const glm::vec3 plain = glm::max(alphaColor / alpha, glm::vec3(0.0f));
    const float mean = m.alphaU / alpha;
    const float spread = std::sqrt(std::max(m.alphaU2 / alpha - mean * mean, 0.0f));
    if (!(spread > float(STARNT_TAIL_MOMENT_PLAIN_BELOW) * mean)) return plain;
    const bool quadratic = quadraticAllowed && spread > float(STARNT_TAIL_MOMENT_LINEAR_BELOW) * mean;
    const float maxDepth = float(STARNT_TAIL_MOMENT_MAX_OPTICAL_DEPTH);
    const float tau = tTail > 0.0f ? std::min(-std::log(tTail), maxDepth) : maxDepth;
    float integral[3];
    exponentialMoments(tau, integral);
    // Shifted Legendre coefficients of exp(-tau x), then the same polynomial in powers of x.
    const float c0 = integral[0], c1 = 3.0f * (2.0f * integral[1] - integral[0]);
    float c2 = quadratic ? 5.0f * (6.0f * integral[2] - 6.0f * integral[1] + integral[0]) : 0.0f;
    // A convex quadratic whose minimum lies before STARNT_TAIL_MOMENT_MIN_VERTEX rises again at the
    // back: the linear weight then (its minimum -b1 / 2 b2 < X, i.e. b1 + 2 X b2 > 0).
    if (c2 > 0.0f && (2.0f * c1 - 6.0f * c2) + 2.0f * float(STARNT_TAIL_MOMENT_MIN_VERTEX) * (6.0f * c2) > 0.0f) c2 = 0.0f;
    const float b0 = c0 - c1 + c2, b1 = 2.0f * c1 - 6.0f * c2, b2 = 6.0f * c2;
    // x = (u - lo) / width over the uniform interval with this mean and spread.
    const float halfWidth = std::sqrt(3.0f) * spread, lo = mean - halfWidth, width = 2.0f * halfWidth;
    const glm::vec3 firstFromLo = m.alphaColorU - lo * alphaColor;
    const glm::vec3 x1 = firstFromLo / width;
    const glm::vec3 x2 = quadratic ? ((m.alphaColorU2 - lo * m.alphaColorU) - lo * firstFromLo) / (width * width) : glm::vec3(0.0f);
    // sum a w(x) = alpha c0 exactly (the x-moments of the alphas are 1/2 and 1/3 by construction).
    return glm::max((b0 * alphaColor + b1 * x1 + b2 * x2) / (c0 * alpha), glm::vec3(0.0f));
}

glm::vec3 momentWeightedTailColor(const PixelSums& s, const TailMoments& m) {
    const float alpha = s.sumAlpha - s.a1 - s.a2;
    if (!(alpha > kTailAlphaEpsilon)) return glm::vec3(0.0f);
    const float t2 = twoLayerTransmittance(s);
    const float tTail = t2 > kTransmittanceEpsilon ? std::clamp(s.transmittance / t2, 0.0f, 1.0f) : 0.0f;
    return momentWeightedColor(tailAlphaColor(s), alpha, m, tTail);
}

glm::vec3 compositeHybridMoments(const PixelSums& s, const TailMoments& m, glm::vec3 background) {
    return compositeThreeLayersExact(s, background,
                                     [&](const auto& x) { return (1.0f - x[0]) * momentWeightedTailColor(s, m); });
}

std::array<float, kStarntDepthInputs> starntDepthFeatures(const PixelSums& s, const TailMoments& m) {
    const auto x = starntFeatures(s);
    const glm::vec3 moment = momentWeightedTailColor(s, m);
    return {x[0], x[1], x[2], x[3], x[4], moment.r, moment.g, moment.b};
}

glm::vec3 starntDepthTarget(const FragmentList& sorted, const PixelSums& sums, const TailMoments& m) {
    const auto x = starntDepthFeatures(sums, m);
    const float tailOpacity = 1.0f - x[0];
    if (tailOpacity < kResidualMinTailOpacity) return glm::vec3(0.0f);
    return starntTarget(sorted) / tailOpacity - glm::vec3(x[5], x[6], x[7]);
}

glm::vec3 compositeStarntDepth(const Network& net, const PixelSums& s, const TailMoments& m, glm::vec3 background) {
    return compositeThreeLayersExact(s, background, [&](const auto& x) {
        const auto d = starntDepthFeatures(s, m);
        return (1.0f - x[0]) * glm::max(glm::vec3(d[5], d[6], d[7]) + forwardInColourScale(net, d, 2), glm::vec3(0.0f));
    });
}

glm::vec3 compositeDfaoit(const Network& net, const PixelSums& s, glm::vec3 background) {
    glm::vec3 transparent(0.0f);
    if (s.count > 0.5f) {
        // Colour inputs from x[1]; sum a C (x[4..6]) scaled but not setting the scale.
        transparent = forwardInColourScale(net, dfaoitFeatures(s), 1, 4, 7, 10);
    }
    return transparent + s.transmittance * background;
}

glm::vec3 compositeNetwork(const Network& net, const PixelSums& s, glm::vec3 background, const TailMoments* moments) {
    switch (net.kind) {
        case NetworkKind::StarNTDepth:
            if (!moments) throw Error("a starnt-d network needs the tail moments");
            return compositeStarntDepth(net, s, *moments, background);
        case NetworkKind::StarNT: return compositeStarnt(net, s, background);
        case NetworkKind::StarNTResidual: return compositeStarntResidual(net, s, background);
        case NetworkKind::DFAOIT: return compositeDfaoit(net, s, background);
    }
    return background;
}

}  // namespace starnt::nn
