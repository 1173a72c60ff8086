// hybrid-moments composite (CPU reference nn::compositeHybridMoments): hybrid's, with the deep tail's
// colour weighted by where the tail's opacity lies in depth (tail_moments.glsl) instead of the plain
// alpha-weighted mean C_tilde. Exact for N <= 3 like starnt. No network: networkApplies() is false.
#include "methods/neural/neural_inputs.glsl"
#include "methods/hybrid_moments/tail_moments.glsl"

#include "methods/common/background.glsl"

bool networkApplies(PixelSums s) { return false; }

void networkInputs(PixelSums s, out float x[STARNT_NN_INPUTS]) {
    for (int i = 0; i < STARNT_NN_INPUTS; ++i) x[i] = 0.0;
}

vec3 compositePixel(PixelSums s, vec3 networkOutput) {
    return threeLayerComposite(s, (1.0 - tailTransmittance(s)) * momentWeightedTailColor(s, ivec2(gl_FragCoord.xy)),
                               background());
}
