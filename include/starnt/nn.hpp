// Neural OIT networks: per-pixel features, the MLP, its weights file and GLSL code generation.
//
// Everything here is the CPU reference of what the GPU computes:
//   passes 1-3 -> PixelSums (sumsFromFragments), PixelSums -> network inputs (starntFeatures,
//   dfaoitFeatures), inputs -> prediction (Network::forward, same maths as generateInferenceGlsl),
//   prediction -> final pixel colour (compositeStarnt, compositeDfaoit).
//
// Feature guards (the GPU shader must apply the same ones, see the constants below):
//   T2     = (1 - a1)(1 - a2)
//   t_tail = T2 > kTransmittanceEpsilon ? clamp(T_all / T2, 0, 1) : 0
//   A_tail = S_a - a1 - a2
//   C_tilde = A_tail > kTailAlphaEpsilon ? max((S_aC - a1 C1 - a2 C2) / A_tail, 0) : 0
//   DFAOIT: n_tail = N - 2; n_tail > 0.5 ? (a_avg = max(A_tail, 0) / n_tail,
//           C_avg = max(S_C - C1 - C2, 0) / n_tail) : zeros.
// Composite of STAR-NT (exact where the sums determine the tail):
//   tail = N < 2.5 ? 0 : N < 3.5 ? max(S_aC - a1 C1 - a2 C2, 0) : f(x)
//   C    = a1 C1 + (1 - a1) a2 C2 + T2 * tail + T_all * C_bg
#pragma once
#include <array>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "starnt/fragments.hpp"

namespace starnt::nn {

enum class NetworkKind { StarNT, DFAOIT };

// "starnt" / "dfaoit".
const char* kindName(NetworkKind kind);
// Parses "starnt" / "dfaoit"; throws starnt::Error otherwise.
NetworkKind parseKind(const std::string& name);

// Feature guards (see the top of this file).
inline constexpr float kTransmittanceEpsilon = 1e-6f;
inline constexpr float kTailAlphaEpsilon = 1e-3f;
inline constexpr float kDefaultAlphaCutoff = 0.03f;

// What passes 1-3 produce for one pixel. Pass 1: nearest fragment (c1, a1); pass 2: second nearest
// (c2, a2); both zero when absent. Pass 3: sums over ALL fragments (after the alpha cut-off).
struct PixelSums {
    glm::vec3 c1{0.0f};
    float a1 = 0.0f;
    glm::vec3 c2{0.0f};
    float a2 = 0.0f;
    float count = 0.0f;                // N
    float sumAlpha = 0.0f;             // S_a = sum a_i
    glm::vec3 sumAlphaColor{0.0f};     // S_aC = sum a_i C_i
    glm::vec3 sumColor{0.0f};          // S_C = sum C_i (DFAOIT only)
    float transmittance = 1.0f;        // T_all = prod (1 - a_i)
};

// CPU reference of passes 1-3. `fragments` may be in any order; fragments with alpha < cutoff are
// dropped, the rest sorted by depth (sortByDepth). Sums are accumulated in double, stored as float.
PixelSums sumsFromFragments(FragmentList fragments, float alphaCutoff = kDefaultAlphaCutoff);

// Drops fragments with alpha < cutoff and sorts the rest by depth: the list targets are defined on.
FragmentList preparedFragments(FragmentList fragments, float alphaCutoff = kDefaultAlphaCutoff);

inline constexpr int kStarntInputs = 5;
inline constexpr int kDfaoitInputs = 10;

// STAR-NT inputs, in this order: t_tail, N, C_tilde.r, C_tilde.g, C_tilde.b.
std::array<float, kStarntInputs> starntFeatures(const PixelSums& s);
// DFAOIT inputs, in this order: a_avg, C_avg.rgb, S_aC.rgb, C_exact2.rgb.
std::array<float, kDfaoitInputs> dfaoitFeatures(const PixelSums& s);

// Targets, from a list already prepared (cut off and sorted, see preparedFragments).
// STAR-NT: exact tail colour sum_{i>=3} a_i C_i prod_{3<=j<i} (1 - a_j) (zero when N <= 2).
glm::vec3 starntTarget(const FragmentList& sorted);
// DFAOIT: whole transparent colour sum_i a_i C_i prod_{j<i} (1 - a_j) (no background).
glm::vec3 dfaoitTarget(const FragmentList& sorted);

// Canonical input names (the `input_order` of the weights file) and layer sizes
// (5-32-16-3 or 10-32-16-3, including the input layer).
const std::vector<std::string>& canonicalInputNames(NetworkKind kind);
std::vector<int> layerSizes(NetworkKind kind);

struct Network {
    struct Layer {
        enum Activation { ReLU, Sigmoid };
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

// He-initialised (ReLU layers) / Xavier-initialised (sigmoid layer) network with identity
// normalisation (offset 0, scale 1), deterministic for `seed`.
Network makeUntrained(NetworkKind kind, uint64_t seed);

// Final pixel colours (CPU reference of the composite shader).
// STAR-NT: see the top of this file (exact for N <= 3, the network is not evaluated there).
glm::vec3 compositeStarnt(const Network& net, const PixelSums& s, glm::vec3 background);
// hybrid (SPEC 7): STAR-NT's composite with the tail in closed form, (1 - t_tail) C_tilde.
glm::vec3 compositeHybrid(const PixelSums& s, glm::vec3 background);
// DFAOIT: f(x) + T_all * C_bg; a pixel without fragments (N < 0.5) is the background alone.
glm::vec3 compositeDfaoit(const Network& net, const PixelSums& s, glm::vec3 background);

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
