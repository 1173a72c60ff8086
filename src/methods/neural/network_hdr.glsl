// The network on colours above 1 (linear HDR; docs/DESIGN.md, "HDR"): the networks were trained on
// colours in [0, 1], and every colour input of every kind is linear in the pixel's fragment colours
// (means and sums of a C), as is what the network predicts (a tail's colour, a correction of one,
// the whole transparent colour). So the colour inputs are divided by the pixel's scale k and the
// output multiplied by it (network_hdr.h states k), where the largest colour input exceeds 1 + 2^-8;
// for a pixel within [0, 1] nothing changes, nor where 16-bit sums round an LDR input a little
// above 1. CPU reference: nn::forwardInColourScale (features.cpp).
#include "methods/neural/network_hdr.h"
// A method's composite may set the inputs that are colours: from STARNT_NN_FIRST_COLOUR_INPUT up to
// STARNT_NN_COLOUR_INPUT_END, those in [STARNT_NN_SCALE_SKIP_BEGIN, STARNT_NN_SCALE_SKIP_END) scaled
// but not setting k (DFAOIT's sum a C, above 1 in LDR pixels too).
#ifndef STARNT_NN_FIRST_COLOUR_INPUT
#define STARNT_NN_FIRST_COLOUR_INPUT 2
#endif
#if !defined(STARNT_NN_COLOUR_INPUT_END) || STARNT_NN_COLOUR_INPUT_END > STARNT_NN_INPUTS
#undef STARNT_NN_COLOUR_INPUT_END
#define STARNT_NN_COLOUR_INPUT_END STARNT_NN_INPUTS
#endif
#ifndef STARNT_NN_SCALE_SKIP_BEGIN
#define STARNT_NN_SCALE_SKIP_BEGIN STARNT_NN_INPUTS
#define STARNT_NN_SCALE_SKIP_END STARNT_NN_INPUTS
#endif

vec3 evaluateNetwork(PixelSums s) {
    float x[STARNT_NN_INPUTS];
    networkInputs(s, x);
    float peak = 1.0;
    for (int i = STARNT_NN_FIRST_COLOUR_INPUT; i < STARNT_NN_COLOUR_INPUT_END; ++i) {
        if (i < STARNT_NN_SCALE_SKIP_BEGIN || i >= STARNT_NN_SCALE_SKIP_END) peak = max(peak, x[i]);
    }
    if (!(peak > float(STARNT_NN_HDR_THRESHOLD))) return nnEvaluate(x);
    float k = peak / (float(STARNT_NN_HDR_TARGET) + (1.0 - float(STARNT_NN_HDR_TARGET)) / peak);
    for (int i = STARNT_NN_FIRST_COLOUR_INPUT; i < STARNT_NN_COLOUR_INPUT_END; ++i) x[i] /= k;
    return k * nnEvaluate(x);
}
