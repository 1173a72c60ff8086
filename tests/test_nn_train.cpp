// Synthetic data, training sets and the trainer (Adam, determinism, learning on fragment lists).
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstring>

#include "test_support.hpp"
#include "nn/random.hpp"
#include "starnt/error.hpp"
#include "starnt/tools/families.hpp"
#include "starnt/tools/train.hpp"

using namespace starnt;
using namespace starnt::nn;

namespace {

bool sameWeights(const Network& a, const Network& b) {
    for (size_t l = 0; l < a.layers.size(); ++l) {
        if (std::memcmp(a.layers[l].weights.data(), b.layers[l].weights.data(),
                        a.layers[l].weights.size() * sizeof(float)) != 0)
            return false;
        if (a.layers[l].bias != b.layers[l].bias) return false;
    }
    return a.inputOffset == b.inputOffset && a.inputScale == b.inputScale;
}

// MSE of always predicting the mean target of `set`.
double meanPredictorMse(const TrainingSet& set) {
    double mean[3] = {0, 0, 0};
    for (size_t i = 0; i < set.size(); ++i)
        for (int k = 0; k < 3; ++k) mean[k] += set.y[3 * i + k];
    for (double& m : mean) m /= static_cast<double>(set.size());
    double sum = 0.0;
    for (size_t i = 0; i < set.size(); ++i)
        for (int k = 0; k < 3; ++k) sum += (set.y[3 * i + k] - mean[k]) * (set.y[3 * i + k] - mean[k]);
    return sum / (3.0 * static_cast<double>(set.size()));
}

// A smooth toy problem with 5 inputs and targets that a ReLU network represents easily.
TrainingSet toyProblem(size_t n) {
    TrainingSet set;
    set.inputs = 5;
    detail::Rng rng(n);
    for (size_t i = 0; i < n; ++i) {
        float x[5];
        for (float& v : x) v = static_cast<float>(rng.uniform());
        set.x.insert(set.x.end(), x, x + 5);
        set.y.insert(set.y.end(), {0.5f * x[0] + 0.2f, std::max(x[1] - x[2], 0.0f), 0.3f + 0.1f * x[3]});
    }
    return set;
}

}  // namespace

TEST(NnSynthetic, ListsAreVariedAndDeterministic) {
    const auto lists = syntheticFragmentLists(5000, 3);
    ASSERT_EQ(lists.size(), 5000u);
    size_t small = 0, large = 0, belowCutoff = 0, nearOne = 0, grey = 0, maxCount = 0;
    for (const auto& list : lists) {
        maxCount = std::max(maxCount, list.size());
        small += list.size() <= 12;
        large += list.size() >= 100;
        for (const auto& f : list) {
            ASSERT_GE(f.alpha, 0.0f);
            ASSERT_LE(f.alpha, 1.0f);
            ASSERT_GE(f.depth, 0.0f);
            ASSERT_LE(f.depth, 1.0f);
            for (int k = 0; k < 3; ++k) ASSERT_TRUE(f.color[k] >= 0.0f && f.color[k] <= 1.0f);
            belowCutoff += f.alpha < 0.03f;
            nearOne += f.alpha > 0.95f;
            grey += f.color.r == f.color.g && f.color.g == f.color.b;
        }
    }
    EXPECT_LE(maxCount, 200u);
    EXPECT_GE(maxCount, 150u);
    EXPECT_GT(small, 1500u);  // skewed toward small counts
    EXPECT_GT(large, 50u);
    EXPECT_GT(belowCutoff, 1000u);
    EXPECT_GT(nearOne, 1000u);
    EXPECT_GT(grey, 1000u);
    // Deterministic for a seed, different for another.
    const auto again = syntheticFragmentLists(50, 3), other = syntheticFragmentLists(50, 4);
    bool allSame = true, anyDiff = false;
    for (size_t i = 0; i < 50; ++i) {
        allSame &= again[i].size() == lists[i].size() &&
                   (again[i].empty() || std::memcmp(again[i].data(), lists[i].data(),
                                                    again[i].size() * sizeof(Fragment)) == 0);
        anyDiff |= other[i].size() != lists[i].size();
    }
    EXPECT_TRUE(allSame);
    EXPECT_TRUE(anyDiff);
}

