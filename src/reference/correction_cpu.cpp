#include "reference/correction_cpu.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>

#include "methods/neural/temporal/packed_nearest.h"
#include "methods/neural/temporal/reprojection_constants.h"
#include "methods/neural/temporal/reprojection_math.hpp"
#include "methods/hybrid_moments/tail_moments_constants.h"
#include "starnt/tools/nn.hpp"

namespace starnt::temporal {

namespace {

constexpr uint32_t kPackedMaxKey = (1u << STARNT_PACKED_KEY_BITS) - 1u;
constexpr uint32_t kPackedPayloadMask = (1u << STARNT_PACKED_PAYLOAD_BITS) - 1u;
constexpr uint32_t kPackedOne = 0x3F800000u;

uint32_t packedDepthKey(float z) {
    const uint32_t w = std::bit_cast<uint32_t>(std::clamp(1.0f - z, 0.0f, 1.0f));
    return std::min((kPackedOne - w) >> STARNT_PACKED_KEY_SHIFT, kPackedMaxKey - 1u);
}

uint32_t packedColour(float c) {
    const float r = std::sqrt(std::max(c, 0.0f));
    return uint32_t(std::floor(r / (1.0f + r) * float(STARNT_PACKED_STEPS) + 0.5f));
}

// The window depth a key stands for: the middle of its depth interval.
float depthOfKey(uint32_t key) {
    return 1.0f - std::bit_cast<float>(kPackedOne - (key << STARNT_PACKED_KEY_SHIFT) - (1u << (STARNT_PACKED_KEY_SHIFT - 1)));
}

float unpackedColour(uint32_t p) {
    const float x = float(p) / float(STARNT_PACKED_STEPS);
    const float r = x / (1.0f - x);
    return r * r;
}

float packedBits(uint32_t key, uint32_t payload) {
    return std::bit_cast<float>(0x40000000u | (key << STARNT_PACKED_PAYLOAD_BITS) | payload);
}

}  // namespace

glm::vec4 packNearest(float z, const glm::vec4& c) {
    const uint32_t key = packedDepthKey(z);
    const uint32_t alpha = uint32_t(std::floor(std::clamp(c.a, 0.0f, 1.0f) * float(STARNT_PACKED_STEPS) + 0.5f));
    return {packedBits(key, packedColour(c.r)), packedBits(key, packedColour(c.g)), packedBits(key, packedColour(c.b)),
            packedBits(key, alpha)};
}

static_assert(STARNT_PACKED_EMPTY_BITS == (0x40000000u | kPackedMaxKey << STARNT_PACKED_PAYLOAD_BITS | kPackedPayloadMask));
glm::vec4 packedEmpty() { return glm::vec4(std::bit_cast<float>(STARNT_PACKED_EMPTY_BITS)); }

glm::vec4 unpackNearest(const glm::vec4& packed, float& z) {
    const uint32_t alphaBits = std::bit_cast<uint32_t>(packed.a);
    const uint32_t key = (alphaBits >> STARNT_PACKED_PAYLOAD_BITS) & kPackedMaxKey;
    if (key == kPackedMaxKey) {
        z = 1.0f;
        return glm::vec4(0.0f);
    }
    z = depthOfKey(key);
    glm::vec4 out;
    for (int c = 0; c < 3; ++c) out[c] = unpackedColour(std::bit_cast<uint32_t>(packed[c]) & kPackedPayloadMask);
    out.a = float(alphaBits & kPackedPayloadMask) / float(STARNT_PACKED_STEPS);
    return out;
}

glm::vec4 blendNearest(const glm::vec4& a, const glm::vec4& b) { return glm::min(a, b); }

float keyedDepth(float z) { return depthOfKey(packedDepthKey(z)); }

namespace {
constexpr uint32_t kLayerMaxKey = (1u << STARNT_PACKED_LAYER_KEY_BITS) - 1u;
constexpr uint32_t kLayerLowBits = 32u - STARNT_PACKED_LAYER_KEY_BITS;
constexpr uint32_t kLayerAlphaLow = STARNT_PACKED_LAYER_ALPHA_BITS - kLayerLowBits;
constexpr uint32_t kLayerGShift = STARNT_PACKED_LAYER_R_BITS;
constexpr uint32_t kLayerBShift = kLayerGShift + STARNT_PACKED_LAYER_G_BITS;
constexpr uint32_t kLayerAShift = kLayerBShift + STARNT_PACKED_LAYER_B_BITS;
constexpr uint32_t kLayerCoarseKeys =
    (STARNT_PACKED_LAYER_EXACT_BITS - STARNT_PACKED_LAYER_NEAREST_BITS) >> STARNT_PACKED_LAYER_COARSE_SHIFT;
static_assert(STARNT_PACKED_LAYER_KEY_BITS + STARNT_PACKED_LAYER_ALPHA_BITS + STARNT_PACKED_LAYER_R_BITS +
                  STARNT_PACKED_LAYER_G_BITS + STARNT_PACKED_LAYER_B_BITS == 64);
static_assert(kLayerAShift + kLayerAlphaLow == 32 && STARNT_PACKED_LAYER_ALPHA_BITS >= kLayerLowBits);
static_assert(STARNT_PACKED_LAYER_NEAREST_BITS == std::bit_cast<uint32_t>(float(STARNT_PACKED_LAYER_NEAREST_DEPTH)));
static_assert(STARNT_PACKED_LAYER_EXACT_BITS == std::bit_cast<uint32_t>(float(STARNT_PACKED_LAYER_EXACT_DEPTH)));
static_assert(STARNT_PACKED_LAYER_EMPTY == 0xFFFFFFFFu);
// z = 1 has a fragment's key, below the empty layer's.
static_assert(0x3F800000u - STARNT_PACKED_LAYER_EXACT_BITS + kLayerCoarseKeys < kLayerMaxKey);

float layerSteps(uint32_t bits) { return float((1u << bits) - 1u); }

constexpr float kLayerLdrShare = float(STARNT_PACKED_LAYER_LDR_SHARE);
constexpr float kLayerHdrScale = (1.0f - kLayerLdrShare) / float(STARNT_PACKED_LAYER_HDR_LOG2_RANGE);

// packed_nearest.glsl's bitsLog2 and bitsExp2: log2 of r >= 1 from its float bits, linear between
// powers of two, and its inverse.
float bitsLog2(float r) { return float(std::bit_cast<uint32_t>(std::max(r, 1.0f)) - 0x3F800000u) * (1.0f / 8388608.0f); }
float bitsExp2(float y) { return std::bit_cast<float>(0x3F800000u + uint32_t(std::max(y, 0.0f) * 8388608.0f)); }

uint32_t layerColour(float c, uint32_t bits) {
    const float r = std::sqrt(std::clamp(c, 0.0f, std::exp2(2.0f * float(STARNT_PACKED_LAYER_HDR_LOG2_RANGE))));
    const float x = r <= 1.0f ? kLayerLdrShare * r : kLayerLdrShare + kLayerHdrScale * bitsLog2(r);
    return uint32_t(std::floor(x * layerSteps(bits) + 0.5f));
}

float unpackedLayerColour(uint32_t word, uint32_t shift, uint32_t bits) {
    const float x = float((word >> shift) & ((1u << bits) - 1u)) / layerSteps(bits);
    const float r = x <= kLayerLdrShare ? x / kLayerLdrShare : bitsExp2((x - kLayerLdrShare) / kLayerHdrScale);
    return r * r;
}

uint32_t layerKey(float z) {
    const uint32_t bits = std::bit_cast<uint32_t>(std::clamp(z, float(STARNT_PACKED_LAYER_NEAREST_DEPTH), 1.0f));
    return bits >= STARNT_PACKED_LAYER_EXACT_BITS ? bits - STARNT_PACKED_LAYER_EXACT_BITS + kLayerCoarseKeys
                                                   : (bits - STARNT_PACKED_LAYER_NEAREST_BITS) >> STARNT_PACKED_LAYER_COARSE_SHIFT;
}

float depthOfLayerKey(uint32_t key) {
    return std::bit_cast<float>(key >= kLayerCoarseKeys ? key - kLayerCoarseKeys + STARNT_PACKED_LAYER_EXACT_BITS
                                                        : (key << STARNT_PACKED_LAYER_COARSE_SHIFT) +
                                                              STARNT_PACKED_LAYER_NEAREST_BITS +
                                                              ((1u << STARNT_PACKED_LAYER_COARSE_SHIFT) >> 1));
}
}  // namespace

namespace {
glm::uvec2 packLayerAtKey(uint32_t key, const glm::vec4& c) {
    const uint32_t alpha = uint32_t(std::floor(std::clamp(c.a, 0.0f, 1.0f) * layerSteps(STARNT_PACKED_LAYER_ALPHA_BITS) + 0.5f));
    return {(key << kLayerLowBits) | (alpha >> kLayerAlphaLow),
            (alpha << kLayerAShift) | layerColour(c.r, STARNT_PACKED_LAYER_R_BITS) |
                (layerColour(c.g, STARNT_PACKED_LAYER_G_BITS) << kLayerGShift) |
                (layerColour(c.b, STARNT_PACKED_LAYER_B_BITS) << kLayerBShift)};
}
}  // namespace

glm::uvec2 packLayer(float z, const glm::vec4& c) { return packLayerAtKey(layerKey(z), c); }

glm::uvec4 packedLayersEmpty() { return {STARNT_PACKED_LAYER_EMPTY, 0u, STARNT_PACKED_LAYER_EMPTY, 0u}; }

glm::uvec4 insertLayer(const glm::uvec4& layers, const glm::uvec2& f) {
    const uint32_t key = f.x >> kLayerLowBits, first = layers.x >> kLayerLowBits;
    if (key < first) return {f.x, f.y, layers.x, layers.y};
    if (key > first && key < (layers.z >> kLayerLowBits)) return {layers.x, layers.y, f.x, f.y};
    return layers;
}

void insertThreeLayers(glm::uvec4& layers, glm::uvec2& third, float z, const glm::vec4& c) {
    const uint32_t key = layerKey(z), first = layers.x >> kLayerLowBits, second = layers.z >> kLayerLowBits;
    const uint32_t last = third.x >> kLayerLowBits;
    const bool tie = key == first || key == second || key == last;
    // The GLSL's one merge, whatever the fragment meets (the kept layer over it, at its key).
    float keptDepth = 1.0f;  // (the key is the fragment's: a tie shares it)
    const glm::vec4 kept = unpackLayer(key == first    ? glm::uvec2(layers.x, layers.y)
                                       : key == second ? glm::uvec2(layers.z, layers.w)
                                                       : third,
                                       keptDepth);
    const float hdrMax = std::exp2(2.0f * float(STARNT_PACKED_LAYER_HDR_LOG2_RANGE));
    const glm::vec4 behind(glm::clamp(glm::vec3(c), glm::vec3(0.0f), glm::vec3(hdrMax)), std::clamp(c.a, 0.0f, 1.0f));
    const float alpha = kept.a + (1.0f - kept.a) * behind.a;
    const glm::vec3 merged = alpha > 0.0f ? (kept.a * glm::vec3(kept) + (1.0f - kept.a) * behind.a * glm::vec3(behind)) / alpha
                                          : glm::vec3(kept);
    const glm::uvec2 f = packLayerAtKey(key, tie ? glm::vec4(merged, alpha) : c);
    if (tie) {
        if (key == first) layers = {f.x, f.y, layers.z, layers.w};
        else if (key == second) layers = {layers.x, layers.y, f.x, f.y};
        else third = f;
    } else if (key < first) {
        third = {layers.z, layers.w};
        layers = {f.x, f.y, layers.x, layers.y};
    } else if (key < second) {
        third = {layers.z, layers.w};
        layers = {layers.x, layers.y, f.x, f.y};
    } else if (key < last) {
        third = f;
    }
}

glm::uvec2 packedLayerEmpty() { return {STARNT_PACKED_LAYER_EMPTY, 0u}; }

glm::vec4 unpackLayer(const glm::uvec2& layer, float& z) {
    const uint32_t key = layer.x >> kLayerLowBits;
    if (key == kLayerMaxKey) {
        z = 1.0f;
        return glm::vec4(0.0f);
    }
    z = depthOfLayerKey(key);
    const uint32_t alpha = ((layer.x & ((1u << kLayerLowBits) - 1u)) << kLayerAlphaLow) | (layer.y >> kLayerAShift);
    return {unpackedLayerColour(layer.y, 0, STARNT_PACKED_LAYER_R_BITS),
            unpackedLayerColour(layer.y, kLayerGShift, STARNT_PACKED_LAYER_G_BITS),
            unpackedLayerColour(layer.y, kLayerBShift, STARNT_PACKED_LAYER_B_BITS),
            float(alpha) / layerSteps(STARNT_PACKED_LAYER_ALPHA_BITS)};
}

float depthBehindReference(float z, float reference) {
    const float scale = float(STARNT_TAIL_MOMENT_DEPTH_SCALE) * std::max(1.0f - reference, float(STARNT_ORDERED_MIN_REFERENCE_GAP));
    const float d = keyedDepth(z) - reference;
    return d >= 0.0f ? std::log(1.0f + d / scale) : -std::log(1.0f - d / scale);
}

std::vector<float> referenceDepthOnCpu(const std::vector<float>& depth, int width, int height) {
    constexpr int tile = STARNT_ORDERED_REFERENCE_TILE;
    const int tilesX = (width + tile - 1) / tile, tilesY = (height + tile - 1) / tile;
    std::vector<float> tiles(size_t(tilesX) * size_t(tilesY), 1.0f), out(tiles.size(), 1.0f);
    for (int ty = 0; ty < tilesY; ++ty)
        for (int tx = 0; tx < tilesX; ++tx)
            for (int y = 0; y < tile; y += STARNT_ORDERED_REFERENCE_STRIDE)
                for (int x = 0; x < tile; x += STARNT_ORDERED_REFERENCE_STRIDE) {
                    const int sx = std::min(tx * tile + x, width - 1), sy = std::min(ty * tile + y, height - 1);
                    float& t = tiles[size_t(ty) * size_t(tilesX) + size_t(tx)];
                    t = std::min(t, depth[size_t(sy) * size_t(width) + size_t(sx)]);
                }
    for (int y = 0; y < tilesY; ++y)
        for (int x = 0; x < tilesX; ++x)
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    const int sx = std::clamp(x + dx, 0, tilesX - 1), sy = std::clamp(y + dy, 0, tilesY - 1);
                    float& o = out[size_t(y) * size_t(tilesX) + size_t(x)];
                    o = std::min(o, tiles[size_t(sy) * size_t(tilesX) + size_t(sx)]);
                }
    return out;
}

