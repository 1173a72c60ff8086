// DFAOIT baseline (Tsopouridis et al. 2024), low-end variant, features and composite, read by the
// inference passes in methods/neural/infer_*.frag.glsl:
//   inputs x = [a_avg, C_avg.rgb, sum a C (rgb), C_exact2.rgb, alpha_exact2, N] (averages over the N-2
//   tail fragments; C_exact2 and alpha_exact2 = 1 - T2 the two front fragments' Porter-Duff over;
//   a network of the earlier ten inputs reads the first ten: docs/DESIGN.md, "DFAOIT's recipe")
//   C = f(x) + T_all * C_bg, where f predicts the whole transparent colour (sigmoid output).
// Pixels without fragments take the background only (f is not evaluated there).
#include "methods/neural/neural_inputs.glsl"

#include "methods/common/background.glsl"

bool networkApplies(PixelSums s) { return s.count >= 0.5; }

// Colour inputs x[1..9]; sum a C (x[4..6]) is scaled with them but does not set the pixel's
// scale (network_hdr.glsl).
#define STARNT_NN_FIRST_COLOUR_INPUT 1
#define STARNT_NN_COLOUR_INPUT_END 10
#define STARNT_NN_SCALE_SKIP_BEGIN 4
#define STARNT_NN_SCALE_SKIP_END 7

void networkInputs(PixelSums s, out float x[STARNT_NN_INPUTS]) {
    float tailCount = s.count - 2.0;
    float aAvg = 0.0;
    vec3 cAvg = vec3(0.0);
    if (tailCount > 0.5) {
        aAvg = max(tailAlphaSum(s), 0.0) / tailCount;
        cAvg = max(s.sumColor - s.c1 - s.c2, vec3(0.0)) / tailCount;
    }
    vec3 exact2 = exactTwo(s);
    x[0] = aAvg;
    x[1] = cAvg.r;
    x[2] = cAvg.g;
    x[3] = cAvg.b;
    x[4] = s.sumAlphaColor.r;
    x[5] = s.sumAlphaColor.g;
    x[6] = s.sumAlphaColor.b;
    x[7] = exact2.r;
    x[8] = exact2.g;
    x[9] = exact2.b;
#if STARNT_NN_INPUTS > 10
    x[10] = 1.0 - (1.0 - s.a1) * (1.0 - s.a2);
    x[11] = s.count;
#endif
}

vec3 compositePixel(PixelSums s, vec3 networkOutput) {
    if (s.count < 0.5) return background();
    return networkOutput + s.transmittance * background();
}
