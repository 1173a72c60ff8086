// Per-pixel sums, features, targets and composites of the neural OIT methods (CPU reference).
#include <gtest/gtest.h>

#include <cmath>

#include "starnt/error.hpp"
#include "starnt/tools/nn.hpp"
#include "starnt/tools/train.hpp"

using namespace starnt;
using namespace starnt::nn;

namespace {

Fragment frag(glm::vec3 c, float a, float z, uint32_t order = 0) { return Fragment{c, a, z, order}; }

void expectVec(glm::vec3 actual, glm::vec3 expected, float tol, const char* what) {
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(actual[k], expected[k], tol) << what << " channel " << k;
}

}  // namespace

TEST(NnFeatures, EmptyPixel) {
    const PixelSums s = sumsFromFragments({});
    EXPECT_EQ(s.count, 0.0f);
    EXPECT_EQ(s.a1, 0.0f);
    EXPECT_EQ(s.a2, 0.0f);
    EXPECT_EQ(s.sumAlpha, 0.0f);
    EXPECT_EQ(s.transmittance, 1.0f);
    const auto f = starntFeatures(s);
    EXPECT_EQ(f[0], 1.0f);  // t_tail = T_all / T2 = 1 / 1
    EXPECT_EQ(f[1], 0.0f);
    EXPECT_EQ(f[2], 0.0f);
    EXPECT_EQ(f[3], 0.0f);
    EXPECT_EQ(f[4], 0.0f);
    for (float v : dfaoitFeatures(s)) EXPECT_EQ(v, 0.0f);
}

TEST(NnFeatures, OneFragment) {
    const PixelSums s = sumsFromFragments({frag({1.0f, 0.5f, 0.25f}, 0.5f, 0.3f)});
    EXPECT_EQ(s.count, 1.0f);
    EXPECT_EQ(s.a1, 0.5f);
    EXPECT_EQ(s.c1, glm::vec3(1.0f, 0.5f, 0.25f));
    EXPECT_EQ(s.a2, 0.0f);
    EXPECT_EQ(s.c2, glm::vec3(0.0f));
    EXPECT_FLOAT_EQ(s.sumAlpha, 0.5f);
    expectVec(s.sumAlphaColor, {0.5f, 0.25f, 0.125f}, 1e-7f, "S_aC");
    expectVec(s.sumColor, {1.0f, 0.5f, 0.25f}, 1e-7f, "S_C");
    EXPECT_FLOAT_EQ(s.transmittance, 0.5f);
    const auto f = starntFeatures(s);
    EXPECT_FLOAT_EQ(f[0], 1.0f);
    EXPECT_EQ(f[1], 1.0f);
    EXPECT_EQ(f[2], 0.0f);  // no tail alpha: guarded to 0
    const auto d = dfaoitFeatures(s);
    EXPECT_EQ(d[0], 0.0f);  // N <= 2: no tail averages
    EXPECT_EQ(d[1], 0.0f);
    EXPECT_FLOAT_EQ(d[4], 0.5f);   // S_aC.r
    EXPECT_FLOAT_EQ(d[7], 0.5f);   // C_exact2 = a1 C1
    EXPECT_FLOAT_EQ(d[8], 0.25f);
    EXPECT_FLOAT_EQ(d[9], 0.125f);
}

TEST(NnFeatures, TwoFragmentsAndCutoffDropsLowAlpha) {
    // Submitted back to front, plus an alpha 0 and an alpha 0.02 fragment nearest to the camera.
    FragmentList list = {frag({0, 0, 1}, 0.25f, 0.8f, 0), frag({1, 0, 0}, 0.5f, 0.2f, 1),
                         frag({0, 1, 0}, 0.0f, 0.1f, 2), frag({1, 1, 1}, 0.02f, 0.05f, 3)};
    const PixelSums s = sumsFromFragments(list);
    EXPECT_EQ(s.count, 2.0f);
    EXPECT_EQ(s.c1, glm::vec3(1, 0, 0));
    EXPECT_EQ(s.a1, 0.5f);
    EXPECT_EQ(s.c2, glm::vec3(0, 0, 1));
    EXPECT_EQ(s.a2, 0.25f);
    EXPECT_FLOAT_EQ(s.transmittance, 0.375f);
    EXPECT_FLOAT_EQ(s.sumAlpha, 0.75f);
    // A zero cut-off keeps the alpha 0.02 fragment (alpha 0 never contributes but counts).
    EXPECT_EQ(sumsFromFragments(list, 0.0f).count, 4.0f);
    EXPECT_EQ(sumsFromFragments(list, 0.0f).c1, glm::vec3(1, 1, 1));
    const auto f = starntFeatures(s);
    EXPECT_FLOAT_EQ(f[0], 1.0f);
    EXPECT_EQ(f[1], 2.0f);
    const auto d = dfaoitFeatures(s);
    expectVec({d[7], d[8], d[9]}, {0.5f, 0.0f, 0.5f * 0.25f}, 1e-7f, "C_exact2");
}