float referenceAt(const std::vector<float>& reference, int width, int x, int y) {
    constexpr int tile = STARNT_ORDERED_REFERENCE_TILE;
    const int tilesX = (width + tile - 1) / tile;
    return reference[size_t(y / tile) * size_t(tilesX) + size_t(x / tile)];
}

OrderedBehind behindMomentsOf(const std::vector<Fragment>& fragments, float reference, float pivot) {
    glm::dvec4 first(0.0);
    double second = 0.0;
    for (const Fragment& f : fragments) {
        const float u = depthBehindReference(f.depth, reference) - pivot;
        const glm::vec4 term = glm::vec4(f.color * f.alpha, f.alpha) * u;  // the shader's float operations
        first += glm::dvec4(term);
        second += double(term.a * u);
    }
    return {glm::vec4(first), float(second), reference, pivot};
}

glm::vec3 orderedClosedFormBehindFromMoments(const glm::vec4& nearest, const glm::vec4& sums, float transmittance,
                                             const glm::vec4& moment1, float moment2, const glm::vec3& background) {
    const float behindT = glm::clamp(transmittance / (1.0f - nearest.a), 0.0f, 1.0f);
    const float behindAlpha = sums.a - nearest.a;
    if (!(behindAlpha > float(STARNT_TEMPORAL_MIN_BEHIND_ALPHA))) return background;
    nn::TailMoments m;
    m.alphaColorU = glm::vec3(moment1);
    m.alphaU = moment1.a;
    m.alphaU2 = moment2;
    const glm::vec3 alphaColor = glm::vec3(sums) - glm::vec3(nearest) * nearest.a;
    const float mean = moment1.a / behindAlpha;
    const bool spread =
        moment2 / behindAlpha - mean * mean > float(STARNT_ORDERED_ALPHA_ROUNDING) / behindAlpha * mean * mean;
    const glm::vec3 color = spread ? nn::momentWeightedColor(alphaColor, behindAlpha, m, behindT, false)
                                   : glm::max(alphaColor / behindAlpha, glm::vec3(0.0f));
    return (1.0f - behindT) * color + behindT * background;
}

