// Weights file: JSON, format "starnt-weights", version 1.
//
// {
//   "format": "starnt-weights", "version": 1, "network": "starnt" | "starnt-residual" | "dfaoit",
//   "layer_sizes": [5, 32, 16, 3], "activations": ["relu", "relu", "relu" | "linear" | "sigmoid"],
//   "input_order": ["t_tail", "count", ...], "input_offset": [...], "input_scale": [...],
//   "normalization": "x' = (x - input_offset) * input_scale",
//   "seed": 1, "training_samples": 10000000, "validation_mse": 0.0012,
//   "layers": [{"weights": [out*in floats, row-major], "bias": [out floats]}, ...]
// }
// Every number must be finite with |value| <= 1e6 (kMaxMagnitude).
// Floats are written with 17 significant digits (nlohmann's double output), so a float survives
// the round trip exactly.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "starnt/error.hpp"
#include "starnt/network.hpp"

namespace starnt::nn {

namespace {

constexpr const char* kFormat = "starnt-weights";
constexpr int kVersion = 1;
// Largest magnitude accepted for any weight, bias, input offset or input scale. The shipped networks
// stay below 20 and the trainer's largest input scale is 1e6 (1 / a standard deviation of 1e-6);
// with every value within 1e6 and inputs within 1e3, no layer's sum can leave float range.
constexpr double kMaxMagnitude = 1e6;

const char* activationName(Network::Layer::Activation a) {
    return a == Network::Layer::ReLU ? "relu" : a == Network::Layer::Sigmoid ? "sigmoid" : "linear";
}

std::vector<Network::Layer::Activation> expectedActivations(NetworkKind kind) {
    using L = Network::Layer;
    return {L::ReLU, L::ReLU, outputActivation(kind)};
}

[[noreturn]] void fail(const std::string& what, const std::string& message) {
    throw Error("weights file " + what + ": " + message);
}

void checkFiniteArray(const std::vector<float>& values, size_t expected, const std::string& what,
                      const std::string& field) {
    if (values.size() != expected)
        fail(what, field + " has " + std::to_string(values.size()) + " values, expected " + std::to_string(expected));
    for (size_t i = 0; i < values.size(); ++i) {
        if (!std::isfinite(values[i])) fail(what, field + "[" + std::to_string(i) + "] is not a finite float");
        if (std::fabs(values[i]) > kMaxMagnitude) {
            std::ostringstream msg;
            msg << field << "[" << i << "] = " << values[i] << " is beyond the plausible range (|value| <= "
                << kMaxMagnitude << ")";
            fail(what, msg.str());
        }
    }
}

// Reads a JSON array of numbers as floats; non-numbers and values outside float range fail.
std::vector<float> readFloats(const nlohmann::json& j, const std::string& what, const std::string& field) {
    if (!j.is_array()) fail(what, "'" + field + "' must be an array of numbers");
    std::vector<float> out;
    out.reserve(j.size());
    for (size_t i = 0; i < j.size(); ++i) {
        const auto& v = j[i];
        if (!v.is_number()) fail(what, field + "[" + std::to_string(i) + "] is not a number (" + v.dump() + ")");
        const double d = v.get<double>();
        const float f = static_cast<float>(d);
        if (!std::isfinite(d) || !std::isfinite(f))
            fail(what, field + "[" + std::to_string(i) + "] is not a finite float (" + v.dump() + ")");
        if (std::fabs(d) > kMaxMagnitude) {
            std::ostringstream msg;
            msg << field << "[" << i << "] = " << v.dump() << " is beyond the plausible range (|value| <= " << kMaxMagnitude
                << ")";
            fail(what, msg.str());
        }
        out.push_back(f);
    }
    return out;
}

const nlohmann::json& field(const nlohmann::json& j, const char* name, const std::string& what) {
    auto it = j.find(name);
    if (it == j.end()) fail(what, std::string("missing field '") + name + "'");
    return *it;
}

// "does not match the KIND inputs [...]" (and the shorter orders a file of the kind may have).
std::string acceptedOrdersText(NetworkKind kind) {
    const auto orders = acceptedInputOrders(kind);
    return std::string("does not match the ") + kindName(kind) + " inputs " + nlohmann::json(orders[0]).dump() +
           (orders.size() > 1 ? " (or their first " + std::to_string(orders[1].size()) + ")" : "");
}

}  // namespace

void validateNetwork(const Network& net, const std::string& what) {
    const auto orders = acceptedInputOrders(net.kind);
    if (std::find(orders.begin(), orders.end(), net.inputNames) == orders.end()) {
        fail(what, "input order " + nlohmann::json(net.inputNames).dump() + " " + acceptedOrdersText(net.kind));
    }
    const std::vector<int> sizes = layerSizes(net.kind, static_cast<int>(net.inputNames.size()));
    const std::string kind = kindName(net.kind);
    if (net.layers.size() + 1 != sizes.size())
        fail(what, "a " + kind + " network has " + std::to_string(sizes.size() - 1) + " layers, found " +
                       std::to_string(net.layers.size()));
    const auto activations = expectedActivations(net.kind);
    for (size_t l = 0; l < net.layers.size(); ++l) {
        const auto& layer = net.layers[l];
        const std::string name = "layer " + std::to_string(l);
        if (layer.in != sizes[l] || layer.out != sizes[l + 1])
            fail(what, name + " is " + std::to_string(layer.in) + "->" + std::to_string(layer.out) + ", a " + kind +
                           " network needs " + std::to_string(sizes[l]) + "->" + std::to_string(sizes[l + 1]));
        if (layer.activation != activations[l])
            fail(what, name + " activation is " + activationName(layer.activation) + ", a " + kind +
                           " network needs " + activationName(activations[l]));
        checkFiniteArray(layer.weights, static_cast<size_t>(layer.in) * layer.out, what, name + " weights");
        checkFiniteArray(layer.bias, static_cast<size_t>(layer.out), what, name + " bias");
    }
    checkFiniteArray(net.inputOffset, static_cast<size_t>(sizes[0]), what, "input_offset");
    checkFiniteArray(net.inputScale, static_cast<size_t>(sizes[0]), what, "input_scale");
    if (!std::isfinite(net.validationMse)) fail(what, "validation_mse is not finite");
}

void saveWeights(const Network& net, const std::filesystem::path& path) {
    validateNetwork(net, path.string() + " (before saving)");
    nlohmann::json j;
    j["format"] = kFormat;
    j["version"] = kVersion;
    j["network"] = kindName(net.kind);
    j["layer_sizes"] = layerSizes(net.kind, static_cast<int>(net.inputNames.size()));
    nlohmann::json activations = nlohmann::json::array();
    for (const auto& layer : net.layers) activations.push_back(activationName(layer.activation));
    j["activations"] = activations;
    j["input_order"] = net.inputNames;
    j["normalization"] = "x' = (x - input_offset) * input_scale";
    j["input_offset"] = net.inputOffset;
    j["input_scale"] = net.inputScale;
    j["seed"] = net.seed;
    j["training_samples"] = net.trainingSamples;
    j["validation_mse"] = net.validationMse;
    nlohmann::json layers = nlohmann::json::array();
    for (const auto& layer : net.layers) layers.push_back({{"weights", layer.weights}, {"bias", layer.bias}});
    j["layers"] = layers;

    std::filesystem::path tmp = path;
    tmp += ".tmp";
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (!out) throw Error("cannot write weights file " + tmp.string());
        out << j.dump(1) << '\n';
        out.flush();
        if (!out) throw Error("cannot write weights file " + tmp.string());
    }
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::filesystem::remove(tmp, ec);
        throw Error("cannot write weights file " + path.string() + ": rename failed");
    }
}

