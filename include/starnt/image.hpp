// Linear-light RGBA float images and their files.
//
// In memory an Image is always linear RGB + alpha, row 0 at the top. PNG files are 8-bit sRGB
// (encoded on write, decoded on read); EXR files hold linear float values. Writes are atomic: the
// file is written under a temporary name in the same folder and renamed, so a failed write never
// leaves a partial file behind.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

namespace starnt {

struct Image {
    int width = 0;
    int height = 0;
    std::vector<float> rgba;  // width * height * 4, linear, row-major, top row first

    Image() = default;
    Image(int w, int h, float fill = 0.0f) : width(w), height(h), rgba(size_t(w) * size_t(h) * 4, fill) {}
    size_t pixelCount() const { return size_t(width) * size_t(height); }
    float* pixel(int x, int y) { return &rgba[(size_t(y) * size_t(width) + size_t(x)) * 4]; }
    const float* pixel(int x, int y) const { return &rgba[(size_t(y) * size_t(width) + size_t(x)) * 4]; }
};

// sRGB transfer functions (IEC 61966-2-1), scalar, no clamping of the input beyond [0, inf).
float linearToSrgb(float linear);
float srgbToLinear(float encoded);

// Reads PNG (sRGB, decoded to linear) or EXR (linear). Throws starnt::Error on a missing,
// unreadable or unsupported file.
Image loadImage(const std::string& path);

// Writes by extension (.png or .exr). Throws starnt::Error; never leaves a partial file.
void saveImage(const Image& image, const std::string& path);
void savePng(const Image& image, const std::string& path);  // sRGB 8-bit RGBA
void saveExr(const Image& image, const std::string& path);  // linear float RGBA

// Writes `contents` to `path` atomically (temp file + rename). Used for every output file.
void writeFileAtomic(const std::string& path, const std::string& contents);

}  // namespace starnt
