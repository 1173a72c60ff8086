// GLSL generated for inference: contents, literals and plausibility (GPU comparison lives elsewhere).
#include <gtest/gtest.h>

#include <cctype>
#include <cstdio>
#include <cstdlib>

#include "test_support.hpp"
#include "starnt/error.hpp"
#include "starnt/tools/nn.hpp"

using namespace starnt;
using namespace starnt::nn;

namespace {

std::string glslLiteral(float v) {
    if (v == 0.0f) return "0.0";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(v));
    std::string s = buf;
    if (s.find_first_of(".e") == std::string::npos) s += ".0";
    return s;
}

Network trainedLooking(NetworkKind kind) {
    Network net = makeUntrained(kind, 77);
    for (size_t i = 0; i < net.inputOffset.size(); ++i) {
        net.inputOffset[i] = 0.37f * static_cast<float>(i) - 1.0f;
        net.inputScale[i] = 1.0f / (3.0f + static_cast<float>(i));
    }
    for (auto& layer : net.layers)
        for (size_t i = 0; i < layer.bias.size(); ++i) layer.bias[i] = 0.01f * static_cast<float>(i) - 0.05f;
    net.layers[0].weights[3] = 2.0f;     // an integral value must still be a float literal
    net.layers[1].weights[7] = 1.5e-7f;  // exponent form
    return net;
}

}  // namespace

class NnGlsl : public ::testing::TestWithParam<NetworkKind> {};

TEST_P(NnGlsl, ContainsTheInterfaceAndEveryWeight) {
    const Network net = trainedLooking(GetParam());
    const std::string code = generateInferenceGlsl(net);
    EXPECT_NE(code.find("#define STARNT_NN_INPUTS " + std::to_string(net.inputCount()) + "\n"), std::string::npos);
    EXPECT_NE(code.find("vec3 nnEvaluate(float x[STARNT_NN_INPUTS])"), std::string::npos);
    EXPECT_EQ(code.find("double"), std::string::npos);
    EXPECT_EQ(code.find("#version"), std::string::npos);
    EXPECT_EQ(code.find("uniform"), std::string::npos);
    EXPECT_NE(code.find(" 2.0"), std::string::npos);
    EXPECT_NE(glslLiteral(1.5e-7f).find("e-07"), std::string::npos);
    EXPECT_NE(code.find(glslLiteral(1.5e-7f)), std::string::npos);
    for (const auto& layer : net.layers) {
        for (float w : layer.weights) EXPECT_NE(code.find(glslLiteral(w)), std::string::npos) << glslLiteral(w);
        for (float b : layer.bias) EXPECT_NE(code.find(glslLiteral(b)), std::string::npos) << glslLiteral(b);
    }
    for (float v : net.inputOffset) EXPECT_NE(code.find(glslLiteral(v)), std::string::npos);
    for (float v : net.inputScale) EXPECT_NE(code.find(glslLiteral(v)), std::string::npos);
    for (int i = 0; i < net.inputCount(); ++i)
        EXPECT_NE(code.find("x[" + std::to_string(i) + "]"), std::string::npos);
    if (GetParam() == NetworkKind::DFAOIT)
        EXPECT_NE(code.find("exp("), std::string::npos);  // sigmoid output
    else
        EXPECT_EQ(code.find("exp("), std::string::npos);
    // ReLU on both hidden layers' 12 chunks, and on the output unless it is linear (residual).
    size_t maxCalls = 0;
    for (size_t at = code.find("max("); at != std::string::npos; at = code.find("max(", at + 1)) ++maxCalls;
    EXPECT_EQ(maxCalls, GetParam() == NetworkKind::StarNT ? 13u : 12u);
    // Compact: well under 100 characters per parameter.
    size_t params = 0;
    for (const auto& layer : net.layers) params += layer.weights.size() + layer.bias.size();
    EXPECT_LT(code.size(), 20 * params);
}

TEST_P(NnGlsl, IsDeterministicAndPlausible) {
    const Network net = trainedLooking(GetParam());
    const std::string full = generateInferenceGlsl(net);
    EXPECT_EQ(full, generateInferenceGlsl(trainedLooking(GetParam())));
    EXPECT_NE(full, generateInferenceGlsl(makeUntrained(GetParam(), 78)));
    // The code without its // comments.
    std::string code;
    for (size_t i = 0; i < full.size();) {
        if (full.compare(i, 2, "//") == 0) {
            i = full.find('\n', i);
            if (i == std::string::npos) break;
        } else {
            code += full[i++];
        }
    }
    // Balanced brackets, never closing more than opened.
    int paren = 0, brace = 0, bracket = 0;
    for (char c : code) {
        paren += (c == '(') - (c == ')');
        brace += (c == '{') - (c == '}');
        bracket += (c == '[') - (c == ']');
        ASSERT_GE(paren, 0);
        ASSERT_GE(brace, 0);
        ASSERT_GE(bracket, 0);
    }
    EXPECT_EQ(paren, 0);
    EXPECT_EQ(brace, 0);
    EXPECT_EQ(bracket, 0);
    EXPECT_NE(code.find("return "), std::string::npos);
    // Every numeric token is a float literal (has '.' or 'e'), except array indices, type names
    // (vec4, mat4x3, h1_2 are identifiers) and the #define value.
    const std::string define = "#define STARNT_NN_INPUTS ";
    for (size_t i = 0; i < code.size(); ++i) {
        const char c = code[i];
        if (!std::isdigit(static_cast<unsigned char>(c))) continue;
        const char before = i ? code[i - 1] : ' ';
        if (std::isalnum(static_cast<unsigned char>(before)) || before == '_' || before == '.') continue;
        size_t end = i;
        while (end < code.size() && (std::isalnum(static_cast<unsigned char>(code[end])) || code[end] == '.' ||
                                     ((code[end] == '-' || code[end] == '+') && (code[end - 1] == 'e'))))
            ++end;
        const std::string token = code.substr(i, end - i);
        const bool index = end < code.size() && code[end] == ']';
        const bool defineValue = i >= define.size() && code.compare(i - define.size(), define.size(), define) == 0;
        if (!index && !defineValue) {
            EXPECT_NE(token.find_first_of(".e"), std::string::npos) << "integer literal " << token;
            char* parsed = nullptr;
            std::strtof(token.c_str(), &parsed);
            EXPECT_EQ(*parsed, '\0') << "not a number: " << token;
        }
        i = end;
    }
    // Statements: one assignment per chunk of every layer plus the return.
    size_t statements = 0;
    for (char c : code) statements += c == ';';
    const size_t inChunks = (static_cast<size_t>(net.inputCount()) + 3) / 4;
    EXPECT_EQ(statements, inChunks + 8 + 4 + 1 + 1);
}

INSTANTIATE_TEST_SUITE_P(EveryKind, NnGlsl,
                         ::testing::Values(NetworkKind::StarNT, NetworkKind::StarNTResidual, NetworkKind::DFAOIT),
                         [](const auto& info) { return test::identifier(kindName(info.param)); });

TEST(NnGlslInvalid, RejectsAnInvalidNetwork) {
    Network net = makeUntrained(NetworkKind::StarNT, 1);
    net.layers[1].weights.pop_back();
    EXPECT_THROW(generateInferenceGlsl(net), Error);
}
