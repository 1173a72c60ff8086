// hybrid-moments: hybrid (STAR-NT's three passes, the tail in closed form, no network) with the
// tail's colour weighted by where its opacity lies in depth. Pass 3 also sums the first two depth
// moments of the tail (NeuralPasses, tailMoments); the composite (hybrid_moments_composite.frag.glsl,
// CPU reference nn::compositeHybridMoments) models the tail's opacity as spread evenly over the
// interval those moments describe, so nearer tail fragments show through less of the tail than
// farther ones. What it costs: 32 bytes a pixel more than hybrid, every pass at full resolution.
// Why (DESIGN.md, "hybrid-moments"): the network and hybrid see the tail without any depth order,
// and that is what MBOIT's moments keep.
#include "methods/neural/neural_method.hpp"
#include "methods/registry.hpp"

namespace starnt {

const NeuralMethodConfig& hybridMomentsConfig() {
    static const NeuralMethodConfig config{"hybrid-moments",
                                           nn::NetworkKind::StarNT,
                                           "methods/hybrid_moments/hybrid_moments_composite.frag.glsl",
                                           "methods/starnt/starnt_weights.json",
                                           false,
                                           false,
                                           true};
    return config;
}

std::unique_ptr<OitMethod> createHybridMomentsMethod(const SurfaceShader& surface, const MethodOptions& options) {
    return createNeuralMethod(hybridMomentsConfig(), surface, options);
}

}  // namespace starnt
