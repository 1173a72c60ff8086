// starnt-residual composite (CPU reference nn::compositeStarntResidual): STAR-NT's inputs and network
// size, the network correcting the closed-form tail instead of replacing it:
//   tail = 0 (N <= 2), the third fragment exactly (N == 3), (1 - t_tail) max(C_tilde + f(x), 0) otherwise,
//   C = a1 C1 + (1 - a1) a2 C2 + T2 * tail + T_all * C_bg.
// f(x) = 0 is hybrid's composite; the correction fades with the tail's opacity, so a faint tail
// (smoke) keeps the closed form's small absolute error. nnEvaluate() (linear output) is generated
// from the weights file and prepended.
#include "methods/neural/neural_inputs.glsl"

uniform vec3 u_background;

bool networkApplies(PixelSums s) { return s.count >= 3.5; }

void networkInputs(PixelSums s, out float x[STARNT_NN_INPUTS]) {
    float t2 = twoLayerTransmittance(s);
    float tTail = t2 > STARNT_EPS_TRANSMITTANCE ? clamp(s.transmittance / t2, 0.0, 1.0) : 0.0;
    float tailAlpha = tailAlphaSum(s);
    vec3 cTilde = tailAlpha > STARNT_EPS_TAIL_ALPHA ? max(tailPremultiplied(s) / tailAlpha, vec3(0.0)) : vec3(0.0);
    x[0] = tTail;
    x[1] = s.count;
    x[2] = cTilde.r;
    x[3] = cTilde.g;
    x[4] = cTilde.b;
}

// `networkOutput` is f(x) where networkApplies(s), unused elsewhere.
vec3 compositePixel(PixelSums s, vec3 networkOutput) {
    vec3 tail;
    if (s.count < 2.5) {
        tail = vec3(0.0);
    } else if (s.count < 3.5) {
        tail = max(tailPremultiplied(s), vec3(0.0));
    } else {
        float x[STARNT_NN_INPUTS];
        networkInputs(s, x);
        tail = (1.0 - x[0]) * max(vec3(x[2], x[3], x[4]) + networkOutput, vec3(0.0));
    }
    return exactTwo(s) + twoLayerTransmittance(s) * tail + s.transmittance * u_background;
}
