// DFAOIT baseline: 10-feature network predicting the whole transparent colour, same three passes.
#include "methods/neural/neural_method.hpp"
#include "methods/registry.hpp"

namespace starnt {

const NeuralMethodConfig& dfaoitConfig() {
    static const NeuralMethodConfig config{"dfaoit", nn::NetworkKind::DFAOIT, "methods/dfaoit/dfaoit_composite.frag.glsl",
                                           "methods/dfaoit/dfaoit_weights.json", false};
    return config;
}

std::unique_ptr<OitMethod> createDfaoitMethod(const SurfaceShader& surface, const MethodOptions& options) {
    return createNeuralMethod(dfaoitConfig(), surface, options);
}

}  // namespace starnt
