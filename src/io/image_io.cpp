// Image files: PNG (8-bit sRGB, via stb) and EXR (32-bit float linear, via OpenEXR), sRGB transfer
// functions and the atomic file write every output goes through.
#include "starnt/error.hpp"
#include "starnt/tools/image.hpp"
#include "io/image_limits.hpp"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStdIO.h>
#include <stb_image.h>
#include <stb_image_write.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fcntl.h>
#include <fstream>
#include <iterator>
#include <memory>
#include <map>
#include <sstream>
#include <sys/stat.h>
#include <unistd.h>

namespace starnt {

namespace {

std::string lowerExtension(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    const size_t dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
    std::string ext = path.substr(dot);
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

void checkWritable(const Image& image, const std::string& path) {
    if (image.width <= 0 || image.height <= 0)
        throw Error("cannot write " + path + ": empty image (" + std::to_string(image.width) + "x" +
                    std::to_string(image.height) + ")");
    if (image.rgba.size() != image.pixelCount() * 4)
        throw Error("cannot write " + path + ": pixel buffer holds " + std::to_string(image.rgba.size()) +
                    " floats, expected " + std::to_string(image.pixelCount() * 4));
}

std::string encodePng(const Image& image, const std::string& path);
std::string encodeExr(const Image& image, const std::string& path);

long long gImagePixelBudget = kMaxImagePixels;  // io/image_limits.hpp

void checkImageDimensions(long long w, long long h, const std::string& path) {
    // Sides first: an EXR data window gives sides up to 2^32, whose product overflows long long.
    if (w <= kMaxImageSide && h <= kMaxImageSide && w * h > gImagePixelBudget && w * h <= kMaxImagePixels) {
        throw Error("image " + path + " is " + std::to_string(w) + "x" + std::to_string(h) +
                    ": over the decode budget of " + std::to_string(gImagePixelBudget) + " pixels set for fuzzing");
    }
    if (w > kMaxImageSide || h > kMaxImageSide || w * h > kMaxImagePixels)
        throw Error("image " + path + " is " + std::to_string(w) + "x" + std::to_string(h) +
                    ": larger than this tool reads (at most " + std::to_string(kMaxImageSide) + " pixels on a side and " +
                    std::to_string(kMaxImagePixels) + " pixels in all, i.e. 8192x8192)");
}

std::string readWholeFile(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error("cannot open image " + path + ": " + std::strerror(errno));
    std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) throw Error("cannot read image " + path);
    return data;
}

Image loadPng(const std::string& path) {
    const std::string data = readWholeFile(path);
    if (data.empty()) throw Error("cannot read PNG " + path + ": file is empty");
    const auto* bytes = reinterpret_cast<const stbi_uc*>(data.data());
    const int len = int(std::min<size_t>(data.size(), size_t(INT32_MAX)));
    int w = 0, h = 0, comp = 0;
    if (!stbi_info_from_memory(bytes, len, &w, &h, &comp))
        throw Error("cannot read PNG " + path + ": " + stbi_failure_reason());
    checkImageDimensions(w, h, path);

    Image img;
    if (stbi_is_16_bit_from_memory(bytes, len)) {
        std::unique_ptr<stbi_us, void (*)(void*)> px(stbi_load_16_from_memory(bytes, len, &w, &h, &comp, 4),
                                                     stbi_image_free);
        if (!px) throw Error("cannot read PNG " + path + ": " + stbi_failure_reason());
        img = Image(w, h);
        for (size_t i = 0; i < img.rgba.size(); ++i) {
            const float v = float(px.get()[i]) / 65535.0f;
            img.rgba[i] = (i % 4 == 3) ? v : srgbToLinear(v);
        }
    } else {
        std::unique_ptr<stbi_uc, void (*)(void*)> px(stbi_load_from_memory(bytes, len, &w, &h, &comp, 4),
                                                     stbi_image_free);
        if (!px) throw Error("cannot read PNG " + path + ": " + stbi_failure_reason());
        float lut[256];
        for (int v = 0; v < 256; ++v) lut[v] = srgbToLinear(float(v) / 255.0f);
        img = Image(w, h);
        for (size_t i = 0; i < img.rgba.size(); ++i) {
            const stbi_uc v = px.get()[i];
            img.rgba[i] = (i % 4 == 3) ? float(v) / 255.0f : lut[v];
        }
    }
    if (img.width <= 0 || img.height <= 0) throw Error("cannot read PNG " + path + ": empty image");
    return img;
}

// Validates the attribute list of an OpenEXR header before OpenEXR opens the file (magic,
// version, then per attribute: name NUL, type NUL, int32 size, value; an empty name ends a header;
// multi-part files have one header per part and an empty one after the last).
// Why: OpenEXR allocates by what a header declares (an unknown type's size; a preview's width x
// height; line buffers by the data window) and reads the types it knows by their structure, not by
// the declared size, carrying on from wherever that ends. A header whose sizes lie is therefore
// read differently by OpenEXR and by any check: fuzz/fuzz_image found 300-byte files that made it
// allocate 2 GB that way. So every declared size must be true: fixed-size types must have their
// size, a channel list must end exactly at its declared size, a preview must hold width x height
// pixels, and nothing may run past the end of the file. The data window must pass
// checkImageDimensions. A header that ends early is left to OpenEXR, which reports it.
void checkExrHeader(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error("cannot open image " + path + ": " + std::strerror(errno));
    in.seekg(0, std::ios::end);
    const std::streamoff fileSize = in.tellg();
    in.seekg(0);
    unsigned char head[8] = {};
    if (!in.read(reinterpret_cast<char*>(head), 8) || head[0] != 0x76 || head[1] != 0x2f || head[2] != 0x31 ||
        head[3] != 0x01) {
        return;  // too short or not an EXR signature: OpenEXR names the problem
    }
    const bool multipart = (head[5] & 0x10) != 0;  // version field bit 12
    // The sizes of the fixed-size attribute types OpenEXR 3 knows.
    static const std::map<std::string, int32_t> kFixedSizes = {
        {"box2i", 16}, {"box2f", 16}, {"chromaticities", 32}, {"compression", 1}, {"double", 8}, {"envmap", 1},
        {"float", 4}, {"int", 4}, {"keycode", 28}, {"lineOrder", 1}, {"m33f", 36}, {"m33d", 72}, {"m44f", 64},
        {"m44d", 128}, {"rational", 8}, {"tiledesc", 9}, {"timecode", 8}, {"v2i", 8}, {"v2f", 8}, {"v2d", 16},
        {"v3i", 12}, {"v3f", 12}, {"v3d", 24}, {"deepImageState", 1}};
    auto fail = [&](const std::string& name, const std::string& what) {
        throw Error("cannot read EXR " + path + ": header attribute '" + name + "' " + what);
    };
    auto readName = [&](std::string& out) {
        out.clear();
        return bool(std::getline(in, out, '\0'));
    };
    auto readInt32 = [&](int32_t& v) {
        unsigned char b[4] = {};
        if (!in.read(reinterpret_cast<char*>(b), 4)) return false;
        v = int32_t(uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24);
        return true;
    };
    for (int part = 0;; ++part) {
        for (bool firstAttribute = true;; firstAttribute = false) {
            std::string name, type;
            if (!readName(name)) return;
            if (name.empty()) {
                if (firstAttribute && multipart && part > 0) return;  // the empty header after the last part
                break;
            }
            int32_t size = 0;
            if (!readName(type) || !readInt32(size)) return;
            const std::streamoff start = in.tellg(), left = fileSize - start;
            if (size < 0 || std::streamoff(size) > left) {
                fail(name, "claims " + std::to_string(size) + " bytes, but the file has " + std::to_string(left) + " left");
            }
            if (auto fixed = kFixedSizes.find(type); fixed != kFixedSizes.end() && size != fixed->second) {
                fail(name, "of type " + type + " has " + std::to_string(size) + " bytes instead of " +
                               std::to_string(fixed->second));
            }
            if (type == "chlist") {
                std::string channel;  // per channel: name NUL, then 16 bytes; an empty name ends the list
                while (readName(channel) && !channel.empty()) in.seekg(16, std::ios::cur);
                if (!in) return;
                if (in.tellg() - start != std::streamoff(size)) {
                    fail(name, "(a channel list) declares " + std::to_string(size) + " bytes but holds " +
                                   std::to_string(in.tellg() - start));
                }
                continue;
            }
            if (type == "preview") {
                int32_t w = 0, h = 0;
                if (size < 8 || !readInt32(w) || !readInt32(h)) return;
                // w x h fits in long long; 4 x that may not, so compare against the size first.
                const long long pixels = (long long)w * h;
                if (w < 0 || h < 0 || pixels > (size - 8) / 4 || 8 + 4 * pixels != size) {
                    fail(name, "(a preview of " + std::to_string(w) + "x" + std::to_string(h) + ") has " +
                                   std::to_string(size) + " bytes");
                }
                in.seekg(start + size);
                continue;
            }
            if (name == "dataWindow" && type == "box2i") {
                int32_t box[4] = {};
                for (int32_t& v : box)
                    if (!readInt32(v)) return;
                const long long w = (long long)box[2] - box[0] + 1, h = (long long)box[3] - box[1] + 1;
                if (w > 0 && h > 0) checkImageDimensions(w, h, path);  // before OpenEXR sizes buffers by it
                continue;
            }
            in.seekg(size, std::ios::cur);
        }
        if (!multipart) return;
    }
}

Image loadExr(const std::string& path) {
    checkExrHeader(path);
    try {
        Imf::InputFile file(path.c_str());
        const Imath::Box2i dw = file.header().dataWindow();
        const int w = dw.max.x - dw.min.x + 1;
        const int h = dw.max.y - dw.min.y + 1;
        if (w <= 0 || h <= 0) throw Error("cannot read EXR " + path + ": empty data window");
        checkImageDimensions(w, h, path);
        Image img(w, h);
        const Imf::ChannelList& channels = file.header().channels();
        // Luminance-only files (channel Y, no R/G/B) are read as grey.
        const bool grey = !channels.findChannel("R") && !channels.findChannel("G") && !channels.findChannel("B") &&
                          channels.findChannel("Y");
        const size_t xStride = 4 * sizeof(float);
        const size_t yStride = size_t(w) * xStride;
        // Slices are addressed with data-window coordinates. Slice::Make offsets the pointer by the
        // window's origin itself: computing that base here overflowed the pointer for windows far
        // from the origin (undefined behaviour; UBSan, found by fuzz/fuzz_image).
        Imf::FrameBuffer fb;
        const char* names[4] = {"R", "G", "B", "A"};
        for (int c = 0; c < 4; ++c) {
            const char* name = (grey && c < 3) ? "Y" : names[c];
            fb.insert(name, Imf::Slice::Make(Imf::FLOAT, img.rgba.data() + c, dw, xStride, yStride, 1, 1,
                                             c == 3 ? 1.0 : 0.0));
        }
        file.setFrameBuffer(fb);
        file.readPixels(dw.min.y, dw.max.y);
        return img;
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error("cannot read EXR " + path + ": " + e.what());
    }
}

void appendToString(void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), size_t(size));
}

}  // namespace

