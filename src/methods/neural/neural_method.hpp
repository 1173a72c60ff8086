// A neural OIT method, in the order the data flows through a real frame:
//   passes (neural_passes.*) -> upsample (upsample.glsl, fused into the reads) -> infer
//   (infer_full / infer_corners + infer_fill, with the network generated from a weights file)
//   -> tiles (tiles/, docs/DESIGN.md, "Adaptive tiles and tile-guided resolution") -> scales of the next real frame (docs/DESIGN.md, "Adaptive tiles and tile-guided resolution"). `starnt` and `dfaoit` are two configurations of
// it (network kind, composite shader, default weights), each in its own folder.
#pragma once
#include <memory>

#include "starnt/network.hpp"
#include "starnt/oit_method.hpp"

namespace starnt {

struct NeuralMethodConfig {
    std::string name;                // what createMethod takes
    nn::NetworkKind kind;            // the network, or for closed forms the inputs' layout
    std::string compositeShader;     // embedded path of the composite fragment shader
    std::string defaultWeights = {};  // embedded path of the shipped weights (JSON); none for closed forms
    bool spatialByDefault = false;   // MethodOptions::spatial when unset
    bool evaluatesNetwork = true;    // false for the closed forms: they read no weights file
    // hybrid-moments: pass 3 also sums the tail's depth moments (NeuralPasses); every pass at full
    // resolution (tiles, reduced scales, corner inference and joint upsampling are refused).
    bool tailMoments = false;
    // kbuffer-moments: every frame is one geometry pass that keeps the nearest three fragments
    // exactly by framebuffer fetch and composites the ordered closed form behind them (the frames
    // recommended interpolates, as a method of their own: docs/DESIGN.md, "kbuffer-moments"). No
    // network, no real frames; the reference depth of a frame's moments is the last frame's.
    bool layeredEveryFrame = false;
};

std::unique_ptr<OitMethod> createNeuralMethod(const NeuralMethodConfig& config, const SurfaceShader& surface,
                                              const MethodOptions& options);

// The network a method would use: options.neural.weightsPath when set, else the shipped weights.
nn::Network loadMethodNetwork(const NeuralMethodConfig& config, const MethodOptions& options);

}  // namespace starnt
