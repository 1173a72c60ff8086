#include "methods/registry.hpp"

#include "methods/neural/neural_method.hpp"
#include "starnt/error.hpp"

namespace starnt {
namespace {

using Factory = std::unique_ptr<OitMethod> (*)(const SurfaceShader&, const MethodOptions&);
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
        {"dfaoit", createDfaoitMethod},
        {"starnt", createStarntMethod},
        {"hybrid", createHybridMethod},
    };
    return all;
}

}  // namespace

std::vector<std::string> methodNames() {
    std::vector<std::string> names;
    for (const Entry& e : entries()) names.emplace_back(e.name);
    return names;
}

std::unique_ptr<OitMethod> createMethod(const std::string& name, const SurfaceShader& surface,
                                        const MethodOptions& options) {
    for (const Entry& e : entries()) {
        if (name != e.name) continue;
        checkGlRequirements();
        return e.factory(surface, options);
    }
    std::string valid;
    for (const Entry& e : entries()) valid += (valid.empty() ? "" : ", ") + std::string(e.name);
    throw Error("unknown method '" + name + "' (valid: " + valid + ")");
}

bool methodUsesTiles(const std::string& name, const MethodOptions& options) {
    const bool corners = options.neural.inference == NeuralOptions::Inference::Corners;
    if (name == starntConfig().name) return options.neural.spatial.value_or(starntConfig().spatialByDefault) || corners;
    if (name == dfaoitConfig().name) return options.neural.spatial.value_or(dfaoitConfig().spatialByDefault) || corners;
    if (name == hybridConfig().name) return options.neural.spatial.value_or(hybridConfig().spatialByDefault) || corners;
    return false;
}

bool methodHasNearestPass(const std::string& name) {
    return name == starntConfig().name || name == dfaoitConfig().name || name == hybridConfig().name;
}

}  // namespace starnt