TEST(NnFeatures, ThreeFragmentsTailIsTheThirdFragment) {
    FragmentList list = {frag({0.2f, 0.4f, 0.6f}, 0.4f, 0.9f, 0), frag({1, 0, 0}, 0.5f, 0.1f, 1),
                         frag({0, 1, 0}, 0.3f, 0.5f, 2)};
    const PixelSums s = sumsFromFragments(list);
    EXPECT_EQ(s.count, 3.0f);
    EXPECT_EQ(s.c1, glm::vec3(1, 0, 0));
    EXPECT_EQ(s.c2, glm::vec3(0, 1, 0));
    const auto f = starntFeatures(s);
    EXPECT_NEAR(f[0], 0.6f, 1e-6);  // T_all / T2 = 1 - a3
    EXPECT_EQ(f[1], 3.0f);
    expectVec({f[2], f[3], f[4]}, {0.2f, 0.4f, 0.6f}, 1e-6f, "C_tilde = C3");
    const auto d = dfaoitFeatures(s);
    EXPECT_NEAR(d[0], 0.4f, 1e-6);
    expectVec({d[1], d[2], d[3]}, {0.2f, 0.4f, 0.6f}, 1e-6f, "C_avg");
    expectVec(starntTarget(preparedFragments(list)), {0.08f, 0.16f, 0.24f}, 1e-7f, "tail target");
}

TEST(NnFeatures, FourFragmentsHandComputed) {
    // Sorted: (red .5), (green .25), (blue .5), (white .2)
    FragmentList list = {frag({1, 1, 1}, 0.2f, 0.9f, 3), frag({0, 0, 1}, 0.5f, 0.6f, 2),
                         frag({1, 0, 0}, 0.5f, 0.1f, 0), frag({0, 1, 0}, 0.25f, 0.3f, 1)};
    const PixelSums s = sumsFromFragments(list);
    EXPECT_EQ(s.count, 4.0f);
    EXPECT_FLOAT_EQ(s.sumAlpha, 1.45f);
    expectVec(s.sumAlphaColor, {0.7f, 0.45f, 0.7f}, 1e-6f, "S_aC");
    expectVec(s.sumColor, {2.0f, 2.0f, 2.0f}, 1e-6f, "S_C");
    EXPECT_NEAR(s.transmittance, 0.5f * 0.75f * 0.5f * 0.8f, 1e-7);
    const auto f = starntFeatures(s);
    EXPECT_NEAR(f[0], 0.4f, 1e-6);  // (1 - .5)(1 - .2)
    EXPECT_EQ(f[1], 4.0f);
    // Tail premultiplied (0.2, 0.2, 0.7) over tail alpha 0.7.
    expectVec({f[2], f[3], f[4]}, {0.2f / 0.7f, 0.2f / 0.7f, 1.0f}, 1e-6f, "C_tilde");
    const auto d = dfaoitFeatures(s);
    EXPECT_NEAR(d[0], 0.35f, 1e-6);
    expectVec({d[1], d[2], d[3]}, {0.5f, 0.5f, 1.0f}, 1e-6f, "C_avg");
    expectVec({d[4], d[5], d[6]}, {0.7f, 0.45f, 0.7f}, 1e-6f, "S_aC");
    expectVec({d[7], d[8], d[9]}, {0.5f, 0.125f, 0.0f}, 1e-7f, "C_exact2");
    EXPECT_NEAR(d[10], 0.625f, 1e-7);  // the front pair's alpha: 1 - (1 - .5)(1 - .25)
    EXPECT_EQ(d[11], 4.0f);
    const FragmentList sorted = preparedFragments(list);
    // Tail: blue .5, then white .2 through .5.
    expectVec(starntTarget(sorted), {0.1f, 0.1f, 0.6f}, 1e-7f, "tail target");
    expectVec(dfaoitTarget(sorted), compositeOver(sorted, glm::vec3(0.0f)), 1e-7f, "dfaoit target");
    expectVec(dfaoitTarget(sorted), {0.5f + 0.375f * 0.1f, 0.125f + 0.375f * 0.1f, 0.375f * 0.6f}, 1e-6f,
              "dfaoit target by hand");
}

