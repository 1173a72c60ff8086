// Factories of the methods; createMethod (registry.cpp) dispatches on the name.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "starnt/oit_method.hpp"

namespace starnt {

std::unique_ptr<OitMethod> createAbufferMethod(const SurfaceShader&, const MethodOptions&);
std::unique_ptr<OitMethod> createPeelMethod(const SurfaceShader&, const MethodOptions&);
std::unique_ptr<OitMethod> createUnsortedMethod(const SurfaceShader&, const MethodOptions&);
std::unique_ptr<OitMethod> createWboitMethod(const SurfaceShader&, const MethodOptions&);
std::unique_ptr<OitMethod> createMboitMethod(const SurfaceShader&, const MethodOptions&);
struct NeuralMethodConfig;
// The neural variants, one row each (neural_variants.cpp).
const std::vector<NeuralMethodConfig>& neuralVariants();
// The neural variant called `name` (a row of neuralVariants(); "recommended" is starnt-d's row),
// null for the others.
const NeuralMethodConfig* neuralConfig(const std::string& name);

// True when `name` with `options` runs the adaptive tiles (a neural method with spatial on, by
// option or by default, or with corner inference): the methods with a tile overlay.
bool methodUsesTiles(const std::string& name, const MethodOptions& options);
// True for the methods built on the three neural passes (pass 1 = the nearest layer): the ones
// with temporal reprojection (warp, refresh or corrected frames).
bool methodHasNearestPass(const std::string& name);

}  // namespace starnt