namespace {
// ordered_behind.glsl's dropRoundedMoments.
void dropRoundedMoments(glm::vec4& moment1Recentred, float& moment2Recentred, float moment2) {
    if (!(moment2Recentred > float(STARNT_ORDERED_RECENTRED_PRECISION) * moment2)) {
        moment1Recentred = glm::vec4(0.0f);
        moment2Recentred = 0.0f;
    }
}
}  // namespace

glm::vec3 orderedClosedFormBehind(const glm::vec4& nearest, float depth, const glm::vec4& sums, float transmittance,
                                  const OrderedBehind& ordered, const glm::vec3& background) {
    const float u = depthBehindReference(depth, ordered.reference) - ordered.pivot;
    glm::vec4 first = ordered.moment1 - u * sums;
    float second2 = ordered.moment2 - u * (ordered.moment1.a + first.a);
    dropRoundedMoments(first, second2, ordered.moment2);
    return orderedClosedFormBehindFromMoments(nearest, sums, transmittance, first, second2, background);
}

glm::vec3 orderedClosedFormBehindSecondFromMoments(const glm::vec4& nearest, const glm::vec4& second, const glm::vec4& sums,
                                                   float transmittance, const glm::vec4& moment1, float moment2,
                                                   const glm::vec3& background) {
    if (!(second.a > 0.0f)) return orderedClosedFormBehindFromMoments(nearest, sums, transmittance, moment1, moment2, background);
    const float open2 = 1.0f - second.a;
    if (!(open2 > float(STARNT_TEMPORAL_MIN_TRANSMITTANCE))) return glm::vec3(second);
    const glm::vec4 nearestTerms(glm::vec3(nearest) * nearest.a, nearest.a);
    const glm::vec3 behind = orderedClosedFormBehindFromMoments(second, sums - nearestTerms, transmittance / (1.0f - nearest.a),
                                                                moment1, moment2, background);
    return second.a * glm::vec3(second) + open2 * behind;
}

