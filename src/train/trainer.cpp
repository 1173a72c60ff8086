// Trainer: MSE loss, Adam written by hand, mini-batches, forward and backward with Eigen.
//
// Why Eigen and not libtorch: the networks are tiny (5-32-16-3 has 771 parameters, 12-32-16-3
// has 995), so one training step is a handful of (<=32) x (<=32) x 256 matrix products; framework
// overhead per op would dominate in libtorch. Eigen is header-only and already a dependency of the
// project, whereas libtorch (CPU) is a ~2 GB download / ~500 MB of shared libraries that no
// distribution package provides. Measured with this trainer (one thread, batch 256, Release build,
// `build/test_nn_train --gtest_also_run_disabled_tests --gtest_filter='*DISABLED_Benchmark*'`):
// 10 M samples in 6.7 s for STAR-NT (~1.5 M samples/s) and 7.6 s for DFAOIT with ten inputs (~1.3 M samples/s),
// i.e. the default training takes seconds, not minutes. (libtorch was not measured: it is not
// installed on the build machines, and this speed leaves nothing for it to win.)
//
// Determinism: everything runs on one thread in a fixed order, and all random draws come from
// detail::Rng (no std distributions), so a seed gives bit-identical weights on every run of the
// same binary.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "train/mlp.hpp"
#include "nn/random.hpp"
#include "starnt/error.hpp"
#include "starnt/tools/train.hpp"

