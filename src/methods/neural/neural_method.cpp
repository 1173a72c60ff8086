#include "methods/neural/neural_method.hpp"

#include <cstdio>

#include "core/shader.hpp"
#include "methods/common/method_base.hpp"
#include "methods/neural/neural_passes.hpp"

namespace starnt {
namespace {

std::string floatLiteral(float v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9e", double(v));
    return buf;
}

class NeuralMethod final : public MethodBase {
public:
    NeuralMethod(const NeuralMethodConfig& config, const SurfaceShader& surface, const MethodOptions& options)
        : MethodBase(surface),
          config_(config),
          network_(loadMethodNetwork(config, options)),
          pass1_(buildGeometryProgram("neural_pass1", "methods/neural/pass1_nearest.frag.glsl")),
          pass2_(buildGeometryProgram("neural_pass2", "methods/neural/pass2_second.frag.glsl")),
          pass3_(buildGeometryProgram("neural_pass3", "methods/neural/pass3_accumulate.frag.glsl")),
          composite_(buildFullscreenProgram(config.name + "_composite", config.compositeShader,
                                            "#define STARNT_EPS_TRANSMITTANCE " + floatLiteral(nn::kTransmittanceEpsilon) +
                                                "\n#define STARNT_EPS_TAIL_ALPHA " + floatLiteral(nn::kTailAlphaEpsilon) +
                                                "\n" + nn::generateInferenceGlsl(network_))),
          passes_(pass1_, pass2_, pass3_) {}

    std::string name() const override { return config_.name; }
    size_t gpuMemoryBytes() const override { return outputBytes() + passes_.gpuMemoryBytes(); }
    nlohmann::json lastFrameStats() const override {
        return {{"network", nn::kindName(network_.kind)},
                {"weights_training_samples", network_.trainingSamples},
                {"peel_epsilon", NeuralPasses::kDefaultPeelEpsilon}};
    }

    void render(const FrameDesc& frame, const DrawCallback& draw) override {
        resizeOutput(frame.width, frame.height);
        passes_.run(frame, draw, NeuralPasses::kDefaultPeelEpsilon);
        gl::ScopedPass timing(frame.timer, "inference");
        resetPassState();
        bindOutputFramebuffer();
        glUseProgram(composite_.id());
        passes_.bindInputs();
        glUniform3fv(composite_.uniform("u_background"), 1, &frame.background[0]);
        drawFullscreen();
    }

private:
    NeuralMethodConfig config_;
    nn::Network network_;
    gl::Program pass1_, pass2_, pass3_, composite_;
    NeuralPasses passes_;
};

}  // namespace

nn::Network loadMethodNetwork(const NeuralMethodConfig& config, const MethodOptions& options) {
    if (!options.weightsPath.empty()) return nn::loadWeights(options.weightsPath, config.kind);
    return nn::parseWeights(gl::embeddedSource(config.defaultWeights), "shipped " + config.name + " weights", config.kind);
}

std::unique_ptr<OitMethod> createNeuralMethod(const NeuralMethodConfig& config, const SurfaceShader& surface,
                                              const MethodOptions& options) {
    return std::make_unique<NeuralMethod>(config, surface, options);
}

}  // namespace starnt
