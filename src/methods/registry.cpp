#include "methods/registry.hpp"

#include "methods/neural/neural_method.hpp"
#include "starnt/error.hpp"

#include <epoxy/gl.h>

namespace starnt {
namespace {

using Factory = std::unique_ptr<OitMethod> (*)(const SurfaceShader&, const MethodOptions&);

// The recommended configuration (docs/DESIGN.md, "The recommended configuration"), chosen per
// context: recommendedMethodInContext's method with recommendedOptionsInContext's options.
std::unique_ptr<OitMethod> createRecommendedMethod(const SurfaceShader& surface, const MethodOptions& options) {
    NeuralMethodConfig config = *neuralConfig(recommendedMethodInContext(options));
    config.name = "recommended";  // name() and messages say what the engine asked for
    return createNeuralMethod(config, surface, recommendedOptionsInContext(options));
}

// The caller left the temporal settings to the configuration (the defaults).
bool leftToTheConfiguration(const NeuralOptions& asked) {
    return asked.temporalInterval == 1 && !asked.temporalAuto && asked.temporalMode == NeuralOptions::TemporalMode::Correct &&
           asked.correctedLayers == NeuralOptions::CorrectedLayers::Auto && asked.correctedOnePass;
}
struct Entry {
    const char* name;
    Factory factory;
};

const std::vector<Entry>& entries() {
    static const std::vector<Entry> all = {
        {"abuffer", createAbufferMethod},
        {"peel", createPeelMethod},
        {"unsorted", createUnsortedMethod},
        {"wboit", createWboitMethod},
        {"mboit", createMboitMethod},
    };
    return all;
}

}  // namespace

MethodOptions recommendedOptions(MethodOptions options) {
    if (options.neural.temporalInterval == 1 && !options.neural.temporalAuto) {
        options.neural.temporalInterval = kRecommendedTemporalInterval;
    }
    return options;
}

MethodOptions recommendedOptionsInContext(MethodOptions options) {
    if (leftToTheConfiguration(options.neural)) return options;  // kbuffer-moments, or starnt-d at K = 1
    return recommendedOptions(options);
}

std::string recommendedMethodInContext(const MethodOptions& options) {
    if (!leftToTheConfiguration(options.neural) || !epoxy_has_gl_extension("GL_EXT_shader_framebuffer_fetch")) return "starnt-d";
    GLint drawBuffers = 0;
    glGetIntegerv(GL_MAX_DRAW_BUFFERS, &drawBuffers);
    return drawBuffers >= 5 ? "kbuffer-moments" : "starnt-d";
}

std::vector<std::string> methodNames() {
    std::vector<std::string> names;
    for (const Entry& e : entries()) names.emplace_back(e.name);
    for (const NeuralMethodConfig& c : neuralVariants()) names.push_back(c.name);
    names.emplace_back("recommended");
    return names;
}

std::unique_ptr<OitMethod> createMethod(const std::string& name, const SurfaceShader& surface,
                                        const MethodOptions& options) {
    for (const Entry& e : entries()) {
        if (name != e.name) continue;
        checkGlRequirements();
        return e.factory(surface, options);
    }
    if (name == "recommended") {
        checkGlRequirements();
        return createRecommendedMethod(surface, options);
    }
    if (const NeuralMethodConfig* config = neuralConfig(name)) {
        checkGlRequirements();
        return createNeuralMethod(*config, surface, options);
    }
    std::string valid;
    for (const std::string& n : methodNames()) valid += (valid.empty() ? "" : ", ") + n;
    throw Error("unknown method '" + name + "' (valid: " + valid + ")");
}

const NeuralMethodConfig* neuralConfig(const std::string& name) {
    const std::string row = name == "recommended" ? "starnt-d" : name;
    for (const NeuralMethodConfig& c : neuralVariants())
        if (row == c.name) return &c;
    return nullptr;
}

bool methodUsesTiles(const std::string& name, const MethodOptions& options) {
    const NeuralMethodConfig* config = neuralConfig(name);
    if (!config) return false;
    const bool corners = options.neural.inference == NeuralOptions::Inference::Corners;
    return options.neural.spatial.value_or(config->spatialByDefault) || corners;
}

bool methodHasNearestPass(const std::string& name) { return neuralConfig(name) != nullptr; }

}  // namespace starnt
