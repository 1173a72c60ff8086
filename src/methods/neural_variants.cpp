// The neural variants: one row each (docs/DESIGN.md, "Adding a neural variant"). Every row runs
// NeuralPasses' three passes and one composite shader; what differs is written here. The registry
// (registry.cpp) lists these rows after the classic methods, in this order.
//
//   name             inputs (NetworkKind)  composite                      network            refuses
//   dfaoit           DFAOIT, 12 inputs     the whole transparent colour   12-32-16-3 sigmoid -
//   starnt           StarNT, 5 inputs      the paper's tail composite     5-32-16-3 ReLU     -
//   hybrid           StarNT's inputs       the tail in closed form        none               -
//   starnt-residual  StarNT, 5 inputs      hybrid's tail + a correction   5-32-16-3 linear   -
//   hybrid-moments   StarNT's inputs       tail weighted by depth moments none               reduced passes*
//   starnt-d         StarNTDepth, 8 inputs hybrid-moments' + a correction 8-32-16-3 linear   reduced passes*
//   kbuffer-moments  one pass: 3 exact layers by framebuffer fetch, the ordered closed form behind none  reduced passes*, temporal frames
//
//   * tiles (--spatial on), fixed scales below 1, corner inference and joint upsampling: the tail
//     moments are relative to pass 2's depth at the same pixel (docs/DESIGN.md, "hybrid-moments and
//     starnt-d"). The closed-form rows evaluate no network; their shaders still declare one of their
//     inputs' shape, built untrained, never called (networkApplies() is false there).
#include "methods/neural/neural_method.hpp"
#include "methods/registry.hpp"

namespace starnt {

const std::vector<NeuralMethodConfig>& neuralVariants() {
    static const std::vector<NeuralMethodConfig> variants = {
        {.name = "dfaoit",
         .kind = nn::NetworkKind::DFAOIT,
         .compositeShader = "methods/dfaoit/dfaoit_composite.frag.glsl",
         .defaultWeights = "methods/dfaoit/dfaoit_weights.json"},
        {.name = "starnt",
         .kind = nn::NetworkKind::StarNT,
         .compositeShader = "methods/starnt/starnt_composite.frag.glsl",
         .defaultWeights = "methods/starnt/starnt_weights.json",
         .spatialByDefault = true},
        {.name = "hybrid",
         .kind = nn::NetworkKind::StarNT,
         .compositeShader = "methods/hybrid/hybrid_composite.frag.glsl",
         .spatialByDefault = true,
         .evaluatesNetwork = false},
        {.name = "starnt-residual",
         .kind = nn::NetworkKind::StarNTResidual,
         .compositeShader = "methods/starnt_residual/starnt_residual_composite.frag.glsl",
         .defaultWeights = "methods/starnt_residual/starnt_residual_weights.json",
         .spatialByDefault = true},
        {.name = "hybrid-moments",
         .kind = nn::NetworkKind::StarNT,
         .compositeShader = "methods/hybrid_moments/hybrid_moments_composite.frag.glsl",
         .evaluatesNetwork = false,
         .tailMoments = true},
        {.name = "starnt-d",
         .kind = nn::NetworkKind::StarNTDepth,
         .compositeShader = "methods/starnt_d/starnt_d_composite.frag.glsl",
         .defaultWeights = "methods/starnt_d/starnt_d_weights.json",
         .tailMoments = true},
        {.name = "kbuffer-moments",
         .kind = nn::NetworkKind::StarNT,
         .compositeShader = "methods/hybrid_moments/hybrid_moments_composite.frag.glsl",
         .evaluatesNetwork = false,
         .tailMoments = true,
         .layeredEveryFrame = true},
    };
    return variants;
}

}  // namespace starnt
