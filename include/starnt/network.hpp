// The networks of the neural methods (part of starnt::oit): the MLP, its weights file and the GLSL
// the inference passes bake it into. nn.hpp (starnt::tools) adds the CPU reference of the features
// and composites they are trained and tested with.
#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace starnt::nn {

// StarNT: the paper's network, f(x) is the tail colour (docs/DESIGN.md, "Pipeline and formats").
// StarNTResidual: the same inputs and layer sizes, a linear output f(x) that corrects the closed-form
//   tail (hybrid's): tail = (1 - t_tail) * max(C_tilde + f(x), 0). Where the tail is faint the
//   correction fades with it, and f = 0 is hybrid exactly (see nn.hpp, compositeStarntResidual).
// DFAOIT: the DFAOIT baseline's network (whole transparent colour, docs/DESIGN.md, "Pipeline and formats").
// StarNTDepth ("starnt-d", docs/DESIGN.md, "hybrid-moments and starnt-d"): STAR-NT's inputs plus the tail colour weighted by the tail's
//   depth moments (hybrid-moments' C_m, nn::momentWeightedTailColor), 8-32-16-3, a linear output
//   that corrects it: tail = (1 - t_tail) * max(C_m + f(x), 0).
enum class NetworkKind { StarNT, StarNTResidual, DFAOIT, StarNTDepth };

// "starnt" / "starnt-residual" / "dfaoit" / "starnt-d".
const char* kindName(NetworkKind kind);
// Parses "starnt" / "starnt-residual" / "dfaoit" / "starnt-d"; throws starnt::Error otherwise.
NetworkKind parseKind(const std::string& name);
// Whether the kind reads STAR-NT's five inputs alone.
inline bool readsStarntInputs(NetworkKind kind) {
    return kind == NetworkKind::StarNT || kind == NetworkKind::StarNTResidual;
}
// Whether the kind's composite is STAR-NT's: the two nearest layers exact, the tail exact for N <= 3,
// the network beyond (every kind but DFAOIT's).
inline bool compositesThreeLayers(NetworkKind kind) { return kind != NetworkKind::DFAOIT; }
// Whether the kind reads pass 3's tail depth moments (its method runs every pass at full resolution).

// Feature guards (the inference shaders and the CPU reference in nn.hpp apply the same ones).
inline constexpr float kTransmittanceEpsilon = 1e-6f;
inline constexpr float kTailAlphaEpsilon = 1e-3f;
inline constexpr float kDefaultAlphaCutoff = 0.03f;

inline constexpr int kStarntInputs = 5;
// DFAOIT: the paper's features (docs/DESIGN.md, "DFAOIT's recipe"): the two front fragments'
// Porter-Duff composite as RGB and alpha, the tail's mean alpha and colour, sum a C and the count.
// Weights files of the earlier ten inputs (the composite's RGB, means and sum a C) still load.
inline constexpr int kDfaoitInputs = 12;
inline constexpr int kDfaoitTenInputs = 10;
inline constexpr int kStarntDepthInputs = 8;

// Number of inputs, canonical input names (the `input_order` of the weights file) and layer sizes
// (5-32-16-3, 12-32-16-3 or 8-32-16-3, including the input layer) of the networks this project trains.
int inputCount(NetworkKind kind);
const std::vector<std::string>& canonicalInputNames(NetworkKind kind);
std::vector<int> layerSizes(NetworkKind kind);
// Every input order a weights file of the kind may have: the canonical one first, then DFAOIT's
// earlier ten (a prefix of its twelve, so the features of a ten-input network are the first ten).
std::vector<std::vector<std::string>> acceptedInputOrders(NetworkKind kind);
// The layer sizes of a network of `kind` with `inputs` inputs.
std::vector<int> layerSizes(NetworkKind kind, int inputs);

struct Network {
    struct Layer {
        enum Activation { ReLU, Sigmoid, Linear };
        int in = 0, out = 0;
        std::vector<float> weights;  // out x in, row-major: weights[o * in + i]
        std::vector<float> bias;     // out
        Activation activation = ReLU;
    };

    NetworkKind kind = NetworkKind::StarNT;
    std::vector<std::string> inputNames;
    // Normalisation applied before the first layer: x'_i = (x_i - inputOffset[i]) * inputScale[i].
    std::vector<float> inputOffset, inputScale;
    std::vector<Layer> layers;
    uint64_t seed = 0;
    uint64_t trainingSamples = 0;  // samples seen by the trainer (0: untrained)
    double validationMse = -1.0;   // MSE on the validation split (-1: not measured)

    int inputCount() const { return layers.empty() ? 0 : layers.front().in; }
    // Normalisation then the layers, in float: the CPU reference of nnEvaluate in GLSL.
    glm::vec3 forward(const float* rawInputs) const;
};

// The output layer's activation of a kind: ReLU (starnt), linear (starnt-residual, starnt-d), sigmoid (dfaoit);
// the hidden layers are ReLU.
Network::Layer::Activation outputActivation(NetworkKind kind);

// He-initialised (ReLU layers) / Xavier-initialised (sigmoid layer) network with identity
// normalisation (offset 0, scale 1), deterministic for `seed`. A linear output layer (the residual
// kind) starts at a tenth of Xavier's scale, so that training starts near f = 0 (the closed form).
Network makeUntrained(NetworkKind kind, uint64_t seed);

// Weights file (JSON, format "starnt-weights", version 1). saveWeights writes a temporary file
// beside `path` and renames it over `path`. loadWeights checks everything (format, version, kind,
// architecture, activations, input order, array lengths, finiteness) and throws starnt::Error
// naming the file and the problem; `expected` additionally requires that kind.
void saveWeights(const Network& net, const std::filesystem::path& path);
Network loadWeights(const std::filesystem::path& path, std::optional<NetworkKind> expected = std::nullopt);
// The same checks on a weights file's text; `what` names its source in error messages.
Network parseWeights(const std::string& text, const std::string& what,
                     std::optional<NetworkKind> expected = std::nullopt);
// Same checks on a network in memory (throws starnt::Error, `what` names its source).
void validateNetwork(const Network& net, const std::string& what);

// GLSL (common subset of GLSL 4.50 and GLSL ES 3.10, no #version line) defining
//   #define STARNT_NN_INPUTS 5|10
//   vec3 nnEvaluate(float x[STARNT_NN_INPUTS])
// with the normalisation and every weight baked in as literal constants. Deterministic.
std::string generateInferenceGlsl(const Network& net);

}  // namespace starnt::nn