glm::vec3 orderedClosedFormBehindTwoLayers(const glm::vec4& nearest, float depth, const glm::vec4& second, float secondDepth,
                                           const glm::vec4& sums, float transmittance, const OrderedBehind& ordered,
                                           const glm::vec3& background) {
    if (!(second.a > 0.0f)) return orderedClosedFormBehind(nearest, depth, sums, transmittance, ordered, background);
    const float u2 = depthBehindReference(secondDepth, ordered.reference) - ordered.pivot;
    const float d = depthBehindReference(depth, ordered.reference) - ordered.pivot - u2;
    const glm::vec4 nearestTerms(glm::vec3(nearest) * nearest.a, nearest.a);
    const glm::vec4 first = ordered.moment1 - u2 * sums;
    float second2 = ordered.moment2 - u2 * (ordered.moment1.a + first.a) - nearestTerms.a * d * d;
    glm::vec4 behindMoment1 = first - nearestTerms * d;
    dropRoundedMoments(behindMoment1, second2, ordered.moment2);
    return orderedClosedFormBehindSecondFromMoments(nearest, second, sums, transmittance, behindMoment1, second2, background);
}

glm::vec3 orderedClosedFormBehindThreeLayers(const glm::vec4& nearest, float depth, const glm::vec4& second, float secondDepth,
                                             const glm::vec4& third, float thirdDepth, const glm::vec4& sums, float transmittance,
                                             const OrderedBehind& ordered, const glm::vec3& background) {
    if (!(third.a > 0.0f)) {
        return orderedClosedFormBehindTwoLayers(nearest, depth, second, secondDepth, sums, transmittance, ordered, background);
    }
    const float open2 = 1.0f - second.a;
    if (!(open2 > float(STARNT_TEMPORAL_MIN_TRANSMITTANCE))) return glm::vec3(second);
    const float u3 = depthBehindReference(thirdDepth, ordered.reference) - ordered.pivot;
    const float d1 = depthBehindReference(depth, ordered.reference) - ordered.pivot - u3;
    const float d2 = depthBehindReference(secondDepth, ordered.reference) - ordered.pivot - u3;
    const glm::vec4 nearestTerms(glm::vec3(nearest) * nearest.a, nearest.a);
    const glm::vec4 secondTerms(glm::vec3(second) * second.a, second.a);
    const glm::vec4 first = ordered.moment1 - u3 * sums;
    float second2 = ordered.moment2 - u3 * (ordered.moment1.a + first.a) - nearestTerms.a * d1 * d1 - secondTerms.a * d2 * d2;
    glm::vec4 behindMoment1 = first - nearestTerms * d1 - secondTerms * d2;
    dropRoundedMoments(behindMoment1, second2, ordered.moment2);
    const glm::vec3 behindSecond = orderedClosedFormBehindSecondFromMoments(
        second, third, sums - nearestTerms, transmittance / (1.0f - nearest.a), behindMoment1, second2, background);
    return second.a * glm::vec3(second) + open2 * behindSecond;
}

