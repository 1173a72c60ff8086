// hybrid composite (docs/DESIGN.md, "Pipeline and formats"; CPU reference nn::compositeHybrid): STAR-NT's inputs, the tail in closed
// form, (1 - t_tail) C_tilde: the alpha-weighted mean tail colour under the tail's total opacity.
// Exact for N <= 3 like starnt. No network: networkApplies() is false, so nnEvaluate is never called.
#include "methods/neural/neural_inputs.glsl"

#include "methods/common/background.glsl"

bool networkApplies(PixelSums s) { return false; }

void networkInputs(PixelSums s, out float x[STARNT_NN_INPUTS]) {
    for (int i = 0; i < STARNT_NN_INPUTS; ++i) x[i] = 0.0;
}

vec3 compositePixel(PixelSums s, vec3 networkOutput) {
    return threeLayerComposite(s, (1.0 - tailTransmittance(s)) * tailMeanColor(s), background());
}
