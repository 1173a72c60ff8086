// Mean squared error of sRGB-encoded values (docs/DESIGN.md, "Benchmark").
#include "starnt/error.hpp"
#include "starnt/tools/metrics.hpp"

#include <algorithm>

namespace starnt {

namespace {
std::string sizeText(const Image& im) { return std::to_string(im.width) + "x" + std::to_string(im.height); }
}  // namespace

// Also throws starnt::Error when the images are empty (the mean over no pixels is undefined).
double mseSrgb(const Image& reference, const Image& test) {
    if (reference.width != test.width || reference.height != test.height)
        throw Error("mse: image sizes differ: reference " + sizeText(reference) + ", test " + sizeText(test));
    if (reference.pixelCount() == 0) throw Error("mse: empty images (" + sizeText(reference) + ")");
    if (reference.rgba.size() != reference.pixelCount() * 4 || test.rgba.size() != test.pixelCount() * 4)
        throw Error("mse: pixel buffer size does not match the image size");
    double sum = 0.0;
    const size_t n = reference.pixelCount();
    for (size_t i = 0; i < n; ++i) {
        for (int c = 0; c < 3; ++c) {
            const double a = linearToSrgb(std::clamp(reference.rgba[i * 4 + c], 0.0f, 1.0f));
            const double b = linearToSrgb(std::clamp(test.rgba[i * 4 + c], 0.0f, 1.0f));
            sum += (a - b) * (a - b);
        }
    }
    return sum / double(n * 3);
}

}  // namespace starnt