TEST(NnFeatures, OpaqueFrontFragmentGuardsTailTransmittance) {
    FragmentList list = {frag({1, 0, 0}, 1.0f, 0.1f), frag({0, 1, 0}, 0.5f, 0.2f), frag({0, 0, 1}, 0.5f, 0.3f),
                         frag({1, 1, 0}, 0.5f, 0.4f)};
    const PixelSums s = sumsFromFragments(list);
    EXPECT_EQ(s.transmittance, 0.0f);
    const auto f = starntFeatures(s);
    EXPECT_EQ(f[0], 0.0f);  // T2 = 0: guarded to 0 (the tail is invisible anyway)
    expectVec({f[2], f[3], f[4]}, {0.5f, 0.5f, 0.5f}, 1e-6f, "C_tilde still defined");
    for (float v : dfaoitFeatures(s)) EXPECT_TRUE(std::isfinite(v));
}

TEST(NnFeatures, FiveHundredFragmentsGiveFiniteFeatures) {
    FragmentList list;
    for (int i = 0; i < 500; ++i)
        list.push_back(frag({(i % 7) / 7.0f, (i % 3) / 3.0f, 0.9f}, 0.03f + 0.9f * ((i * 37) % 100) / 100.0f,
                            ((i * 7919) % 1000) / 1000.0f, static_cast<uint32_t>(i)));
    const PixelSums s = sumsFromFragments(list);
    EXPECT_EQ(s.count, 500.0f);
    const auto f = starntFeatures(s);
    for (float v : f) EXPECT_TRUE(std::isfinite(v));
    EXPECT_GE(f[0], 0.0f);
    EXPECT_LE(f[0], 1.0f);
    for (float v : dfaoitFeatures(s)) EXPECT_TRUE(std::isfinite(v));
    const glm::vec3 t = starntTarget(preparedFragments(list));
    for (int k = 0; k < 3; ++k) EXPECT_TRUE(std::isfinite(t[k]));
}

TEST(NnComposite, UpToThreeFragmentsIsExactWhateverTheWeights) {
    const glm::vec3 bg(0.9f, 0.6f, 0.3f);
    const auto lists = syntheticFragmentLists(3000, 11);
    int tested = 0;
    for (uint64_t seed = 1; seed <= 3; ++seed) {
        Network net = makeUntrained(NetworkKind::StarNT, seed);
        for (auto& layer : net.layers)
            for (float& b : layer.bias) b += 5.0f;  // a network that outputs something large
        for (const auto& list : lists) {
            const FragmentList sorted = preparedFragments(list);
            if (sorted.size() > 3) continue;
            const glm::vec3 c = compositeStarnt(net, sumsFromFragments(list), bg);
            expectVec(c, compositeOver(sorted, bg), 1e-6f, "exact composite");
            ++tested;
        }
    }
    EXPECT_GT(tested, 30);
}

TEST(NnComposite, ExactTailGivesTheExactComposite) {
    const glm::vec3 bg(0.2f, 0.5f, 1.0f);
    int tested = 0;
    for (const auto& list : syntheticFragmentLists(2000, 12)) {
        const FragmentList sorted = preparedFragments(list);
        if (sorted.size() <= 3) continue;
        const PixelSums s = sumsFromFragments(list);
        const float t2 = (1.0f - s.a1) * (1.0f - s.a2);
        const glm::vec3 c =
            s.a1 * s.c1 + (1.0f - s.a1) * s.a2 * s.c2 + t2 * starntTarget(sorted) + s.transmittance * bg;
        expectVec(c, compositeOver(sorted, bg), 2e-6f, "formula");
        ++tested;
    }
    EXPECT_GT(tested, 1000);
}

