// MLP forward pass, initialisation and analytic gradients (checked against finite differences).
#include <gtest/gtest.h>

#include <cmath>

#include "test_support.hpp"
#include "train/mlp.hpp"
#include "nn/random.hpp"
#include "starnt/error.hpp"
#include "starnt/tools/nn.hpp"

using namespace starnt;
using namespace starnt::nn;

namespace {

// 2 inputs -> 3 (ReLU) -> 3 (activation `last`), normalisation offset (1, -1), scale (0.5, 2).
Network tinyNetwork(Network::Layer::Activation last) {
    Network net;
    net.inputOffset = {1.0f, -1.0f};
    net.inputScale = {0.5f, 2.0f};
    Network::Layer l1;
    l1.in = 2;
    l1.out = 3;
    l1.weights = {1.0f, 0.0f,    // h0 = x0'
                  0.0f, -1.0f,   // h1 = relu(-x1' + 1)
                  1.0f, 1.0f};   // h2 = relu(x0' + x1' - 1)
    l1.bias = {0.0f, 1.0f, -1.0f};
    Network::Layer l2;
    l2.in = 3;
    l2.out = 3;
    l2.weights = {1.0f, 1.0f, 1.0f,  //
                  2.0f, 0.0f, -1.0f,  //
                  0.0f, -3.0f, 0.0f};
    l2.bias = {0.5f, 0.0f, 0.25f};
    l2.activation = last;
    net.layers = {l1, l2};
    return net;
}

}  // namespace

TEST(NnNetwork, TinyNetworkReluMatchesHandComputation) {
    const Network net = tinyNetwork(Network::Layer::ReLU);
    const float x[2] = {5.0f, -0.75f};  // normalised: (2, 0.5)
    // h = relu(2, -0.5 + 1, 2 + 0.5 - 1) = (2, 0.5, 1.5)
    // out = relu(4 + 0.5, 4 - 1.5, -1.5 + 0.25) = (4.5, 2.5, 0)
    const glm::vec3 y = net.forward(x);
    EXPECT_FLOAT_EQ(y.x, 4.5f);
    EXPECT_FLOAT_EQ(y.y, 2.5f);
    EXPECT_FLOAT_EQ(y.z, 0.0f);
}

TEST(NnNetwork, TinyNetworkSigmoidMatchesHandComputation) {
    const Network net = tinyNetwork(Network::Layer::Sigmoid);
    const float x[2] = {5.0f, -0.75f};
    auto sigmoid = [](float z) { return 1.0f / (1.0f + std::exp(-z)); };
    const glm::vec3 y = net.forward(x);
    EXPECT_NEAR(y.x, sigmoid(4.5f), 1e-6);
    EXPECT_NEAR(y.y, sigmoid(2.5f), 1e-6);
    EXPECT_NEAR(y.z, sigmoid(-1.25f), 1e-6);  // negative pre-activation: not clamped to 0
    EXPECT_GT(y.z, 0.2f);
}

TEST(NnNetwork, NormalisationIsApplied) {
    Network net = tinyNetwork(Network::Layer::ReLU);
    const float x[2] = {5.0f, -0.75f};
    const glm::vec3 before = net.forward(x);
    net.inputOffset = {0.0f, 0.0f};
    net.inputScale = {1.0f, 1.0f};
    EXPECT_NE(net.forward(x), before);
}

TEST(NnNetwork, UntrainedNetworksHaveTheArchitectureAndAreSeeded) {
    for (NetworkKind kind : {NetworkKind::StarNT, NetworkKind::StarNTResidual, NetworkKind::DFAOIT, NetworkKind::StarNTDepth}) {
        const Network a = makeUntrained(kind, 7), b = makeUntrained(kind, 7), c = makeUntrained(kind, 8);
        EXPECT_NO_THROW(validateNetwork(a, "untrained"));
        ASSERT_EQ(a.layers.size(), 3u);
        EXPECT_EQ(a.layers[0].in, kind == NetworkKind::DFAOIT ? 12 : kind == NetworkKind::StarNTDepth ? 8 : 5);
        EXPECT_EQ(a.layers[0].out, 32);
        EXPECT_EQ(a.layers[1].out, 16);
        EXPECT_EQ(a.layers[2].out, 3);
        EXPECT_EQ(a.layers[2].activation, kind == NetworkKind::StarNT   ? Network::Layer::ReLU
                                          : kind == NetworkKind::DFAOIT ? Network::Layer::Sigmoid
                                                                        : Network::Layer::Linear);
        EXPECT_EQ(a.inputNames, canonicalInputNames(kind));
        EXPECT_EQ(a.layers[0].weights, b.layers[0].weights);
        EXPECT_NE(a.layers[0].weights, c.layers[0].weights);
        // He init: the first layer's weights have roughly variance 2 / fan_in.
        double sumSq = 0.0;
        for (float w : a.layers[1].weights) sumSq += w * w;
        EXPECT_NEAR(sumSq / a.layers[1].weights.size(), 2.0 / 32.0, 0.02);
    }
    EXPECT_EQ(parseKind("dfaoit"), NetworkKind::DFAOIT);
    EXPECT_EQ(parseKind("starnt-residual"), NetworkKind::StarNTResidual);
    EXPECT_STREQ(kindName(NetworkKind::StarNT), "starnt");
    EXPECT_STREQ(kindName(NetworkKind::StarNTResidual), "starnt-residual");
    EXPECT_EQ(parseKind("starnt-d"), NetworkKind::StarNTDepth);
    EXPECT_STREQ(kindName(NetworkKind::StarNTDepth), "starnt-d");
    // The residual's linear output starts small (a tenth of Xavier: variance 0.01 * 2 / (16 + 3)),
    // so that training starts near f = 0, the closed form.
    const Network r = makeUntrained(NetworkKind::StarNTResidual, 7);
    double outSq = 0.0;
    for (float w : r.layers[2].weights) outSq += w * w;
    EXPECT_LT(outSq / r.layers[2].weights.size(), 0.01 * 2.0 / 19.0 * 3.0);
    EXPECT_GT(outSq / r.layers[2].weights.size(), 0.01 * 2.0 / 19.0 / 3.0);
    EXPECT_THROW(parseKind("wboit"), Error);
}