Network loadWeights(const std::filesystem::path& path, std::optional<NetworkKind> expected) {
    const std::string what = path.string();
    std::ifstream in(path, std::ios::binary);
    if (!std::filesystem::is_regular_file(path) || !in) fail(what, "cannot be opened (missing or unreadable)");
    std::stringstream buffer;
    buffer << in.rdbuf();
    return parseWeights(buffer.str(), what, expected);
}

Network parseWeights(const std::string& text, const std::string& what, std::optional<NetworkKind> expected) {
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        fail(what, std::string("is not valid JSON (truncated or corrupt): ") + e.what());
    }
    if (!j.is_object()) fail(what, "is not a JSON object");
    try {
        const auto& format = field(j, "format", what);
        if (!format.is_string() || format.get<std::string>() != kFormat)
            fail(what, "format is " + format.dump() + ", expected \"" + kFormat + "\"");
        const auto& version = field(j, "version", what);
        if (!version.is_number_integer() || version.get<int64_t>() != kVersion)
            fail(what, "unsupported version " + version.dump() + " (this build reads version " +
                           std::to_string(kVersion) + ")");
        const auto& kindJson = field(j, "network", what);
        if (!kindJson.is_string()) fail(what, "'network' must be a string");
        const std::string kindStr = kindJson.get<std::string>();
        Network net;
        try {
            net.kind = parseKind(kindStr);
        } catch (const Error& e) {
            fail(what, e.what());
        }
        if (expected && *expected != net.kind)
            fail(what, std::string("is a ") + kindName(net.kind) + " network, --method " + kindName(*expected) +
                           " needs a " + kindName(*expected) + " network");

        const auto& order = field(j, "input_order", what);
        const auto orders = acceptedInputOrders(net.kind);
        const auto accepted = std::find_if(orders.begin(), orders.end(),
                                           [&](const auto& names) { return order == nlohmann::json(names); });
        if (accepted == orders.end()) fail(what, "input_order " + order.dump() + " " + acceptedOrdersText(net.kind));
        net.inputNames = *accepted;

        const std::vector<int> sizes = layerSizes(net.kind, static_cast<int>(net.inputNames.size()));
        const auto& sizesJson = field(j, "layer_sizes", what);
        if (!sizesJson.is_array() || sizesJson != nlohmann::json(sizes))
            fail(what, "layer_sizes " + sizesJson.dump() + " do not match the " + kindStr + " architecture " +
                           nlohmann::json(sizes).dump());
        const auto activations = expectedActivations(net.kind);
        nlohmann::json expectedActs = nlohmann::json::array();
        for (auto a : activations) expectedActs.push_back(activationName(a));
        const auto& acts = field(j, "activations", what);
        if (acts != expectedActs)
            fail(what, "activations " + acts.dump() + " do not match the " + kindStr + " network " +
                           expectedActs.dump());
        net.inputOffset = readFloats(field(j, "input_offset", what), what, "input_offset");
        net.inputScale = readFloats(field(j, "input_scale", what), what, "input_scale");

        const auto& seed = field(j, "seed", what);
        if (!seed.is_number_unsigned() && !(seed.is_number_integer() && seed.get<int64_t>() >= 0))
            fail(what, "seed must be a non-negative integer");
        net.seed = seed.get<uint64_t>();
        const auto& samples = field(j, "training_samples", what);
        if (!samples.is_number_unsigned() && !(samples.is_number_integer() && samples.get<int64_t>() >= 0))
            fail(what, "training_samples must be a non-negative integer");
        net.trainingSamples = samples.get<uint64_t>();
        const auto& mse = field(j, "validation_mse", what);
        if (!mse.is_number() || !std::isfinite(mse.get<double>()))
            fail(what, "validation_mse must be a finite number");
        net.validationMse = mse.get<double>();

        const auto& layers = field(j, "layers", what);
        if (!layers.is_array() || layers.size() + 1 != sizes.size())
            fail(what, "'layers' must be an array of " + std::to_string(sizes.size() - 1) + " layers");
        for (size_t l = 0; l < layers.size(); ++l) {
            const std::string name = "layers[" + std::to_string(l) + "]";
            if (!layers[l].is_object()) fail(what, name + " must be an object with weights and bias");
            Network::Layer layer;
            layer.in = sizes[l];
            layer.out = sizes[l + 1];
            layer.activation = activations[l];
            layer.weights = readFloats(field(layers[l], "weights", what), what, name + ".weights");
            layer.bias = readFloats(field(layers[l], "bias", what), what, name + ".bias");
            net.layers.push_back(std::move(layer));
        }
        validateNetwork(net, what);
        return net;
    } catch (const nlohmann::json::exception& e) {
        fail(what, std::string("malformed field: ") + e.what());
    }
}

}  // namespace starnt::nn