float linearToSrgb(float linear) {
    if (!(linear > 0.0f)) return 0.0f;  // also maps NaN to 0
    // Evaluated in double so that 1 maps to exactly 1 (and back).
    if (linear <= 0.0031308f) return float(12.92 * double(linear));
    return float(1.055 * std::pow(double(linear), 1.0 / 2.4) - 0.055);
}

float srgbToLinear(float encoded) {
    if (!(encoded > 0.0f)) return 0.0f;
    if (encoded <= 0.04045f) return float(double(encoded) / 12.92);
    return float(std::pow((double(encoded) + 0.055) / 1.055, 2.4));
}

Image loadImage(const std::string& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) throw Error("cannot open image " + path + ": " + std::strerror(errno));
    if (S_ISDIR(st.st_mode)) throw Error("cannot read image " + path + ": is a directory, not an image file");
    if (!S_ISREG(st.st_mode)) throw Error("cannot read image " + path + ": not a regular file");
    const std::string ext = lowerExtension(path);
    if (ext == ".png") return loadPng(path);
    if (ext == ".exr") return loadExr(path);
    throw Error("cannot read image " + path + ": unsupported extension '" + ext + "' (expected .png or .exr)");
}

void saveImage(const Image& image, const std::string& path) { writeFileAtomic(path, encodeImage(image, path)); }