TEST(NnTrainingSet, KeepsThePixelsEachNetworkIsUsedFor) {
    const auto lists = syntheticFragmentLists(2000, 5);
    size_t moreThan3 = 0, atLeast1 = 0;
    for (const auto& list : lists) {
        const size_t n = preparedFragments(list).size();
        moreThan3 += n > 3;
        atLeast1 += n >= 1;
    }
    const TrainingSet s = buildTrainingSet(NetworkKind::StarNT, lists, kDefaultAlphaCutoff);
    const TrainingSet d = buildTrainingSet(NetworkKind::DFAOIT, lists, kDefaultAlphaCutoff);
    EXPECT_EQ(s.inputs, 5);
    EXPECT_EQ(d.inputs, 12);
    EXPECT_EQ(s.size(), moreThan3);
    EXPECT_EQ(d.size(), atLeast1);
    EXPECT_LT(s.size(), d.size());
    EXPECT_EQ(s.y.size(), 3 * s.size());
    for (size_t i = 0; i < s.size(); ++i) EXPECT_GT(s.x[5 * i + 1], 3.5f);  // N > 3
    // Sample 0 matches the features and target computed directly.
    for (const auto& list : lists) {
        if (preparedFragments(list).size() <= 3) continue;
        const auto f = starntFeatures(sumsFromFragments(list));
        for (int k = 0; k < 5; ++k) EXPECT_EQ(s.x[k], f[k]);
        EXPECT_EQ(s.y[0], starntTarget(preparedFragments(list)).r);
        break;
    }
    TrainingSet both = s;
    both.append(s);
    EXPECT_EQ(both.size(), 2 * s.size());
    EXPECT_THROW(both.append(d), Error);
}

// The residual kind: STAR-NT's samples and inputs, the target tail / (1 - t_tail) - C_tilde, each
// sample weighted by (1 - t_tail)^2 (times T2^2 with TailVisibility), so that its weighted loss is
// the tail-colour (image-space) error of the composite.
TEST(NnTrainingSet, ResidualTargetsAndWeights) {
    const auto lists = syntheticFragmentLists(2000, 5);
    const TrainingSet s = buildTrainingSet(NetworkKind::StarNT, lists, kDefaultAlphaCutoff);
    const TrainingSet r = buildTrainingSet(NetworkKind::StarNTResidual, lists, kDefaultAlphaCutoff);
    const TrainingSet v = buildTrainingSet(NetworkKind::StarNTResidual, lists, kDefaultAlphaCutoff, SampleWeighting::TailVisibility);
    ASSERT_EQ(r.size(), s.size());
    EXPECT_EQ(r.x, s.x);
    ASSERT_EQ(r.w.size(), r.size());
    ASSERT_EQ(v.w.size(), r.size());
    size_t i = 0, negative = 0;
    for (const auto& list : lists) {
        const FragmentList sorted = preparedFragments(list);
        if (sorted.size() <= 3) continue;
        const PixelSums sums = sumsFromFragments(list);
        const float opacity = 1.0f - r.x[5 * i], t2 = (1.0f - sums.a1) * (1.0f - sums.a2);
        EXPECT_FLOAT_EQ(r.w[i], opacity * opacity);
        EXPECT_FLOAT_EQ(v.w[i], opacity * opacity * t2 * t2);
        for (int k = 0; k < 3; ++k) {
            // (1 - t_tail) (C_tilde + y) is the exact tail.
            const float rebuilt = opacity * (r.x[5 * i + 2 + k] + r.y[3 * i + k]);
            if (opacity >= kResidualMinTailOpacity) EXPECT_NEAR(rebuilt, s.y[3 * i + k], 2e-5f);
            else EXPECT_EQ(r.y[3 * i + k], 0.0f);
            negative += r.y[3 * i + k] < 0.0f;
        }
        ++i;
    }
    EXPECT_EQ(i, r.size());
    EXPECT_GT(negative, r.size() / 10) << "the closed form overshoots often: the residual needs a linear output";
}