TEST(NnComposite, NetworkTailIsUsedBeyondThreeFragments) {
    // A network that outputs a constant tail (all weights 0, output bias b): C = exact2 + T2 b + T bg.
    Network net = makeUntrained(NetworkKind::StarNT, 3);
    for (auto& layer : net.layers) std::fill(layer.weights.begin(), layer.weights.end(), 0.0f);
    for (auto& layer : net.layers) std::fill(layer.bias.begin(), layer.bias.end(), 0.0f);
    net.layers.back().bias = {0.25f, 0.5f, 0.75f};
    FragmentList list = {frag({1, 0, 0}, 0.5f, 0.1f), frag({0, 1, 0}, 0.5f, 0.2f), frag({0, 0, 1}, 0.5f, 0.3f),
                         frag({1, 1, 1}, 0.5f, 0.4f)};
    const glm::vec3 c = compositeStarnt(net, sumsFromFragments(list), glm::vec3(1.0f));
    expectVec(c, glm::vec3(0.5f, 0.25f, 0.0f) + 0.25f * glm::vec3(0.25f, 0.5f, 0.75f) + glm::vec3(0.0625f), 1e-6f,
              "constant tail");
}

namespace {
// The three-layer composite written out with a deep tail of colour `tailColor` (clamped at 0) under
// the tail's opacity 1 - tTail: what a residual kind's exact target must rebuild.
glm::vec3 deepTailComposite(const PixelSums& s, float tTail, glm::vec3 tailColor, glm::vec3 bg) {
    const float t2 = (1.0f - s.a1) * (1.0f - s.a2);
    return s.a1 * s.c1 + (1.0f - s.a1) * s.a2 * s.c2 + t2 * (1.0f - tTail) * glm::max(tailColor, glm::vec3(0.0f)) +
           s.transmittance * bg;
}
}  // namespace

// The residual kind: with f = 0 it is hybrid's composite bit for bit; with f the exact residual
// target it is the exact composite; its correction is scaled by the tail opacity, so a faint tail
// cannot move the pixel much whatever the network says.
TEST(NnComposite, ResidualIsHybridPlusACorrectionThatFadesWithTheTail) {
    Network net = makeUntrained(NetworkKind::StarNTResidual, 5);
    for (float& w : net.layers.back().weights) w = 0.0f;
    std::fill(net.layers.back().bias.begin(), net.layers.back().bias.end(), 0.0f);
    const glm::vec3 bg(0.3f, 0.6f, 0.9f);
    int deep = 0;
    for (const auto& list : syntheticFragmentLists(2000, 13)) {
        const PixelSums s = sumsFromFragments(list);
        const glm::vec3 residual = compositeStarntResidual(net, s, bg), hybrid = compositeHybrid(s, bg);
        ASSERT_EQ(residual, hybrid);
        const FragmentList sorted = preparedFragments(list);
        if (sorted.size() <= 3) continue;
        ++deep;
        // The exact residual in place of f gives the exact composite.
        const auto x = starntFeatures(s);
        if (1.0f - x[0] < kResidualMinTailOpacity) continue;
        const glm::vec3 target = starntResidualTarget(sorted, s);
        expectVec(deepTailComposite(s, x[0], glm::vec3(x[2], x[3], x[4]) + target, bg), compositeOver(sorted, bg), 1e-5f,
                  "exact residual");
    }
    EXPECT_GT(deep, 1000);
    // A large constant correction (+1 per channel) moves a deep pixel by at most T2 (1 - t_tail).
    for (float& b : net.layers.back().bias) b = 1.0f;
    FragmentList faint;
    for (int i = 0; i < 8; ++i) faint.push_back(frag({0.5f, 0.5f, 0.5f}, i < 2 ? 0.5f : 0.031f, 0.1f * float(i)));
    const PixelSums s = sumsFromFragments(faint);
    const float opacity = 1.0f - starntFeatures(s)[0];
    EXPECT_LT(opacity, 0.2f);
    const glm::vec3 moved = compositeStarntResidual(net, s, bg) - compositeHybrid(s, bg);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(moved[k], 0.25f * opacity, 1e-6f);
    EXPECT_EQ(compositeNetwork(net, s, bg), compositeStarntResidual(net, s, bg));
}

