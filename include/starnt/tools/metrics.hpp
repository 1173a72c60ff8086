// Image-quality metrics: MSE and LDR-FLIP (Andersson et al. 2020, "FLIP: A Difference Evaluator for
// Alternating Images"), both computed from linear-light Images.
#pragma once
#include "starnt/tools/image.hpp"

namespace starnt {

// Mean over pixels and RGB channels of the squared difference of sRGB-encoded values, each
// clamped to [0, 1]. Alpha is ignored. Throws starnt::Error when the sizes differ.
double mseSrgb(const Image& reference, const Image& test);

struct FlipResult {
    double mean = 0.0;  // mean LDR-FLIP error over all pixels, in [0, 1]
    Image errorMap;     // per-pixel FLIP error in R=G=B, alpha 1 (linear values in [0, 1])
};

// Pixels per degree accepted by flip(): 1 (a 1-pixel feature spans a degree: a very coarse view)
// to 1000 (far beyond any display: 8K at arm's length is ~150). Outside, the filters either vanish
// or grow to thousands of pixels (1e8 ran for minutes, 1e12 overflowed the radius).
inline constexpr double kFlipMinPixelsPerDegree = 1.0;
inline constexpr double kFlipMaxPixelsPerDegree = 1000.0;

// LDR-FLIP with the paper's default viewing conditions expressed as pixels per degree
// (67.02 = 0.7 m from a 0.7 m wide 3840-pixel monitor). Inputs are clamped to [0, 1] and
// treated as linear RGB. Throws starnt::Error when the sizes differ or an image is empty.
// Throws starnt::Error for pixelsPerDegree outside kFlipMinPixelsPerDegree..kFlipMaxPixelsPerDegree.
// Works in bands of rows: besides the inputs (and the map), memory stays at a few hundred MB for
// any image size.
FlipResult flip(const Image& reference, const Image& test, double pixelsPerDegree = 67.02);
// The same mean without the error map (one full-size image less).
double flipMean(const Image& reference, const Image& test, double pixelsPerDegree = 67.02);

// The FLIP error map coloured with the magma colour map (as the FLIP paper shows it), ready to save.
Image flipHeatmap(const Image& errorMap);

}  // namespace starnt
