// starnt-d (docs/DESIGN.md, "hybrid-moments and starnt-d"): STAR-NT's passes with hybrid-moments' tail depth moments, and a network that
// corrects the moment-weighted tail colour (NetworkKind::StarNTDepth, 8-32-16-3, linear output).
// The network kind the issue allows when the paper's five inputs, which carry no depth order inside
// the tail, cannot beat the peers; measured in docs/results/ (the 13-scene table) and DESIGN.md.
// Memory: hybrid-moments' (pass 3's two moment targets and its 32-bit sums), every pass at full
// resolution. Shipped weights: `starnt train --network starnt-d --weighting tail-visibility`.
#include "methods/neural/neural_method.hpp"
#include "methods/registry.hpp"

namespace starnt {

const NeuralMethodConfig& starntDepthConfig() {
    static const NeuralMethodConfig config{"starnt-d",
                                           nn::NetworkKind::StarNTDepth,
                                           "methods/starnt_d/starnt_d_composite.frag.glsl",
                                           "methods/starnt_d/starnt_d_weights.json",
                                           false,
                                           true,
                                           true};
    return config;
}

std::unique_ptr<OitMethod> createStarntDepthMethod(const SurfaceShader& surface, const MethodOptions& options) {
    return createNeuralMethod(starntDepthConfig(), surface, options);
}

}  // namespace starnt
