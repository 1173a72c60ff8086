// What a geometry pass's fragments write into its colour targets, read off the GL state at the
// moment the pass draws (docs/DESIGN.md, "Cost on a GPU"): per format class, the bytes each
// fragment blends, fetches or writes (the channels its write masks let through), and the bits a
// pixel of all bound colour targets hold. On a GPU a pass's time follows these bytes (and on a
// tile-based GPU its tile size follows the bits), where llvmpipe's follows the shader's work; the
// description is taken from the driver, so it cannot drift from what a method binds.
#pragma once
#include <map>
#include <string>

namespace starnt::gl {

struct PassBlend {
    // Format class ("float32", "float16", "unorm16", "unorm10", "unorm8", "uint32", ...) -> bytes a
    // fragment writes into targets of that class (read-modify-write through blending or
    // framebuffer fetch, or a plain write).
    std::map<std::string, double> bytesByClass;
    int targetBitsPerPixel = 0;  // every bound colour target, written or not
    double bytes() const {
        double sum = 0;
        for (const auto& [cls, b] : bytesByClass) sum += b;
        return sum;
    }
    double bytesOf(const std::string& cls) const {
        auto it = bytesByClass.find(cls);
        return it == bytesByClass.end() ? 0.0 : it->second;
    }
    bool operator==(const PassBlend&) const = default;
};

// The colour targets of the bound draw framebuffer, as a fragment drawn now would write them
// (framebuffer 0: nothing is described). Changes no GL state.
PassBlend describeBoundColourTargets();

// Whether the current context blends 32-bit float colour targets: desktop GL always, OpenGL ES
// with GL_EXT_float_blend (which ES 3.2 leaves optional).
bool floatBlendAvailable();
// True when a fragment drawn now would blend into a 32-bit float target of the bound draw
// framebuffer (blending on for a draw buffer whose attachment has 32-bit float channels).
bool blendsFloat32Target();
// Throws starnt::Error naming `pass` and GL_EXT_float_blend where a draw now would blend a 32-bit
// float target that the context cannot (an INVALID_OPERATION, and a silently wrong frame).
void checkFloatBlend(const std::string& pass);

}  // namespace starnt::gl