namespace starnt::nn {

using detail::Mat;
using detail::Mlp;

void TrainingSet::append(const TrainingSet& other) {
    if (other.size() == 0) return;
    if (size() == 0) inputs = other.inputs;
    if (inputs != other.inputs) throw Error("cannot append training sets with different input counts");
    if (!w.empty() || !other.w.empty()) {
        w.resize(size(), 1.0f);
        if (other.w.empty()) {
            w.insert(w.end(), other.size(), 1.0f);
        } else {
            w.insert(w.end(), other.w.begin(), other.w.end());
        }
    }
    x.insert(x.end(), other.x.begin(), other.x.end());
    y.insert(y.end(), other.y.begin(), other.y.end());
}

TrainingSet buildTrainingSet(NetworkKind kind, const std::vector<FragmentList>& lists, float alphaCutoff,
                             SampleWeighting weighting) {
    TrainingSet set;
    set.inputs = inputCount(kind);
    for (const FragmentList& list : lists) {
        const FragmentList sorted = preparedFragments(list, alphaCutoff);
        const size_t n = sorted.size();
        if (compositesThreeLayers(kind) ? n <= 3 : n < 1) continue;
        // Already cut off and sorted, so the cut-off cannot drop anything more here.
        const PixelSums sums = sumsFromFragments(sorted, alphaCutoff);
        glm::vec3 target;
        if (compositesThreeLayers(kind)) {
            const auto f = starntFeatures(sums);
            // How much an error of the prediction weighs in the tail colour (the residuals' are
            // scaled by the tail opacity), then in the image (through T2).
            float tailScale = 1.0f;
            if (kind == NetworkKind::StarNTDepth) {
                const TailMoments moments = tailMomentsFromFragments(sorted, alphaCutoff);
                const auto d = starntDepthFeatures(sums, moments);
                set.x.insert(set.x.end(), d.begin(), d.end());
                target = starntDepthTarget(sorted, sums, moments);
            } else {
                set.x.insert(set.x.end(), f.begin(), f.end());
                target = kind == NetworkKind::StarNTResidual ? starntResidualTarget(sorted, sums) : starntTarget(sorted);
            }
            const bool residual = outputActivation(kind) == Network::Layer::Linear;
            if (residual) tailScale = 1.0f - f[0];
            const float visibility = weighting == SampleWeighting::TailVisibility ? (1.0f - sums.a1) * (1.0f - sums.a2) : 1.0f;
            if (weighting == SampleWeighting::TailVisibility || residual)
                set.w.push_back(tailScale * tailScale * visibility * visibility);
        } else {
            const auto f = dfaoitFeatures(sums);
            set.x.insert(set.x.end(), f.begin(), f.end());
            target = dfaoitTarget(sorted);
        }
        set.y.insert(set.y.end(), {target.r, target.g, target.b});
    }
    return set;
}

namespace {

// Copies the samples `indices` of `set` into column matrices, normalising the inputs.
void gather(const TrainingSet& set, const std::vector<size_t>& indices, const std::vector<float>& offset,
            const std::vector<float>& scale, Mat<float>& x, Mat<float>& y, std::vector<float>* weights = nullptr) {
    if (weights) {
        weights->resize(indices.size());
        for (size_t c = 0; c < indices.size(); ++c) (*weights)[c] = set.w[indices[c]];
    }
    const int inputs = set.inputs;
    x.resize(inputs, static_cast<Eigen::Index>(indices.size()));
    y.resize(3, static_cast<Eigen::Index>(indices.size()));
    for (size_t c = 0; c < indices.size(); ++c) {
        const float* src = set.x.data() + indices[c] * inputs;
        for (int i = 0; i < inputs; ++i) x(i, static_cast<Eigen::Index>(c)) = (src[i] - offset[i]) * scale[i];
        for (int k = 0; k < 3; ++k) y(k, static_cast<Eigen::Index>(c)) = set.y[indices[c] * 3 + k];
    }
}

double mseOn(const Mlp<float>& m, const TrainingSet& set, const std::vector<size_t>& indices,
             const std::vector<float>& offset, const std::vector<float>& scale) {
    if (indices.empty()) return 0.0;
    detail::Workspace<float> ws;
    Mat<float> x, y;
    std::vector<float> w;
    const bool weighted = !set.w.empty();
    double sum = 0.0, weightSum = 0.0;
    const size_t chunk = 4096;
    for (size_t begin = 0; begin < indices.size(); begin += chunk) {
        const size_t end = std::min(indices.size(), begin + chunk);
        std::vector<size_t> part(indices.begin() + static_cast<std::ptrdiff_t>(begin),
                                 indices.begin() + static_cast<std::ptrdiff_t>(end));
        gather(set, part, offset, scale, x, y, weighted ? &w : nullptr);
        const Mat<float>& out = detail::forwardBatch<float>(m, x, ws);
        if (!weighted) {
            sum += (out - y).cast<double>().squaredNorm();
            weightSum += static_cast<double>(part.size());
            continue;
        }
        const Eigen::VectorXd perSample = (out - y).cast<double>().colwise().squaredNorm().transpose();
        for (Eigen::Index c = 0; c < perSample.size(); ++c) {
            sum += w[static_cast<size_t>(c)] * perSample(c);
            weightSum += w[static_cast<size_t>(c)];
        }
    }
    return weightSum > 0.0 ? sum / (3.0 * weightSum) : 0.0;
}

void shuffle(std::vector<size_t>& v, detail::Rng& rng) {
    for (size_t i = v.size(); i > 1; --i) std::swap(v[i - 1], v[rng.below(i)]);
}

}  // namespace

TrainOptions recipeOptions(NetworkKind kind) {
    TrainOptions options;
    if (kind == NetworkKind::DFAOIT) {
        // Measured on the training families and the suite (docs/DESIGN.md, "Training"): more steps
        // and a larger step lower DFAOIT's error on every family but smoke; the other kinds'
        // shipped weights keep their recipe.
        options.samples = 30'000'000;
        options.learningRate = 3e-3f;
    }
    return options;
}

double evaluateMse(const Network& net, const TrainingSet& set) {
    if (set.inputs != net.inputCount()) throw Error("training set and network have different input counts");
    std::vector<size_t> all(set.size());
    std::iota(all.begin(), all.end(), size_t{0});
    return mseOn(detail::toMlp<float>(net), set, all, net.inputOffset, net.inputScale);
}

Network train(NetworkKind kind, const TrainingSet& set, const TrainOptions& options) {
    const int inputs = inputCount(kind);
    if (set.inputs != inputs)
        throw Error(std::string("training set has ") + std::to_string(set.inputs) + " inputs, a " + kindName(kind) +
                    " network needs " + std::to_string(inputs));
    const size_t n = set.size();
    if (n < 2) throw Error("training set has fewer than 2 samples");
    if (set.y.size() != 3 * n) throw Error("training set has inconsistent target count");
    if (options.batchSize < 1) throw Error("batch size must be at least 1");
    const bool weighted = !set.w.empty();
    if (weighted && set.w.size() != n) throw Error("training set has inconsistent weight count");
    if (weighted && std::any_of(set.w.begin(), set.w.end(), [](float v) { return !(v >= 0.0f && std::isfinite(v)); }))
        throw Error("training set has a negative or non-finite sample weight");

    detail::Rng rng(options.seed * 0x9e3779b97f4a7c15ULL + 0x7a11);
    std::vector<size_t> order(n);
    std::iota(order.begin(), order.end(), size_t{0});
    shuffle(order, rng);
    size_t validationCount = static_cast<size_t>(std::llround(options.validationFraction * static_cast<double>(n)));
    validationCount = std::clamp<size_t>(validationCount, 1, n - 1);
    std::vector<size_t> validation(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(validationCount));
    std::vector<size_t> training(order.begin() + static_cast<std::ptrdiff_t>(validationCount), order.end());

    Network net = makeUntrained(kind, options.seed);
    // Normalisation from the training split: offset = mean, scale = 1 / std.
    for (int i = 0; i < inputs; ++i) {
        double sum = 0.0, sumSq = 0.0;
        for (size_t s : training) {
            const double v = set.x[s * inputs + i];
            sum += v;
            sumSq += v * v;
        }
        const double mean = sum / static_cast<double>(training.size());
        const double var = std::max(0.0, sumSq / static_cast<double>(training.size()) - mean * mean);
        const double sd = std::sqrt(var);
        net.inputOffset[i] = static_cast<float>(mean);
        net.inputScale[i] = sd > 1e-6 ? static_cast<float>(1.0 / sd) : 1.0f;
    }

    // Output bias: the mean training target (through the inverse sigmoid for DFAOIT), so training
    // starts from the constant predictor. The residual kinds start from f = 0, the closed form.
    if (outputActivation(kind) != Network::Layer::Linear) {
        double mean[3] = {0.0, 0.0, 0.0};
        for (size_t s : training)
            for (int k = 0; k < 3; ++k) mean[k] += set.y[s * 3 + k];
        auto& out = net.layers.back();
        for (int k = 0; k < 3; ++k) {
            const double v = mean[k] / static_cast<double>(training.size());
            if (out.activation == Network::Layer::Sigmoid) {
                const double p = std::clamp(v, 0.01, 0.99);
                out.bias[k] = static_cast<float>(std::log(p / (1.0 - p)));
            } else {
                out.bias[k] = static_cast<float>(std::max(v, 0.01));
            }
        }
    }

    Mlp<float> m = detail::toMlp<float>(net);
    m.linearOutput = options.linearOutputWhileTraining && net.layers.back().activation == Network::Layer::ReLU;
    Mlp<float> grad = m.zerosLike(), m1 = m.zerosLike(), m2 = m.zerosLike();
    detail::Workspace<float> ws;
    Mat<float> xb, yb;
    std::vector<float> wb;
    std::vector<size_t> batch;

    const uint64_t totalSamples = options.samples;
    const size_t batchSize = static_cast<size_t>(options.batchSize);
    const uint64_t steps = (totalSamples + batchSize - 1) / batchSize;
    const double beta1 = options.adamBeta1, beta2 = options.adamBeta2;
    double beta1Power = 1.0, beta2Power = 1.0;
    size_t cursor = training.size();  // forces a shuffle before the first batch
    uint64_t seen = 0;
    double lossSum = 0.0;
    uint64_t lossBatches = 0, nextReport = 1;
    const uint64_t reportEvery = std::max<uint64_t>(1, steps / 100);

    for (uint64_t step = 0; step < steps; ++step) {
        const size_t size = static_cast<size_t>(std::min<uint64_t>(batchSize, totalSamples - seen));
        batch.clear();
        while (batch.size() < size) {
            if (cursor == training.size()) {
                shuffle(training, rng);
                cursor = 0;
            }
            const size_t take = std::min(size - batch.size(), training.size() - cursor);
            batch.insert(batch.end(), training.begin() + static_cast<std::ptrdiff_t>(cursor),
                         training.begin() + static_cast<std::ptrdiff_t>(cursor + take));
            cursor += take;
        }
        gather(set, batch, net.inputOffset, net.inputScale, xb, yb, weighted ? &wb : nullptr);
        lossSum += detail::lossAndGradients<float>(m, xb, yb, &grad, ws, weighted ? wb.data() : nullptr);
        ++lossBatches;
        seen += size;

        // Adam with bias correction and a cosine-decayed step size.
        const double t = steps > 1 ? static_cast<double>(step) / static_cast<double>(steps - 1) : 1.0;
        const double f = options.finalLearningRateFactor;
        const double lr = options.learningRate * (f + (1.0 - f) * 0.5 * (1.0 + std::cos(3.141592653589793 * t)));
        beta1Power *= beta1;
        beta2Power *= beta2;
        const float stepSize = static_cast<float>(lr * std::sqrt(1.0 - beta2Power) / (1.0 - beta1Power));
        const float b1 = options.adamBeta1, b2 = options.adamBeta2;
        // Epsilon applied to the bias-corrected second moment, as in the Adam paper.
        const float eps = static_cast<float>(options.adamEpsilon * std::sqrt(1.0 - beta2Power));
        auto update = [&](auto& param, auto& g, auto& mom1, auto& mom2) {
            mom1 = b1 * mom1 + (1.0f - b1) * g;
            mom2 = b2 * mom2 + (1.0f - b2) * g.cwiseProduct(g);
            param.array() -= stepSize * mom1.array() / (mom2.array().sqrt() + eps);
        };
        for (size_t l = 0; l < m.w.size(); ++l) {
            update(m.w[l], grad.w[l], m1.w[l], m2.w[l]);
            update(m.b[l], grad.b[l], m1.b[l], m2.b[l]);
        }

        if (options.progress && (step + 1 == steps || step + 1 >= nextReport * reportEvery)) {
            options.progress(static_cast<double>(seen) / static_cast<double>(totalSamples),
                             lossSum / static_cast<double>(lossBatches));
            lossSum = 0.0;
            lossBatches = 0;
            ++nextReport;
        }
    }

    detail::fromMlp(m, net);
    net.trainingSamples = seen;
    net.validationMse = mseOn(detail::toMlp<float>(net), set, validation, net.inputOffset, net.inputScale);
    if (!std::isfinite(net.validationMse)) throw Error("training diverged (validation MSE is not finite)");
    return net;
}

}  // namespace starnt::nn
