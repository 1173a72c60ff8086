// starnt-residual: STAR-NT's three passes, inputs and 5-32-16-3 network, the network trained to
// correct the closed-form tail (hybrid's) rather than to predict the tail (nn::NetworkKind::
// StarNTResidual). Not the paper's composite (docs/DESIGN.md, "Pipeline and formats" keeps `starnt` as the paper's); it is measured
// beside starnt and hybrid in the bench (docs/DESIGN.md, "hybrid-moments and starnt-d", "what the network adds").
#include "methods/neural/neural_method.hpp"
#include "methods/registry.hpp"

namespace starnt {

const NeuralMethodConfig& starntResidualConfig() {
    static const NeuralMethodConfig config{"starnt-residual", nn::NetworkKind::StarNTResidual,
                                           "methods/starnt_residual/starnt_residual_composite.frag.glsl",
                                           "methods/starnt_residual/starnt_residual_weights.json", true};
    return config;
}

std::unique_ptr<OitMethod> createStarntResidualMethod(const SurfaceShader& surface, const MethodOptions& options) {
    return createNeuralMethod(starntResidualConfig(), surface, options);
}

}  // namespace starnt
