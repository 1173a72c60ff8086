// Network kinds, architecture, CPU forward pass and initialisation.
#include <cmath>

#include "nn/random.hpp"
#include "starnt/error.hpp"
#include "starnt/network.hpp"

namespace starnt::nn {

const char* kindName(NetworkKind kind) {
    switch (kind) {
        case NetworkKind::StarNT: return "starnt";
        case NetworkKind::StarNTResidual: return "starnt-residual";
        case NetworkKind::DFAOIT: return "dfaoit";
        case NetworkKind::StarNTDepth: return "starnt-d";
    }
    return "?";
}

NetworkKind parseKind(const std::string& name) {
    if (name == "starnt") return NetworkKind::StarNT;
    if (name == "starnt-residual") return NetworkKind::StarNTResidual;
    if (name == "dfaoit") return NetworkKind::DFAOIT;
    if (name == "starnt-d") return NetworkKind::StarNTDepth;
    throw Error("unknown network kind '" + name + "' (expected starnt, starnt-residual, dfaoit or starnt-d)");
}

int inputCount(NetworkKind kind) {
    return readsStarntInputs(kind) ? kStarntInputs : kind == NetworkKind::StarNTDepth ? kStarntDepthInputs : kDfaoitInputs;
}

const std::vector<std::string>& canonicalInputNames(NetworkKind kind) {
    static const std::vector<std::string> starnt = {"t_tail", "count", "c_tilde_r", "c_tilde_g", "c_tilde_b"};
    static const std::vector<std::string> dfaoit = {
        "alpha_avg",           "c_avg_r",             "c_avg_g",   "c_avg_b",   "sum_alpha_color_r",
        "sum_alpha_color_g",   "sum_alpha_color_b",   "c_exact2_r", "c_exact2_g", "c_exact2_b", "alpha_exact2", "count"};
    static const std::vector<std::string> depth = {"t_tail",    "count",      "c_tilde_r",  "c_tilde_g",
                                                   "c_tilde_b", "c_moment_r", "c_moment_g", "c_moment_b"};
    return readsStarntInputs(kind) ? starnt : kind == NetworkKind::StarNTDepth ? depth : dfaoit;
}

std::vector<int> layerSizes(NetworkKind kind) { return layerSizes(kind, inputCount(kind)); }

std::vector<int> layerSizes(NetworkKind, int inputs) { return {inputs, 32, 16, 3}; }

std::vector<std::vector<std::string>> acceptedInputOrders(NetworkKind kind) {
    const auto& names = canonicalInputNames(kind);
    if (kind != NetworkKind::DFAOIT) return {names};
    return {names, std::vector<std::string>(names.begin(), names.begin() + kDfaoitTenInputs)};
}

glm::vec3 Network::forward(const float* rawInputs) const {
    // Largest layer is 32 wide; keep the buffers on the stack but allow any size.
    std::vector<float> current(static_cast<size_t>(inputCount()));
    for (size_t i = 0; i < current.size(); ++i) current[i] = (rawInputs[i] - inputOffset[i]) * inputScale[i];
    std::vector<float> next;
    for (const Layer& layer : layers) {
        next.assign(static_cast<size_t>(layer.out), 0.0f);
        for (int o = 0; o < layer.out; ++o) {
            float z = layer.bias[o];
            const float* w = layer.weights.data() + static_cast<size_t>(o) * layer.in;
            for (int i = 0; i < layer.in; ++i) z += w[i] * current[i];
            next[o] = layer.activation == Layer::ReLU      ? std::max(z, 0.0f)
                      : layer.activation == Layer::Sigmoid ? 1.0f / (1.0f + std::exp(-z))
                                                           : z;
        }
        current.swap(next);
    }
    glm::vec3 out(0.0f);
    for (size_t i = 0; i < 3 && i < current.size(); ++i) out[static_cast<int>(i)] = current[i];
    return out;
}

Network::Layer::Activation outputActivation(NetworkKind kind) {
    switch (kind) {
        case NetworkKind::StarNT: return Network::Layer::ReLU;
        case NetworkKind::StarNTResidual: return Network::Layer::Linear;
        case NetworkKind::DFAOIT: return Network::Layer::Sigmoid;
        case NetworkKind::StarNTDepth: return Network::Layer::Linear;
    }
    return Network::Layer::ReLU;
}

Network makeUntrained(NetworkKind kind, uint64_t seed) {
    Network net;
    net.kind = kind;
    net.inputNames = canonicalInputNames(kind);
    const std::vector<int> sizes = layerSizes(kind);
    net.inputOffset.assign(static_cast<size_t>(sizes.front()), 0.0f);
    net.inputScale.assign(static_cast<size_t>(sizes.front()), 1.0f);
    net.seed = seed;
    detail::Rng rng(seed ^ 0x5eed0f1a2b3c4d5eULL);
    for (size_t l = 0; l + 1 < sizes.size(); ++l) {
        Network::Layer layer;
        layer.in = sizes[l];
        layer.out = sizes[l + 1];
        const bool last = l + 2 == sizes.size();
        layer.activation = last ? outputActivation(kind) : Network::Layer::ReLU;
        // He for layers followed by ReLU, Xavier (Glorot normal) for the sigmoid output layer, a
        // tenth of Xavier for the residual's linear output (it starts near the closed form).
        const double xavier = std::sqrt(2.0 / (layer.in + layer.out));
        const double stddev = layer.activation == Network::Layer::ReLU    ? std::sqrt(2.0 / layer.in)
                              : layer.activation == Network::Layer::Linear ? 0.1 * xavier
                                                                            : xavier;
        layer.weights.resize(static_cast<size_t>(layer.in) * layer.out);
        for (float& w : layer.weights) w = static_cast<float>(stddev * rng.normal());
        // A small positive output bias keeps the ReLU outputs of STAR-NT alive at the start.
        layer.bias.assign(static_cast<size_t>(layer.out), last && kind == NetworkKind::StarNT ? 0.1f : 0.0f);
        net.layers.push_back(std::move(layer));
    }
    return net;
}

}  // namespace starnt::nn
