// starnt-residual composite (CPU reference nn::compositeStarntResidual): STAR-NT's inputs and network
// size (the inputs are starnt's, methods/starnt/starnt_composite.frag.glsl), the network correcting
// the closed-form tail instead of replacing it:
//   tail = 0 (N <= 2), the third fragment exactly (N == 3), (1 - t_tail) max(C_tilde + f(x), 0) otherwise,
//   C = a1 C1 + (1 - a1) a2 C2 + T2 * tail + T_all * C_bg.
// f(x) = 0 is hybrid's composite; the correction fades with the tail's opacity, so a faint tail
// (smoke) keeps the closed form's small absolute error. nnEvaluate() (linear output) is generated
// from the weights file and prepended.
#include "methods/neural/neural_inputs.glsl"

#include "methods/common/background.glsl"

bool networkApplies(PixelSums s) { return s.count >= 3.5 && s.a2 > 0.0; }  // threeLayerComposite's deep tail

void networkInputs(PixelSums s, out float x[STARNT_NN_INPUTS]) { starntInputs(s, x); }

// `networkOutput` is f(x) where networkApplies(s), unused elsewhere.
vec3 compositePixel(PixelSums s, vec3 networkOutput) {
    vec3 deepTail = (1.0 - tailTransmittance(s)) * max(tailMeanColor(s) + networkOutput, vec3(0.0));
    return threeLayerComposite(s, deepTail, background());
}
