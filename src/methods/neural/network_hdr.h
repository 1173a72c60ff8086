// The networks on colours above 1 (docs/DESIGN.md, "HDR"): shared by network_hdr.glsl and its CPU
// reference nn::forwardInColourScale (included from C++ and GLSL; keep it to #defines).
//
// A pixel whose largest colour input p exceeds STARNT_NN_HDR_THRESHOLD has its colour inputs divided
// by k = p / (t + (1 - t) / p), t = STARNT_NN_HDR_TARGET, and the network's output multiplied by k:
// the largest input becomes t + (1 - t) / p, 1 at p = 1 and t for a pixel far above 1. Dividing by
// k = p instead (largest input exactly 1) put every HDR pixel at the brightest edge of the training
// data: DFAOIT, whose sigmoid predicts the whole colour, erred 2.3x its LDR twin there.
#ifndef STARNT_NETWORK_HDR_H
#define STARNT_NETWORK_HDR_H

// Above 1 by 2^-8, so that 16-bit sums rounding an LDR input a little above 1 change nothing.
#define STARNT_NN_HDR_THRESHOLD (1.0 + 1.0 / 256.0)
#define STARNT_NN_HDR_TARGET 0.5

#endif
