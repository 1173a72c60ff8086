// Training of the STAR-NT and DFAOIT networks: synthetic fragment lists, training sets and the
// trainer (MSE loss, Adam, mini-batches with Eigen on the CPU, single-threaded so that a seed gives
// the same weights on every run).
#pragma once
#include <cstdint>
#include <functional>
#include <vector>

#include "starnt/tools/fragments.hpp"
#include "starnt/tools/nn.hpp"

namespace starnt::nn {

// `count` random per-pixel fragment lists (unsorted, random depths), deterministic for `seed`:
// fragment counts 0..~200 skewed toward small counts; alphas uniform over random ranges, clustered,
// near the cut-off (some below it), near 1; colours random, similar, greyscale or from a small palette.
std::vector<FragmentList> syntheticFragmentLists(size_t count, uint64_t seed);

// Samples stored row by row: sample i has inputs x[i*inputs .. i*inputs+inputs) (raw, not
// normalised) and target y[3*i .. 3*i+3).
// Optional weights w[i] >= 0 scale sample i's squared error in the training loss (empty: all 1;
// appending a weighted and an unweighted set gives the unweighted samples weight 1).
struct TrainingSet {
    int inputs = 0;
    std::vector<float> x, y, w;
    size_t size() const { return inputs > 0 ? x.size() / static_cast<size_t>(inputs) : 0; }
    void append(const TrainingSet& other);  // same `inputs` (or this one empty)
};

// How buildTrainingSet weights the samples. The residual kind's samples always carry the square of
// their tail opacity (1 - t_tail)^2, by which an error of f reaches the tail colour, so that its
// loss measures what starnt's measures; TailVisibility multiplies that by T2^2.
enum class SampleWeighting {
    None,
    // STAR-NT only: weight T2^2 = ((1 - a1)(1 - a2))^2, the factor by which an error of the tail
    // colour reaches the image, so that the loss is the image-space squared error. (DFAOIT's target
    // is the whole pixel already: its weights stay 1.)
    TailVisibility,
};

// Features (sumsFromFragments + starntFeatures/dfaoitFeatures) and targets (starntTarget,
// starntResidualTarget or dfaoitTarget of the cut-off, sorted list) of every list that the network is used for:
// STAR-NT keeps pixels with N > 3 (the others are composited exactly), DFAOIT keeps N >= 1.
TrainingSet buildTrainingSet(NetworkKind kind, const std::vector<FragmentList>& lists,
                             float alphaCutoff = kDefaultAlphaCutoff, SampleWeighting weighting = SampleWeighting::None);

struct TrainOptions {
    uint64_t samples = 10'000'000;  // samples seen in total (epochs over the training split as needed)
    uint64_t seed = 1;              // initial weights, split, shuffling
    int batchSize = 256;
    float learningRate = 1e-3f;     // Adam step size at the start ...
    float finalLearningRateFactor = 0.05f;  // ... cosine-decayed to this fraction of it at the end
    float adamBeta1 = 0.9f, adamBeta2 = 0.999f, adamEpsilon = 1e-8f;
    double validationFraction = 0.05;  // held out (at least one sample), never trained on
    // STAR-NT's ReLU output layer is trained as linear (a surrogate loss that bounds the real MSE
    // from above, as targets are >= 0), so that output units cannot die; inference keeps the ReLU.
    bool linearOutputWhileTraining = true;
    // Called about 100 times: progress in [0, 1] and the mean training loss since the last call.
    std::function<void(double progress, double trainLoss)> progress;
};

// The options of a kind's shipped recipe (what `starnt train` uses unless told otherwise): the
// defaults above, except DFAOIT's 30 M samples at a step size of 3e-3. With the defaults DFAOIT is
// under-trained: its error on pixels of one or two fragments, where WBOIT is exact, stays near 1e-4
// (docs/DESIGN.md, "Training", DFAOIT's recipe).
TrainOptions recipeOptions(NetworkKind kind);

// Trains a network of `kind` on `set` (set.inputs must match the kind). Input normalisation is
// mean/std of the training split (scale 1 for a constant input). Records seed, samples seen and the
// validation MSE (mean over samples and the 3 channels, weighted by the sample weights if any) in
// the result. Throws starnt::Error on an empty or mismatched set.
Network train(NetworkKind kind, const TrainingSet& set, const TrainOptions& options);

// Mean squared error (over samples and the 3 channels) of `net` on `set`; with sample weights, the
// weighted mean (sum w e^2 / sum w), as the recorded validation MSE.
double evaluateMse(const Network& net, const TrainingSet& set);

}  // namespace starnt::nn