glm::vec3 closedFormBehind(const glm::vec4& nearest, const glm::vec4& sums, float transmittance, const glm::vec3& background) {
    const float behindT = glm::clamp(transmittance / (1.0f - nearest.a), 0.0f, 1.0f);
    const float behindAlpha = sums.a - nearest.a;
    const glm::vec3 mean = behindAlpha > float(STARNT_TEMPORAL_MIN_BEHIND_ALPHA)
                               ? glm::max(glm::vec3(sums) - nearest.a * glm::vec3(nearest), glm::vec3(0.0f)) / behindAlpha
                               : background;
    return (1.0f - behindT) * mean + behindT * background;
}

std::vector<glm::vec4> correctionOnCpu(const CorrectionSource& real, const glm::mat4& viewProj, const glm::vec3& background) {
    const glm::vec4 sourceScale = makeReprojection(viewProj, viewProj).sourceScale;
    std::vector<glm::vec4> out(size_t(real.width) * size_t(real.height));
    for (int y = 0; y < real.height; ++y) {
        for (int x = 0; x < real.width; ++x) {
            const size_t t = size_t(y) * size_t(real.width) + size_t(x);
            const glm::vec4 n = real.nearest[t];
            const float open = 1.0f - n.a;
            if (!(open > float(STARNT_TEMPORAL_MIN_TRANSMITTANCE))) {
                out[t] = glm::vec4(0.0f, 0.0f, 0.0f, -1.0f);
                continue;
            }
            const glm::vec2 ndc = (glm::vec2(float(x), float(y)) + 0.5f) / glm::vec2(float(real.width), float(real.height)) * 2.0f - 1.0f;
            const float inverseViewDepth = glm::dot(sourceScale, glm::vec4(ndc, real.depth[t] * 2.0f - 1.0f, 1.0f));
            const glm::vec3 network = (glm::vec3(real.composite[t]) - n.a * glm::vec3(n)) / open;
            out[t] = glm::vec4(network - closedFormBehind(n, real.sums[t], real.transmittance[t], background), inverseViewDepth);
        }
    }
    return out;
}