void savePng(const Image& image, const std::string& path) { writeFileAtomic(path, encodePng(image, path)); }

void saveExr(const Image& image, const std::string& path) { writeFileAtomic(path, encodeExr(image, path)); }

std::string encodeImage(const Image& image, const std::string& path) {
    const std::string ext = lowerExtension(path);
    if (ext == ".png") return encodePng(image, path);
    if (ext == ".exr") return encodeExr(image, path);
    throw Error("cannot write image " + path + ": unsupported extension '" + ext + "' (expected .png or .exr)");
}

namespace {

std::string encodePng(const Image& image, const std::string& path) {
    checkWritable(image, path);
    std::vector<unsigned char> bytes(image.rgba.size());
    for (size_t i = 0; i < bytes.size(); ++i) {
        float v = std::clamp(image.rgba[i], 0.0f, 1.0f);  // NaN is mapped to 0 by linearToSrgb / below
        if (i % 4 != 3) v = linearToSrgb(v);
        if (!(v > 0.0f)) v = 0.0f;
        bytes[i] = static_cast<unsigned char>(std::lround(std::min(v, 1.0f) * 255.0f));
    }
    std::string encoded;
    if (!stbi_write_png_to_func(appendToString, &encoded, image.width, image.height, 4, bytes.data(),
                                image.width * 4))
        throw Error("cannot write PNG " + path + ": encoding failed");
    return encoded;
}

// EXR output holds 32-bit FLOAT R, G, B, A channels (ZIP compressed), so a round trip is exact.
std::string encodeExr(const Image& image, const std::string& path) {
    checkWritable(image, path);
    std::string encoded;
    try {
        Imf::Header header(image.width, image.height);
        header.compression() = Imf::ZIP_COMPRESSION;
        const char* names[4] = {"R", "G", "B", "A"};
        for (const char* n : names) header.channels().insert(n, Imf::Channel(Imf::FLOAT));
        Imf::FrameBuffer fb;
        const size_t xStride = 4 * sizeof(float);
        const size_t yStride = size_t(image.width) * xStride;
        char* base = const_cast<char*>(reinterpret_cast<const char*>(image.rgba.data()));
        for (int c = 0; c < 4; ++c) fb.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), xStride, yStride));
        Imf::StdOSStream stream;
        {
            Imf::OutputFile file(stream, header);
            file.setFrameBuffer(fb);
            file.writePixels(image.height);
        }
        encoded = stream.str();
    } catch (const std::exception& e) {
        throw Error("cannot write EXR " + path + ": " + e.what());
    }
    return encoded;
}

