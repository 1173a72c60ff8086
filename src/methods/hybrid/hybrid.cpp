// hybrid: STAR-NT's three passes, tiles and temporal frames with the tail composited in closed form
// instead of by the network (docs/DESIGN.md, "Pipeline and formats"): tail ~ (1 - t_tail) C_tilde, the alpha-weighted mean tail
// colour under the tail's total opacity. It answers what the network adds. It shares starnt's
// programs, so it loads starnt's shipped weights, but its composite never evaluates them.
#include "methods/neural/neural_method.hpp"
#include "methods/registry.hpp"

namespace starnt {

const NeuralMethodConfig& hybridConfig() {
    static const NeuralMethodConfig config{"hybrid", nn::NetworkKind::StarNT, "methods/hybrid/hybrid_composite.frag.glsl",
                                           "methods/starnt/starnt_weights.json", true, false};
    return config;
}

std::unique_ptr<OitMethod> createHybridMethod(const SurfaceShader& surface, const MethodOptions& options) {
    return createNeuralMethod(hybridConfig(), surface, options);
}

}  // namespace starnt