// starnt-d: with f = 0 it is hybrid-moments' composite bit for bit; with f its exact target the
// exact composite; compositeNetwork needs the moments for it.
TEST(NnComposite, StarntDepthIsHybridMomentsPlusACorrection) {
    Network net = makeUntrained(NetworkKind::StarNTDepth, 5);
    for (float& w : net.layers.back().weights) w = 0.0f;
    std::fill(net.layers.back().bias.begin(), net.layers.back().bias.end(), 0.0f);
    const glm::vec3 bg(0.3f, 0.6f, 0.9f);
    int deep = 0, weighted = 0;
    for (const auto& list : syntheticFragmentLists(2000, 17)) {
        const PixelSums s = sumsFromFragments(list);
        const TailMoments m = tailMomentsFromFragments(list);
        ASSERT_EQ(compositeStarntDepth(net, s, m, bg), compositeHybridMoments(s, m, bg));
        ASSERT_EQ(compositeNetwork(net, s, bg, &m), compositeHybridMoments(s, m, bg));
        const FragmentList sorted = preparedFragments(list);
        if (sorted.size() <= 3) continue;
        ++deep;
        const auto x = starntDepthFeatures(s, m);
        weighted += glm::length(glm::vec3(x[5], x[6], x[7]) - glm::vec3(x[2], x[3], x[4])) > 1e-3f;
        if (1.0f - x[0] < kResidualMinTailOpacity) continue;
        const glm::vec3 target = starntDepthTarget(sorted, s, m);
        expectVec(deepTailComposite(s, x[0], glm::vec3(x[5], x[6], x[7]) + target, bg), compositeOver(sorted, bg), 1e-5f,
                  "exact depth residual");
    }
    EXPECT_GT(deep, 1000);
    EXPECT_GT(weighted, deep / 2) << "C_m should differ from C_tilde on most deep synthetic lists";
    EXPECT_THROW(compositeNetwork(net, sumsFromFragments(syntheticFragmentLists(1, 1)[0]), bg), Error);
}

TEST(NnComposite, DfaoitAddsBackgroundThroughAllLayers) {
    Network net = makeUntrained(NetworkKind::DFAOIT, 4);
    for (auto& layer : net.layers) std::fill(layer.weights.begin(), layer.weights.end(), 0.0f);
    for (auto& layer : net.layers) std::fill(layer.bias.begin(), layer.bias.end(), 0.0f);
    FragmentList list = {frag({1, 0, 0}, 0.5f, 0.1f), frag({0, 1, 0}, 0.5f, 0.2f)};
    // Sigmoid(0) = 0.5 everywhere, background through 0.25.
    expectVec(compositeDfaoit(net, sumsFromFragments(list), glm::vec3(1.0f)), glm::vec3(0.75f), 1e-6f, "dfaoit");
    // No fragment: the background alone.
    expectVec(compositeDfaoit(net, sumsFromFragments({}), glm::vec3(0.3f)), glm::vec3(0.3f), 0.0f, "empty");
}

// hybrid-moments (nn::momentWeightedTailColor): the tail's colour weighted by where its opacity lies.
namespace {

// Two front layers, then `n` tail layers of alpha `a` evenly spaced in depth from `zFront` to
// `zBack`, their colour running from `front` to `back`.
FragmentList graded(int n, float a, float zFront, float zBack, glm::vec3 front, glm::vec3 back) {
    FragmentList list = {frag({0.2f, 0.2f, 0.2f}, 0.3f, 0.1f), frag({0.5f, 0.5f, 0.5f}, 0.3f, 0.2f)};
    for (int i = 0; i < n; ++i) {
        const float s = n > 1 ? float(i) / float(n - 1) : 0.0f;
        list.push_back(frag(glm::mix(front, back, s), a, zFront + (zBack - zFront) * s));
    }
    return list;
}

glm::vec3 exactTailColor(const FragmentList& list) {
    const FragmentList sorted = preparedFragments(list);
    const glm::vec3 tail = starntTarget(sorted);
    const PixelSums s = sumsFromFragments(list);
    return tail / (1.0f - starntFeatures(s)[0]);  // the exact tail's colour under its own opacity
}

}  // namespace

// A dense graded tail (front red, back blue): over-compositing shows mostly its front, which the
// plain alpha-weighted mean cannot see and the depth moments do.
TEST(NnTailMoments, NearerTailLayersWeighMoreThanFartherOnes) {
    const FragmentList list = graded(40, 0.1f, 0.3f, 0.6f, {1, 0, 0}, {0, 0, 1});
    const PixelSums s = sumsFromFragments(list);
    const TailMoments m = tailMomentsFromFragments(list);
    const glm::vec3 exact = exactTailColor(list), plain(starntFeatures(s)[2], starntFeatures(s)[3], starntFeatures(s)[4]);
    const glm::vec3 weighted = momentWeightedTailColor(s, m);
    EXPECT_GT(exact.r, 0.75f);            // the front dominates
    EXPECT_NEAR(plain.r, 0.5f, 1e-3f);    // the plain mean cannot tell
    const float plainError = glm::length(plain - exact), weightedError = glm::length(weighted - exact);
    EXPECT_LT(weightedError, 0.1f * plainError) << "plain " << plainError << " weighted " << weightedError;
    // The composite uses it under the tail's opacity, with the two front layers exact.
    const glm::vec3 bg(0.3f, 0.6f, 0.9f);
    const glm::vec3 truth = compositeOver(preparedFragments(list), bg);
    EXPECT_LT(glm::length(compositeHybridMoments(s, m, bg) - truth), 0.1f * glm::length(compositeHybrid(s, bg) - truth));
}