TEST(NnNetwork, BatchedForwardMatchesNetworkForward) {
    for (NetworkKind kind : {NetworkKind::StarNT, NetworkKind::StarNTResidual, NetworkKind::DFAOIT, NetworkKind::StarNTDepth}) {
        Network net = makeUntrained(kind, 3);
        for (float& b : net.layers.back().bias) b = -0.05f;  // some outputs negative before the activation
        const int inputs = net.inputCount();
        detail::Rng rng(5);
        detail::Mat<float> x(inputs, 16);
        for (Eigen::Index i = 0; i < x.size(); ++i) x.data()[i] = static_cast<float>(rng.normal());
        detail::Workspace<float> ws;
        const detail::Mat<float> out = detail::forwardBatch<float>(detail::toMlp<float>(net), x, ws);
        for (int c = 0; c < 16; ++c) {
            const glm::vec3 y = net.forward(x.col(c).data());  // identity normalisation
            for (int k = 0; k < 3; ++k) EXPECT_NEAR(out(k, c), y[k], 1e-5f * (1.0f + std::abs(y[k])));
        }
    }
}

// Analytic gradients of the MSE loss w.r.t. every weight and bias agree with central differences.
// Also with the linear-output training surrogate (see detail::Mlp::linearOutput).
class NnGradient : public ::testing::TestWithParam<std::tuple<NetworkKind, bool>> {};

TEST_P(NnGradient, AnalyticMatchesFiniteDifferences) {
    const NetworkKind kind = std::get<0>(GetParam());
    using M = detail::Mat<double>;
    detail::Mlp<double> mlp = detail::toMlp<double>(makeUntrained(kind, 21));
    mlp.linearOutput = std::get<1>(GetParam());
    detail::Rng rng(99);
    for (auto& b : mlp.b)
        for (Eigen::Index i = 0; i < b.size(); ++i) b(i) = 0.1 * rng.normal();  // non-zero biases
    const int inputs = inputCount(kind);
    const int batch = 12;
    M x(inputs, batch), y(3, batch);
    for (Eigen::Index i = 0; i < x.size(); ++i) x.data()[i] = rng.normal();
    for (Eigen::Index i = 0; i < y.size(); ++i) y.data()[i] = rng.uniform();

    detail::Workspace<double> ws;
    detail::Mlp<double> grad = mlp.zerosLike();
    const double loss = detail::lossAndGradients<double>(mlp, x, y, &grad, ws);
    ASSERT_GT(loss, 0.0);

    const double h = 1e-6;
    int checked = 0, nonZero = 0;
    double worst = 0.0;
    auto check = [&](double& param, double analytic) {
        const double saved = param;
        param = saved + h;
        const double up = detail::lossAndGradients<double>(mlp, x, y, nullptr, ws);
        param = saved - h;
        const double down = detail::lossAndGradients<double>(mlp, x, y, nullptr, ws);
        param = saved;
        const double numeric = (up - down) / (2.0 * h);
        const double err = std::abs(analytic - numeric);
        const double scale = std::max(std::abs(analytic), std::abs(numeric));
        EXPECT_LE(err, 1e-4 * scale + 1e-9) << "analytic " << analytic << " numeric " << numeric;
        if (scale > 1e-9) worst = std::max(worst, err / scale);
        ++checked;
        nonZero += scale > 1e-6;
    };
    for (size_t l = 0; l < mlp.w.size(); ++l) {
        for (Eigen::Index i = 0; i < mlp.w[l].size(); ++i) check(mlp.w[l].data()[i], grad.w[l].data()[i]);
        for (Eigen::Index i = 0; i < mlp.b[l].size(); ++i) check(mlp.b[l].data()[i], grad.b[l].data()[i]);
    }
    EXPECT_EQ(checked, inputs * 32 + 32 + 32 * 16 + 16 + 16 * 3 + 3);
    EXPECT_GT(nonZero, checked / 2);  // the check is not vacuous
    RecordProperty("worst_relative_error", std::to_string(worst));
}

INSTANTIATE_TEST_SUITE_P(EveryKind, NnGradient,
                         ::testing::Combine(::testing::Values(NetworkKind::StarNT, NetworkKind::StarNTResidual,
                                                              NetworkKind::DFAOIT, NetworkKind::StarNTDepth),
                                            ::testing::Bool()),
                         [](const auto& info) {
                             return test::identifier(kindName(std::get<0>(info.param))) +
                                    (std::get<1>(info.param) ? "_linear_output" : "");
                         });

TEST(NnNetwork, LinearOutputSurrogateOnlyChangesTheLastActivation) {
    detail::Mlp<double> mlp = detail::toMlp<double>(makeUntrained(NetworkKind::StarNT, 2));
    mlp.b.back().setConstant(-10.0);  // every real output is clamped to 0
    detail::Mat<double> x = detail::Mat<double>::Ones(5, 4), y = detail::Mat<double>::Ones(3, 4);
    detail::Workspace<double> ws;
    EXPECT_NEAR(detail::lossAndGradients<double>(mlp, x, y, nullptr, ws), 1.0, 1e-12);
    mlp.linearOutput = true;
    EXPECT_GT(detail::lossAndGradients<double>(mlp, x, y, nullptr, ws), 1.0);
}
