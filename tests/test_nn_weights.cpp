// Weights file: exact round trip and a helpful starnt::Error for every kind of bad file.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "starnt/error.hpp"
#include "starnt/tools/nn.hpp"
#include "test_support.hpp"

using namespace starnt;
using namespace starnt::nn;
namespace fs = std::filesystem;

namespace {

Network sampleNetwork(NetworkKind kind) {
    Network net = makeUntrained(kind, 42);
    for (size_t i = 0; i < net.inputOffset.size(); ++i) {
        net.inputOffset[i] = 0.1f * static_cast<float>(i) + 1.0f / 3.0f;
        net.inputScale[i] = 1.0f / (7.0f + static_cast<float>(i));
    }
    net.layers[0].weights[0] = 1e-30f;  // tiny and extreme values survive too
    net.layers[0].weights[1] = -999999.94f;  // the largest magnitude a weights file may hold is 1e6
    net.layers[1].bias[3] = 0.1f;
    net.trainingSamples = 12345678901ULL;
    net.validationMse = 0.00123456789;
    return net;
}

std::string readText(const fs::path& p) {
    std::ifstream in(p);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

void writeText(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

// Expects loadWeights to throw starnt::Error whose message names the file and contains `fragment`.
void expectLoadError(const fs::path& p, const std::string& fragment,
                     std::optional<NetworkKind> expected = std::nullopt) {
    try {
        loadWeights(p, expected);
        ADD_FAILURE() << "no error for " << p << " (expected '" << fragment << "')";
    } catch (const Error& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find(p.string()), std::string::npos) << msg;
        EXPECT_NE(msg.find(fragment), std::string::npos) << "message: " << msg << "\nexpected: " << fragment;
    }
}

class NnWeightsFile : public ::testing::Test {
protected:
    void SetUp() override {
        dir = test::makeTempDir("nn_weights");
        good = dir / "good.json";
        saveWeights(sampleNetwork(NetworkKind::StarNT), good);
        json = nlohmann::json::parse(readText(good));
    }
    // Writes `j` to a fresh file and returns its path.
    fs::path write(const nlohmann::json& j, const std::string& name) {
        const fs::path p = dir / name;
        writeText(p, j.dump());
        return p;
    }
    fs::path dir, good;
    nlohmann::json json;
};

}  // namespace

TEST_F(NnWeightsFile, RoundTripIsExact) {
    for (NetworkKind kind : {NetworkKind::StarNT, NetworkKind::StarNTResidual, NetworkKind::DFAOIT, NetworkKind::StarNTDepth}) {
        const Network a = sampleNetwork(kind);
        const fs::path p = dir / (std::string(kindName(kind)) + ".json");
        saveWeights(a, p);
        EXPECT_FALSE(fs::exists(fs::path(p.string() + ".tmp")));
        const Network b = loadWeights(p, kind);
        EXPECT_EQ(b.kind, a.kind);
        EXPECT_EQ(b.inputNames, a.inputNames);
        EXPECT_EQ(b.inputOffset, a.inputOffset);
        EXPECT_EQ(b.inputScale, a.inputScale);
        EXPECT_EQ(b.seed, a.seed);
        EXPECT_EQ(b.trainingSamples, a.trainingSamples);
        EXPECT_EQ(b.validationMse, a.validationMse);
        ASSERT_EQ(b.layers.size(), a.layers.size());
        for (size_t l = 0; l < a.layers.size(); ++l) {
            EXPECT_EQ(b.layers[l].in, a.layers[l].in);
            EXPECT_EQ(b.layers[l].out, a.layers[l].out);
            EXPECT_EQ(b.layers[l].activation, a.layers[l].activation);
            ASSERT_EQ(b.layers[l].weights.size(), a.layers[l].weights.size());
            EXPECT_EQ(0, std::memcmp(b.layers[l].weights.data(), a.layers[l].weights.data(),
                                     a.layers[l].weights.size() * sizeof(float)));
            EXPECT_EQ(b.layers[l].bias, a.layers[l].bias);
        }
        // Saving again gives the same bytes.
        const fs::path p2 = dir / "again.json";
        saveWeights(b, p2);
        EXPECT_EQ(readText(p), readText(p2));
    }
    // The file documents itself.
    EXPECT_EQ(json["format"], "starnt-weights");
    EXPECT_EQ(json["version"], 1);
    EXPECT_EQ(json["network"], "starnt");
    EXPECT_EQ(json["layer_sizes"], nlohmann::json({5, 32, 16, 3}));
    EXPECT_EQ(json["input_order"][0], "t_tail");
    EXPECT_EQ(json["seed"], 42);
}

TEST_F(NnWeightsFile, SaveOverwritesAtomically) {
    saveWeights(sampleNetwork(NetworkKind::DFAOIT), good);
    EXPECT_EQ(loadWeights(good).kind, NetworkKind::DFAOIT);
    Network bad = sampleNetwork(NetworkKind::StarNT);
    bad.layers[2].bias[0] = std::nanf("");
    EXPECT_THROW(saveWeights(bad, good), Error);
    EXPECT_EQ(loadWeights(good).kind, NetworkKind::DFAOIT);  // the old file is intact
}

TEST_F(NnWeightsFile, MissingFile) { expectLoadError(dir / "nope.json", "cannot be opened"); }

TEST_F(NnWeightsFile, TruncatedJson) {
    const std::string text = readText(good);
    const fs::path p = dir / "truncated.json";
    writeText(p, text.substr(0, text.size() / 2));
    expectLoadError(p, "not valid JSON");
    writeText(p, "");
    expectLoadError(p, "not valid JSON");
}

TEST_F(NnWeightsFile, WrongFormatOrVersion) {
    auto j = json;
    j["format"] = "onnx";
    expectLoadError(write(j, "format.json"), "format");
    j = json;
    j["version"] = 2;
    expectLoadError(write(j, "version.json"), "unsupported version 2");
    j = json;
    j.erase("version");
    expectLoadError(write(j, "noversion.json"), "missing field 'version'");
    expectLoadError(write(nlohmann::json::array({1, 2}), "array.json"), "not a JSON object");
}

TEST_F(NnWeightsFile, WrongKind) {
    expectLoadError(good, "is a starnt network, --method dfaoit needs a dfaoit network", NetworkKind::DFAOIT);
    EXPECT_NO_THROW(loadWeights(good, NetworkKind::StarNT));
    auto j = json;
    j["network"] = "wboit";
    expectLoadError(write(j, "kind.json"), "unknown network kind");
    // A dfaoit-labelled file with starnt contents fails on its inputs.
    j = json;
    j["network"] = "dfaoit";
    expectLoadError(write(j, "mislabelled.json"), "input_order");
    // starnt and starnt-residual share inputs and sizes: the kind and the output activation tell them apart.
    expectLoadError(good, "is a starnt network, --method starnt-residual needs a starnt-residual network",
                    NetworkKind::StarNTResidual);
    j = json;
    j["network"] = "starnt-residual";
    expectLoadError(write(j, "residual-relu.json"), "activations");
}

TEST_F(NnWeightsFile, WrongLayerSizesOrActivations) {
    auto j = json;
    j["layer_sizes"] = {5, 64, 16, 3};
    expectLoadError(write(j, "sizes.json"), "layer_sizes [5,64,16,3] do not match");
    j = json;
    j["activations"] = {"relu", "relu", "sigmoid"};
    expectLoadError(write(j, "acts.json"), "activations");
    j = json;
    j["layers"].erase(2);
    expectLoadError(write(j, "layers.json"), "array of 3 layers");
}

TEST_F(NnWeightsFile, WrongInputOrder) {
    auto j = json;
    std::swap(j["input_order"][0], j["input_order"][1]);
    expectLoadError(write(j, "order.json"), "input_order");
}

// DFAOIT's earlier ten-input files load (their inputs are the first ten of twelve); any other
// prefix, or ten inputs with twelve-input layer sizes, does not.
TEST_F(NnWeightsFile, DfaoitTakesItsEarlierTenInputs) {
    const fs::path twelve = dir / "dfaoit12.json";
    saveWeights(sampleNetwork(NetworkKind::DFAOIT), twelve);
    EXPECT_EQ(loadWeights(twelve, NetworkKind::DFAOIT).inputCount(), kDfaoitInputs);
    const auto dfaoit = nlohmann::json::parse(readText(twelve));
    ASSERT_EQ(dfaoit["input_order"].size(), size_t(kDfaoitInputs));

    Network ten = sampleNetwork(NetworkKind::DFAOIT);
    ten.inputNames.resize(kDfaoitTenInputs);
    ten.inputOffset.resize(kDfaoitTenInputs);
    ten.inputScale.resize(kDfaoitTenInputs);
    auto& first = ten.layers[0];
    std::vector<float> weights;
    for (int o = 0; o < first.out; ++o) {
        for (int i = 0; i < kDfaoitTenInputs; ++i) weights.push_back(first.weights[size_t(o) * first.in + i]);
    }
    first.weights = weights;
    first.in = kDfaoitTenInputs;
    const fs::path tenPath = dir / "dfaoit10.json";
    saveWeights(ten, tenPath);
    const Network loaded = loadWeights(tenPath, NetworkKind::DFAOIT);
    EXPECT_EQ(loaded.inputCount(), kDfaoitTenInputs);
    // It reads the first ten of the twelve features.
    float x[kDfaoitInputs];
    for (int i = 0; i < kDfaoitInputs; ++i) x[i] = 0.05f * float(i + 1);
    EXPECT_EQ(loaded.forward(x), ten.forward(x));

    auto j = nlohmann::json::parse(readText(tenPath));
    j["input_order"].erase(9);
    j["layer_sizes"][0] = 9;
    expectLoadError(write(j, "dfaoit9.json"), "input_order");
    j = nlohmann::json::parse(readText(tenPath));
    j["layer_sizes"][0] = kDfaoitInputs;
    expectLoadError(write(j, "dfaoit10as12.json"), "layer_sizes");
}

TEST_F(NnWeightsFile, NonFiniteValues) {
    // JSON has no NaN: a hand-made file with the bare token, a string, and an overflowing number.
    std::string text = json.dump();
    const std::string key = "\"bias\":[";
    const size_t at = text.find(key) + key.size();
    const fs::path p = dir / "nan.json";
    writeText(p, text.substr(0, at) + "NaN," + text.substr(text.find(',', at) + 1));
    expectLoadError(p, "not valid JSON");
    auto j = json;
    j["layers"][1]["weights"][5] = "nan";
    expectLoadError(write(j, "string.json"), "layers[1].weights[5] is not a number");
    const fs::path huge = dir / "huge.json";
    writeText(huge, text.substr(0, at) + "1e999," + text.substr(text.find(',', at) + 1));
    try {
        loadWeights(huge);
        ADD_FAILURE() << "1e999 accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find(huge.string()), std::string::npos);
    }
    j = json;
    j["input_scale"][2] = 1e300;  // finite double, not a finite float
    expectLoadError(write(j, "double.json"), "input_scale[2] is not a finite float");
    j = json;
    j["validation_mse"] = nullptr;
    expectLoadError(write(j, "mse.json"), "validation_mse");
}

TEST_F(NnWeightsFile, ArrayLengthMismatch) {
    auto j = json;
    j["layers"][0]["weights"].erase(0);
    expectLoadError(write(j, "weights.json"), "layer 0 weights has 159 values, expected 160");
    j = json;
    j["layers"][2]["bias"].push_back(0.5);
    expectLoadError(write(j, "bias.json"), "layer 2 bias has 4 values, expected 3");
    j = json;
    j["input_offset"].erase(4);
    expectLoadError(write(j, "offset.json"), "input_offset has 4 values, expected 5");
}