// A faint tail (t_tail near 1) lets every layer through alike: the weight is flat and the colour is
// the plain mean. So is a tail whose layers share one depth (no spread to weigh by).
TEST(NnTailMoments, FlatWeightsGiveThePlainMean) {
    const auto plainMean = [](const PixelSums& s) {
        const auto x = starntFeatures(s);
        return glm::vec3(x[2], x[3], x[4]);
    };
    // 30 layers of alpha 1e-4 (no cut-off): tau = 0.003, weights within 0.3 % of each other.
    const FragmentList faint = graded(30, 1e-4f, 0.3f, 0.6f, {1, 0, 0}, {0, 0, 1});
    const PixelSums s = sumsFromFragments(faint, 0.0f);
    const glm::vec3 weighted = momentWeightedTailColor(s, tailMomentsFromFragments(faint, 0.0f));
    expectVec(weighted, plainMean(s), 2e-3f, "faint tail");
    EXPECT_GT(weighted.r, plainMean(s).r);  // still front-weighted, a little
    // One depth for the whole tail: exactly the plain mean.
    const FragmentList flat = graded(30, 0.2f, 0.5f, 0.5f, {1, 0, 0}, {0, 0, 1});
    const PixelSums f = sumsFromFragments(flat);
    expectVec(momentWeightedTailColor(f, tailMomentsFromFragments(flat)), plainMean(f), 0.0f, "one depth");
}

// The moments count only what lies behind the second layer, in a logarithmic depth behind it, and a
// tail whose spread is tiny next to its distance (32-bit sums could not centre it) falls back to the
// plain mean.
TEST(NnTailMoments, MomentsAreLogarithmicBehindTheSecondLayerAndGuarded) {
    const FragmentList list = {frag({1, 0, 0}, 0.5f, 0.4f), frag({0, 1, 0}, 0.5f, 0.2f), frag({0, 0, 1}, 0.5f, 0.5f),
                               frag({1, 1, 1}, 0.5f, 0.7f), frag({1, 1, 0}, 0.01f, 0.9f)};  // the last below the cut-off
    const TailMoments m = tailMomentsFromFragments(list);
    // Tail: blue 0.1 and white 0.3 behind z2 = 0.4 in window depth, with 0.6 of the range left:
    // u = ln(1 + 0.1 / 6e-4) = ln(167.67) and ln(1 + 0.3 / 6e-4) = ln(501) (tail_moments_constants.h).
    const float u1 = std::log(1.0f + 0.1f / 6e-4f), u2 = std::log(501.0f);
    EXPECT_NEAR(u1, 5.1220f, 1e-4f);
    EXPECT_NEAR(m.alphaU, 0.5f * (u1 + u2), 1e-3f);
    EXPECT_NEAR(m.alphaU2, 0.5f * (u1 * u1 + u2 * u2), 1e-2f);
    expectVec(m.alphaColorU, 0.5f * glm::vec3(u2, u2, u1 + u2), 1e-3f, "sum a C u");
    expectVec(m.alphaColorU2, 0.5f * glm::vec3(u2 * u2, u2 * u2, u1 * u1 + u2 * u2), 1e-2f, "sum a C u^2");
    // Far fragments are pulled in: twice as far behind adds about ln 2 to u, not twice u.
    EXPECT_LT(u2 - u1, 1.2f);
    // Spread 1e-5 in depth 0.3 behind z2: below STARNT_TAIL_MOMENT_PLAIN_BELOW of the mean.
    FragmentList far = graded(20, 0.3f, 0.5f, 0.50001f, {1, 0, 0}, {0, 0, 1});
    const PixelSums s = sumsFromFragments(far);
    const glm::vec3 plain(starntFeatures(s)[2], starntFeatures(s)[3], starntFeatures(s)[4]);
    expectVec(momentWeightedTailColor(s, tailMomentsFromFragments(far)), plain, 0.0f, "guarded");
}