// Writes `contents` to `tmp` (created or truncated); on failure removes it and throws naming `path`.
void writeTemporary(const std::string& tmp, const std::string& path, const std::string& contents) {
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd < 0) throw Error("cannot write " + path + ": " + std::strerror(errno));
    auto fail = [&](const std::string& what, int err) {
        ::unlink(tmp.c_str());
        throw Error("cannot write " + path + ": " + what + ": " + std::strerror(err));
    };
    size_t done = 0;
    while (done < contents.size()) {
        const ssize_t n = ::write(fd, contents.data() + done, contents.size() - done);
        if (n < 0) {
            if (errno == EINTR) continue;
            const int err = errno;
            ::close(fd);
            fail("write failed", err);
        }
        done += size_t(n);
    }
    if (::close(fd) != 0) fail("close failed", errno);
}

std::string temporaryName(const std::string& path) { return path + ".tmp-" + std::to_string(::getpid()); }

}  // namespace

void writeFileAtomic(const std::string& path, const std::string& contents) {
    OutputFiles out;
    out.stage(path, contents);
    out.commit();
}

OutputFiles::~OutputFiles() {
    for (const Entry& e : staged_) ::unlink(e.temporary.c_str());
}

void OutputFiles::stage(const std::string& path, const std::string& contents) {
    const std::string tmp = temporaryName(path);
    writeTemporary(tmp, path, contents);
    for (const Entry& e : staged_)
        if (e.path == path) return;  // staged again: the temporary now holds the new contents
    staged_.push_back({tmp, path});
}

void OutputFiles::commit() {
    // A target that is a folder would fail its rename after others succeeded: refuse them all first.
    for (const Entry& e : staged_) {
        struct stat st {};
        if (::stat(e.path.c_str(), &st) == 0 && S_ISDIR(st.st_mode))
            throw Error("cannot write " + e.path + ": is a directory");
    }
    for (size_t i = 0; i < staged_.size(); ++i) {
        if (::rename(staged_[i].temporary.c_str(), staged_[i].path.c_str()) != 0) {
            const int err = errno;
            for (size_t k = 0; k < i; ++k) ::unlink(staged_[k].path.c_str());  // none or all
            const std::string failed = staged_[i].path;
            staged_.erase(staged_.begin(), staged_.begin() + std::ptrdiff_t(i));  // the rest are removed by ~OutputFiles
            throw Error("cannot write " + failed + ": rename failed: " + std::strerror(err));
        }
    }
    staged_.clear();
}

}  // namespace starnt

namespace starnt::detail {

void setImagePixelBudget(long long pixels) { gImagePixelBudget = pixels; }

}  // namespace starnt::detail
