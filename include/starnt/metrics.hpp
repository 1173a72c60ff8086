// Image-quality metrics: MSE and LDR-FLIP (Andersson et al. 2020, "FLIP: A Difference Evaluator for
// Alternating Images"), both computed from linear-light Images.
#pragma once
#include "starnt/image.hpp"

namespace starnt {

// Mean over pixels and RGB channels of the squared difference of sRGB-encoded values, each
// clamped to [0, 1]. Alpha is ignored. Throws starnt::Error when the sizes differ.
double mseSrgb(const Image& reference, const Image& test);

struct FlipResult {
    double mean = 0.0;  // mean LDR-FLIP error over all pixels, in [0, 1]
    Image errorMap;     // per-pixel FLIP error in R=G=B, alpha 1 (linear values in [0, 1])
};

// LDR-FLIP with the paper's default viewing conditions expressed as pixels per degree
// (67.02 = 0.7 m from a 0.7 m wide 3840-pixel monitor). Inputs are clamped to [0, 1] and
// treated as linear RGB. Throws starnt::Error when the sizes differ or an image is empty.
FlipResult flip(const Image& reference, const Image& test, double pixelsPerDegree = 67.02);

// The FLIP error map coloured with the magma colour map (as the FLIP paper shows it), ready to save.
Image flipHeatmap(const Image& errorMap);

}  // namespace starnt
