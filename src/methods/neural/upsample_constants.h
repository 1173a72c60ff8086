// Joint bilateral upsampling of the reduced passes (upsample.glsl, CPU reference upsample_cpu.cpp).
// Keep it to #defines: it is included from C++ and GLSL.
#ifndef STARNT_UPSAMPLE_CONSTANTS_H
#define STARNT_UPSAMPLE_CONSTANTS_H

// Width of the depth kernel, relative to the pixel's own view distance: a tap whose nearest surface
// lies r = (d_tap - d) / (SIGMA d) away keeps exp(-r^2) of its bilinear weight.
#ifndef STARNT_UPSAMPLE_SIGMA
#define STARNT_UPSAMPLE_SIGMA 0.05
#endif
// Every tap at least this agreement: the plain bilinear weights (one filtered fetch per target).
#define STARNT_UPSAMPLE_PLAIN_AGREEMENT 0.99
// Below this total kept weight (all four taps on other surfaces) the plain bilinear weights apply.
#define STARNT_UPSAMPLE_MIN_WEIGHT 1e-3

#endif