TEST(NnTrain, AdamSolvesAToyProblemAndReportsProgress) {
    const TrainingSet set = toyProblem(4000);
    const Network untrained = makeUntrained(NetworkKind::StarNT, 1);
    TrainOptions o;
    o.samples = 300'000;
    o.learningRate = 3e-3f;
    o.batchSize = 32;
    std::vector<double> progress;
    double lastLoss = 0.0;
    o.progress = [&](double p, double loss) {
        progress.push_back(p);
        lastLoss = loss;
    };
    const Network net = train(NetworkKind::StarNT, set, o);
    EXPECT_LT(net.validationMse, 2e-4);
    EXPECT_LT(lastLoss, 2e-4);
    EXPECT_LT(evaluateMse(net, set), 0.01 * evaluateMse(untrained, set));
    EXPECT_EQ(net.trainingSamples, 300'000u);
    ASSERT_GE(progress.size(), 50u);
    EXPECT_DOUBLE_EQ(progress.back(), 1.0);
    for (size_t i = 1; i < progress.size(); ++i) EXPECT_GT(progress[i], progress[i - 1]);
    EXPECT_NO_THROW(validateNetwork(net, "trained"));
}

TEST(NnTrain, SameSeedSameWeightsOtherSeedOtherWeights) {
    const TrainingSet set = toyProblem(1000);
    TrainOptions o;
    o.samples = 20'000;
    o.batchSize = 100;  // the last batch of an epoch wraps around the shuffled split
    const Network a = train(NetworkKind::StarNT, set, o), b = train(NetworkKind::StarNT, set, o);
    EXPECT_TRUE(sameWeights(a, b));
    EXPECT_EQ(a.validationMse, b.validationMse);
    o.seed = 2;
    const Network c = train(NetworkKind::StarNT, set, o);
    EXPECT_FALSE(sameWeights(a, c));
    EXPECT_EQ(c.seed, 2u);
}

TEST(NnTrain, RejectsBadSets) {
    TrainingSet empty;
    empty.inputs = 5;
    EXPECT_THROW(train(NetworkKind::StarNT, empty, {}), Error);
    EXPECT_THROW(train(NetworkKind::DFAOIT, toyProblem(10), {}), Error);
}

// Both networks learn the synthetic fragment lists: held-out error far below the untrained
// network's and well below predicting the mean.
class NnTrainSynthetic : public ::testing::TestWithParam<NetworkKind> {};

TEST_P(NnTrainSynthetic, ReducesHeldOutError) {
    const NetworkKind kind = GetParam();
    const TrainingSet set = buildTrainingSet(kind, syntheticFragmentLists(30'000, 1), kDefaultAlphaCutoff);
    const TrainingSet heldOut = buildTrainingSet(kind, syntheticFragmentLists(5'000, 2), kDefaultAlphaCutoff);
    TrainOptions o;
    o.samples = 200'000;
    const auto start = std::chrono::steady_clock::now();
    const Network net = train(kind, set, o);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const Network untrained = makeUntrained(kind, 1);
    const double trained = evaluateMse(net, heldOut), before = evaluateMse(untrained, heldOut),
                 baseline = meanPredictorMse(heldOut);
    std::printf("%s: held-out MSE %.3g (validation %.3g), untrained %.3g, mean predictor %.3g, %.0f samples/s\n",
                kindName(kind), trained, net.validationMse, before, baseline, 200'000 / seconds);
    if (kind == NetworkKind::StarNTResidual) {
        // It starts at the closed form (f near 0). On the synthetic lists, whose tail colours do not
        // depend on depth, there is nothing to add to it (measured: 0.0182 against 0.0181): training
        // must not lose it. On the particles family, whose dense core is warmer, it must gain.
        auto closedForm = [&](const TrainingSet& set) {
            Network zero = untrained;
            for (float& w : zero.layers.back().weights) w = 0.0f;
            for (float& b : zero.layers.back().bias) b = 0.0f;
            return evaluateMse(zero, set);  // weighted: the residual's samples carry weights
        };
        std::printf("  f = 0 (the closed form) %.4g\n", closedForm(heldOut));
        EXPECT_LT(trained, 1.03 * closedForm(heldOut));
        EXPECT_LT(trained, 0.01 * before);
        const TrainingSet particles = buildTrainingSet(kind, proceduralFamilyLists("particles", 20'000, 1));
        const TrainingSet particlesHeldOut = buildTrainingSet(kind, proceduralFamilyLists("particles", 5'000, 2));
        const Network learnt = train(kind, particles, o);
        std::printf("  particles: trained %.4g, f = 0 %.4g\n", evaluateMse(learnt, particlesHeldOut),
                    closedForm(particlesHeldOut));
        EXPECT_LT(evaluateMse(learnt, particlesHeldOut), 0.5 * closedForm(particlesHeldOut));
        return;
    }
    EXPECT_LT(trained, 0.3 * before);
    // The tail colour of STAR-NT depends on the unknown order of the tail fragments, so part of its
    // target variance cannot be learnt; DFAOIT's target is dominated by the exact front layers.
    const double vsMean = kind == NetworkKind::StarNT ? 0.6 : 0.3;
    EXPECT_LT(trained, vsMean * baseline);
    EXPECT_LT(net.validationMse, vsMean * baseline);
}

INSTANTIATE_TEST_SUITE_P(EveryKind, NnTrainSynthetic,
                         ::testing::Values(NetworkKind::StarNT, NetworkKind::StarNTResidual, NetworkKind::DFAOIT),
                         [](const auto& info) { return test::identifier(kindName(info.param)); });

// Not run by default: the default 10 M-sample training, to measure speed and the MSE reached.
// Run: build/test_nn_train --gtest_also_run_disabled_tests --gtest_filter='*DISABLED_Benchmark*'
// (STARNT_BENCH_SAMPLES overrides the sample count). Also prints the image-space MSE of both
// methods on held-out pixels (composite over black vs the exact composite).
TEST(NnTrain, DISABLED_Benchmark) {
    const char* env = std::getenv("STARNT_BENCH_SAMPLES");
    const uint64_t samples = env ? std::strtoull(env, nullptr, 10) : 10'000'000ULL;
    const auto lists = syntheticFragmentLists(400'000, 1);
    const auto testLists = syntheticFragmentLists(20'000, 2);
    Network nets[2];
    for (NetworkKind kind : {NetworkKind::StarNT, NetworkKind::DFAOIT}) {
        const TrainingSet set = buildTrainingSet(kind, lists, kDefaultAlphaCutoff);
        const TrainingSet heldOut = buildTrainingSet(kind, testLists, kDefaultAlphaCutoff);
        TrainOptions o;
        o.samples = samples;
        const auto start = std::chrono::steady_clock::now();
        const Network net = train(kind, set, o);
        const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::printf("%s: %llu samples in %.1f s = %.0f samples/s; set %zu; validation MSE %.4g, held-out %.4g, "
                    "mean predictor %.4g\n",
                    kindName(kind), static_cast<unsigned long long>(samples), seconds, samples / seconds,
                    set.size(), net.validationMse, evaluateMse(net, heldOut), meanPredictorMse(heldOut));
        nets[kind == NetworkKind::StarNT ? 0 : 1] = net;
    }
    double err[2] = {0, 0};
    size_t pixels = 0;
    for (const auto& list : testLists) {
        const FragmentList sorted = preparedFragments(list);
        if (sorted.empty()) continue;
        const PixelSums s = sumsFromFragments(list);
        const glm::vec3 exact = compositeOver(sorted, glm::vec3(0.0f));
        const glm::vec3 a = compositeStarnt(nets[0], s, glm::vec3(0.0f)) - exact;
        const glm::vec3 b = compositeDfaoit(nets[1], s, glm::vec3(0.0f)) - exact;
        err[0] += glm::dot(a, a) / 3.0;
        err[1] += glm::dot(b, b) / 3.0;
        ++pixels;
    }
    std::printf("image-space MSE (linear, over black) on %zu held-out pixels: starnt %.4g, dfaoit %.4g\n", pixels,
                err[0] / pixels, err[1] / pixels);
}

// Sample weights: the same inputs with two targets, one of them weighted 0, must be fitted to the
// other; without weights the network settles between them.
TEST(NnTrain, SampleWeightsDecideBetweenConflictingTargets) {
    TrainingSet set = toyProblem(2000);
    const TrainingSet copy = set;
    set.w.assign(set.size(), 1.0f);
    TrainingSet conflicting = copy;
    for (float& v : conflicting.y) v = 0.9f;
    conflicting.w.assign(conflicting.size(), 0.0f);
    set.append(conflicting);
    ASSERT_EQ(set.w.size(), set.size());
    TrainOptions o;
    o.samples = 200'000;
    o.learningRate = 3e-3f;
    o.batchSize = 32;
    o.validationFraction = 0.01;
    const Network weighted = train(NetworkKind::StarNT, set, o);
    TrainingSet unweighted = set;
    unweighted.w.clear();
    const Network plain = train(NetworkKind::StarNT, unweighted, o);
    const double weightedMse = evaluateMse(weighted, copy), plainMse = evaluateMse(plain, copy);
    std::printf("MSE on the weighted targets: weighted training %.3g, unweighted %.3g\n", weightedMse, plainMse);
    EXPECT_LT(weightedMse, 2e-3);
    EXPECT_GT(plainMse, 0.03);
    // Appending an unweighted set gives its samples weight 1.
    TrainingSet mixed = copy;
    mixed.append(conflicting);
    EXPECT_EQ(mixed.w.size(), mixed.size());
    EXPECT_EQ(mixed.w.front(), 1.0f);
    EXPECT_EQ(mixed.w.back(), 0.0f);
    TrainingSet negative = copy;
    negative.w.assign(negative.size(), 1.0f);
    negative.w[5] = -1.0f;
    EXPECT_THROW(train(NetworkKind::StarNT, negative, o), Error);
}

TEST(NnTrainingSet, TailVisibilityWeightsAreTheSquaredTransmittanceOfTheFirstTwoLayers) {
    const auto lists = syntheticFragmentLists(500, 9);
    const TrainingSet plain = buildTrainingSet(NetworkKind::StarNT, lists);
    const TrainingSet s = buildTrainingSet(NetworkKind::StarNT, lists, kDefaultAlphaCutoff, SampleWeighting::TailVisibility);
    EXPECT_TRUE(plain.w.empty());
    EXPECT_EQ(s.x, plain.x);
    EXPECT_EQ(s.y, plain.y);
    ASSERT_EQ(s.w.size(), s.size());
    size_t i = 0;
    for (const auto& list : lists) {
        const FragmentList sorted = preparedFragments(list);
        if (sorted.size() <= 3) continue;
        const float t2 = (1.0f - sorted[0].alpha) * (1.0f - sorted[1].alpha);
        EXPECT_FLOAT_EQ(s.w[i], t2 * t2);
        ++i;
    }
    EXPECT_EQ(i, s.size());
    // DFAOIT predicts the whole pixel: no weights.
    EXPECT_TRUE(buildTrainingSet(NetworkKind::DFAOIT, lists, kDefaultAlphaCutoff, SampleWeighting::TailVisibility).w.empty());
}
