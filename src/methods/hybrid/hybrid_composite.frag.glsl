// hybrid composite (SPEC 7; CPU reference nn::compositeHybrid): STAR-NT's inputs, the tail in closed
// form, (1 - t_tail) C_tilde: the alpha-weighted mean tail colour under the tail's total opacity.
// Exact for N <= 3 like starnt. No network: networkApplies() is false, so nnEvaluate is never called.
#include "methods/neural/neural_inputs.glsl"

uniform vec3 u_background;

bool networkApplies(PixelSums s) { return false; }

void networkInputs(PixelSums s, out float x[STARNT_NN_INPUTS]) {
    for (int i = 0; i < STARNT_NN_INPUTS; ++i) x[i] = 0.0;
}

vec3 compositePixel(PixelSums s, vec3 networkOutput) {
    vec3 tail;
    if (s.count < 2.5) {
        tail = vec3(0.0);
    } else if (s.count < 3.5) {
        tail = max(tailPremultiplied(s), vec3(0.0));
    } else {
        float t2 = twoLayerTransmittance(s);
        float tTail = t2 > STARNT_EPS_TRANSMITTANCE ? clamp(s.transmittance / t2, 0.0, 1.0) : 0.0;
        float tailAlpha = tailAlphaSum(s);
        vec3 cTilde = tailAlpha > STARNT_EPS_TAIL_ALPHA ? max(tailPremultiplied(s) / tailAlpha, vec3(0.0)) : vec3(0.0);
        tail = (1.0 - tTail) * cTilde;
    }
    return exactTwo(s) + twoLayerTransmittance(s) * tail + s.transmittance * u_background;
}
