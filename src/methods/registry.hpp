// Factories of the methods; createMethod (registry.cpp) dispatches on the name.
#pragma once
#include <memory>

#include "starnt/oit_method.hpp"

namespace starnt {

std::unique_ptr<OitMethod> createAbufferMethod(const SurfaceShader&, const MethodOptions&);
std::unique_ptr<OitMethod> createPeelMethod(const SurfaceShader&, const MethodOptions&);
std::unique_ptr<OitMethod> createUnsortedMethod(const SurfaceShader&, const MethodOptions&);
std::unique_ptr<OitMethod> createWboitMethod(const SurfaceShader&, const MethodOptions&);
std::unique_ptr<OitMethod> createMboitMethod(const SurfaceShader&, const MethodOptions&);
std::unique_ptr<OitMethod> createDfaoitMethod(const SurfaceShader&, const MethodOptions&);
std::unique_ptr<OitMethod> createStarntMethod(const SurfaceShader&, const MethodOptions&);
std::unique_ptr<OitMethod> createHybridMethod(const SurfaceShader&, const MethodOptions&);
std::unique_ptr<OitMethod> createStarntResidualMethod(const SurfaceShader&, const MethodOptions&);
std::unique_ptr<OitMethod> createHybridMomentsMethod(const SurfaceShader&, const MethodOptions&);
std::unique_ptr<OitMethod> createStarntDepthMethod(const SurfaceShader&, const MethodOptions&);

struct NeuralMethodConfig;
const NeuralMethodConfig& starntConfig();
const NeuralMethodConfig& dfaoitConfig();
const NeuralMethodConfig& hybridConfig();
const NeuralMethodConfig& starntResidualConfig();
const NeuralMethodConfig& hybridMomentsConfig();
const NeuralMethodConfig& starntDepthConfig();
// The neural method called `name` (starnt, dfaoit, hybrid, starnt-residual, hybrid-moments,
// starnt-d), null for the others.
const NeuralMethodConfig* neuralConfig(const std::string& name);

// True when `name` with `options` runs the adaptive tiles (a neural method with spatial on, by
// option or by default, or with corner inference): the methods with a tile overlay.
bool methodUsesTiles(const std::string& name, const MethodOptions& options);
// True for the methods built on the three neural passes (pass 1 = the nearest layer): the ones
// with temporal reprojection (warp, refresh or corrected frames).
bool methodHasNearestPass(const std::string& name);

}  // namespace starnt
