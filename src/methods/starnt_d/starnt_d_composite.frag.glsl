// starnt-d composite (CPU reference nn::compositeStarntDepth): STAR-NT's five inputs plus C_m, the
// tail colour weighted by the tail's depth moments (hybrid-moments' closed form,
// methods/hybrid_moments/tail_moments.glsl), and a network of 8-32-16-3 that corrects C_m:
//   tail = 0 (N <= 2), the third fragment exactly (N == 3), (1 - t_tail) max(C_m + f(x), 0) otherwise,
//   C = a1 C1 + (1 - a1) a2 C2 + T2 * tail + T_all * C_bg.
// f(x) = 0 is hybrid-moments' composite. nnEvaluate() (linear output) is generated from the weights
// file and prepended.
#include "methods/neural/neural_inputs.glsl"
#include "methods/hybrid_moments/tail_moments.glsl"

#include "methods/common/background.glsl"

bool networkApplies(PixelSums s) { return s.count >= 3.5 && s.a2 > 0.0; }  // threeLayerComposite's deep tail

// C_m of this pixel, computed once: networkInputs and compositePixel both need it (each call reads
// two moment texels and evaluates the weight's integrals).
vec3 tailMomentColor;
bool tailMomentColorKnown = false;
vec3 pixelTailMomentColor(PixelSums s) {
    if (!tailMomentColorKnown) {
        tailMomentColor = momentWeightedTailColor(s, ivec2(gl_FragCoord.xy));
        tailMomentColorKnown = true;
    }
    return tailMomentColor;
}

void networkInputs(PixelSums s, out float x[STARNT_NN_INPUTS]) {
    float starnt[5];
    starntInputs(s, starnt);
    for (int i = 0; i < 5; ++i) x[i] = starnt[i];
    vec3 moment = pixelTailMomentColor(s);
    x[5] = moment.r;
    x[6] = moment.g;
    x[7] = moment.b;
}

// `networkOutput` is f(x) where networkApplies(s), unused elsewhere (threeLayerComposite ignores the
// deep tail for N <= 3).
vec3 compositePixel(PixelSums s, vec3 networkOutput) {
    vec3 moment = pixelTailMomentColor(s);
    vec3 deepTail = (1.0 - tailTransmittance(s)) * max(moment + networkOutput, vec3(0.0));
    return threeLayerComposite(s, deepTail, background());
}
