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

// Largest image loadImage reads: 16384 pixels on a side and 8192 x 8192 pixels in all (an image
// in memory takes 16 bytes a pixel: 1 GiB at the limit; `compare` holds two).
inline constexpr int kMaxImageSide = 16384;
inline constexpr long long kMaxImagePixels = 8192LL * 8192LL;

// Reads PNG (sRGB, decoded to linear) or EXR (linear). Throws starnt::Error on a missing,
// unreadable, unsupported or too large (see above) file, and on a path that is not a regular file.
Image loadImage(const std::string& path);

// Writes by extension (.png or .exr). Throws starnt::Error; never leaves a partial file.
void saveImage(const Image& image, const std::string& path);
void savePng(const Image& image, const std::string& path);  // sRGB 8-bit RGBA
void saveExr(const Image& image, const std::string& path);  // linear float RGBA

// Writes `contents` to `path` atomically (temp file + rename). Used for every output file.
void writeFileAtomic(const std::string& path, const std::string& contents);

// The bytes saveImage would write to `path` (format by extension).
std::string encodeImage(const Image& image, const std::string& path);

// Output files of one command that appear together or not at all. stage() writes each file at
// once under a temporary name beside it (PATH.tmp-PID); commit() renames them all into place;
// an OutputFiles destroyed without commit() (an error on the way) removes its temporaries. A
// rename failing during commit() removes the files already renamed, so none is left.
class OutputFiles {
public:
    OutputFiles() = default;
    OutputFiles(const OutputFiles&) = delete;
    OutputFiles& operator=(const OutputFiles&) = delete;
    ~OutputFiles();
    void stage(const std::string& path, const std::string& contents);
    void stageImage(const Image& image, const std::string& path) { stage(path, encodeImage(image, path)); }
    void commit();
    size_t size() const { return staged_.size(); }

private:
    struct Entry {
        std::string temporary, path;
    };
    std::vector<Entry> staged_;
};

}  // namespace starnt
