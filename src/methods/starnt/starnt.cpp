// STAR-NT: 5-feature tail network over the three-pass pipeline (docs/DESIGN.md, "Pipeline and formats").
#include "methods/neural/neural_method.hpp"
#include "methods/registry.hpp"

namespace starnt {

const NeuralMethodConfig& starntConfig() {
    static const NeuralMethodConfig config{"starnt", nn::NetworkKind::StarNT, "methods/starnt/starnt_composite.frag.glsl",
                                           "methods/starnt/starnt_weights.json", true};
    return config;
}

std::unique_ptr<OitMethod> createStarntMethod(const SurfaceShader& surface, const MethodOptions& options) {
    return createNeuralMethod(starntConfig(), surface, options);
}

}  // namespace starnt
