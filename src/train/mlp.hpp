// Batched MLP maths for the trainer (internal): forward, MSE loss and its gradients by hand.
// Templated on the scalar so that the trainer runs in float and the gradient check in double with
// the same code. Samples are columns: inputs x batch.
#pragma once
#include <vector>

#include <Eigen/Dense>

#include "starnt/tools/nn.hpp"

namespace starnt::nn::detail {

template <class S>
using Mat = Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic>;
template <class S>
using Vec = Eigen::Matrix<S, Eigen::Dynamic, 1>;

template <class S>
struct Mlp {
    std::vector<Mat<S>> w;  // out x in
    std::vector<Vec<S>> b;  // out
    std::vector<Network::Layer::Activation> act;
    // Training surrogate for a ReLU output layer: the output activation is skipped (identity), so
    // an output unit can never die. Because targets are >= 0, |relu(z) - y| <= |z - y|: the MSE of
    // the real (ReLU) network is at most the surrogate loss.
    bool linearOutput = false;

    // Whether layer l's activation is the identity: a linear layer, or the output under the surrogate.
    bool identityAt(size_t l) const { return act[l] == Network::Layer::Linear || (linearOutput && l + 1 == w.size()); }

    // Same shapes, all zero (gradients, Adam moments).
    Mlp zerosLike() const {
        Mlp z;
        z.act = act;
        z.linearOutput = linearOutput;
        for (size_t l = 0; l < w.size(); ++l) {
            z.w.push_back(Mat<S>::Zero(w[l].rows(), w[l].cols()));
            z.b.push_back(Vec<S>::Zero(b[l].size()));
        }
        return z;
    }
};

template <class S>
Mlp<S> toMlp(const Network& net) {
    Mlp<S> m;
    for (const auto& layer : net.layers) {
        Mat<S> w(layer.out, layer.in);
        for (int o = 0; o < layer.out; ++o)
            for (int i = 0; i < layer.in; ++i) w(o, i) = static_cast<S>(layer.weights[static_cast<size_t>(o) * layer.in + i]);
        Vec<S> b(layer.out);
        for (int o = 0; o < layer.out; ++o) b(o) = static_cast<S>(layer.bias[o]);
        m.w.push_back(std::move(w));
        m.b.push_back(std::move(b));
        m.act.push_back(layer.activation);
    }
    return m;
}

template <class S>
void fromMlp(const Mlp<S>& m, Network& net) {
    for (size_t l = 0; l < net.layers.size(); ++l) {
        auto& layer = net.layers[l];
        for (int o = 0; o < layer.out; ++o) {
            for (int i = 0; i < layer.in; ++i)
                layer.weights[static_cast<size_t>(o) * layer.in + i] = static_cast<float>(m.w[l](o, i));
            layer.bias[o] = static_cast<float>(m.b[l](o));
        }
    }
}

template <class S>
struct Workspace {
    std::vector<Mat<S>> a;  // a[0] = input, a[l+1] = output of layer l
    Mat<S> delta, prevDelta;
};

// Forward pass of normalised inputs x (inputs x batch); returns the output (outputs x batch), which
// lives in ws.a.back().
template <class S>
const Mat<S>& forwardBatch(const Mlp<S>& m, const Eigen::Ref<const Mat<S>>& x, Workspace<S>& ws) {
    ws.a.resize(m.w.size() + 1);
    ws.a[0] = x;
    for (size_t l = 0; l < m.w.size(); ++l) {
        Mat<S>& z = ws.a[l + 1];
        z.resize(m.w[l].rows(), x.cols());
        z.noalias() = m.w[l] * ws.a[l];
        z.colwise() += m.b[l];
        if (m.identityAt(l)) continue;
        if (m.act[l] == Network::Layer::ReLU)
            z = z.cwiseMax(S(0));
        else
            z = (S(1) / (S(1) + (-z.array()).exp())).matrix();
    }
    return ws.a.back();
}

// MSE loss (mean over batch and outputs) of the network on (x, y); when grad is given, fills it
// with d loss / d parameters (grad must have the network's shapes, e.g. from zerosLike()).
// `sampleWeights` (one per column of x, or null for all 1) weights each sample's squared error.
template <class S>
S lossAndGradients(const Mlp<S>& m, const Eigen::Ref<const Mat<S>>& x, const Eigen::Ref<const Mat<S>>& y,
                   Mlp<S>* grad, Workspace<S>& ws, const S* sampleWeights = nullptr) {
    const Mat<S>& out = forwardBatch(m, x, ws);
    const S count = static_cast<S>(out.rows() * out.cols());
    ws.delta = out - y;
    S loss;
    if (sampleWeights) {
        // Weighted squared error: sum_c w_c |out_c - y_c|^2 / count; d/d out = 2 w_c (out_c - y_c) / count.
        const Eigen::Map<const Eigen::Matrix<S, Eigen::Dynamic, 1>> w(sampleWeights, out.cols());
        loss = (ws.delta.colwise().squaredNorm().transpose().cwiseProduct(w)).sum() / count;
        ws.delta = ws.delta * w.asDiagonal();
    } else {
        loss = ws.delta.squaredNorm() / count;
    }
    if (!grad) return loss;
    ws.delta *= S(2) / count;  // d loss / d out
    for (size_t l = m.w.size(); l-- > 0;) {
        const Mat<S>& a = ws.a[l + 1];
        // d loss / d z, from the activation output.
        if (m.identityAt(l)) {
            // identity
        } else if (m.act[l] == Network::Layer::ReLU)
            ws.delta = ws.delta.cwiseProduct((a.array() > S(0)).template cast<S>().matrix());
        else
            ws.delta = ws.delta.cwiseProduct((a.array() * (S(1) - a.array())).matrix());
        grad->w[l].noalias() = ws.delta * ws.a[l].transpose();
        grad->b[l] = ws.delta.rowwise().sum();
        if (l > 0) {
            ws.prevDelta.resize(m.w[l].cols(), ws.delta.cols());
            ws.prevDelta.noalias() = m.w[l].transpose() * ws.delta;
            ws.delta.swap(ws.prevDelta);
        }
    }
    return loss;
}

}  // namespace starnt::nn::detail