glm::vec3 correctedPixel(int x, int y, int width, int height, const glm::vec4& nearest, float depth, const glm::vec4& sums,
                         float transmittance, const std::vector<glm::vec4>& correction, const glm::mat4& oldViewProj,
                         const glm::mat4& newViewProj, const glm::vec3& background, const OrderedBehind* ordered) {
    if (!(nearest.a > 0.0f)) return background;
    const float open = 1.0f - nearest.a;
    glm::vec3 behind = background;
    if (open > float(STARNT_TEMPORAL_MIN_TRANSMITTANCE)) {
        behind = ordered ? orderedClosedFormBehind(nearest, depth, sums, transmittance, *ordered, background)
                         : closedFormBehind(nearest, sums, transmittance, background);
        const CorrectionMatrices m = makeCorrectionMatrices(oldViewProj, newViewProj);
        const glm::vec2 c = (glm::vec2(float(x), float(y)) + 0.5f) / glm::vec2(float(width), float(height)) * 2.0f - 1.0f;
        const glm::vec4 old = m.newToOld * glm::vec4(c, depth * 2.0f - 1.0f, 1.0f);
        if (!correction.empty() && old.w > 0.0f) {
            const glm::vec3 ndc = glm::vec3(old) / old.w;
            const float reference = glm::dot(m.sourceScale, glm::vec4(ndc, 1.0f));
            const glm::vec2 f = (glm::vec2(ndc) * 0.5f + 0.5f) * glm::vec2(float(width), float(height)) - 0.5f;
            if (reference > 0.0f && f.x > -1.0f && f.y > -1.0f && f.x < float(width) && f.y < float(height)) {
                const glm::ivec2 base(int(std::floor(f.x)), int(std::floor(f.y)));
                const glm::vec2 w = f - glm::vec2(base);
                glm::vec3 sum(0.0f);
                float weight = 0.0f;
                for (int k = 0; k < 4; ++k) {
                    const glm::ivec2 t = base + glm::ivec2(k & 1, k >> 1);
                    if (t.x < 0 || t.y < 0 || t.x >= width || t.y >= height) continue;
                    const glm::vec4 d = correction[size_t(t.y) * size_t(width) + size_t(t.x)];
                    if (!(d.a > 0.0f) || std::abs(d.a / reference - 1.0f) > float(STARNT_TEMPORAL_SAME_SURFACE)) continue;
                    const float wk = ((k & 1) ? w.x : 1.0f - w.x) * ((k >> 1) ? w.y : 1.0f - w.y);
                    sum += wk * glm::vec3(d);
                    weight += wk;
                }
                if (weight > 0.0f) behind += sum / weight;
            }
        }
    }
    return nearest.a * glm::vec3(nearest) + open * glm::max(behind, glm::vec3(0.0f));
}

}  // namespace starnt::temporal
