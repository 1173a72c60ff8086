// Clears of colour targets that cost what they should on every driver (docs/DESIGN.md, "Findings
// on Mesa llvmpipe": clears). A GPU clears by metadata, so glClearBuffer* is the fastest there.
// Mesa's llvmpipe writes every texel, and 16-byte texels one small copy at a time: an RGBA32F
// target at 1280x720 takes 1.6-2.8 ms to clear, where copying the same value from a strip of
// texels (glCopyImageSubData) takes 0.2-0.3 ms. So on a software rasteriser a clear of a 16-byte
// format becomes copies from a strip that holds the value; everything else stays glClearBuffer*.
#pragma once
#include <epoxy/gl.h>

#include <array>
#include <cstddef>
#include <vector>

#include "gl/gl_util.hpp"

namespace starnt::gl {

class TargetClears {
public:
    // Auto: copies on a software rasteriser (llvmpipe, softpipe), clears elsewhere. Copy and Clear
    // force one way (tests). stripWidth x stripRows: the strip copied from (tests make it small to
    // check the tiling).
    enum class Path { Auto, Clear, Copy };
    explicit TargetClears(Path path = Path::Auto, int stripWidth = 2048, int stripRows = 16);

    // What glClearBufferfv(GL_COLOR, drawBuffer, value) does to the bound draw framebuffer: the
    // scissor box when the scissor test is on, the whole attachment otherwise. It is that call
    // wherever a copy would differ or gain nothing: texels of other than 16 bytes, a colour mask,
    // a renderbuffer, a layer or a level other than 0, a texture without immutable storage, an
    // integer target (colorUint clears those).
    void color(GLint drawBuffer, const float value[4]);
    // The same for an unsigned integer target: glClearBufferuiv(GL_COLOR, drawBuffer, value).
    void colorUint(GLint drawBuffer, const GLuint value[4]);

    // Bytes the strips hold (one per format and value met; 512 KiB for RGBA32F).
    size_t bytes() const;

private:
    // A clear value: its bits, and whether they are floats or unsigned integers.
    struct Value {
        std::array<GLuint, 4> bits{};
        bool integer = false;
        bool operator==(const Value&) const = default;
    };
    struct Strip {
        GLenum format = 0;
        Value value;
        Texture2D texture;
    };
    bool copies();
    void clear(GLint drawBuffer, const Value& value);
    // False where a copy cannot stand in for the clear; then nothing was written.
    bool copyInto(GLenum attachment, const Value& value);
    bool copyTo(GLuint texture, GLuint activeUnit, const Value& value);
    const Strip& strip(GLenum format, const Value& value);
    static void clearBuffer(GLint drawBuffer, const Value& value);

    static constexpr size_t kMaxStrips = 4;
    Path path_;
    int stripWidth_, stripRows_;
    int software_ = -1;  // unknown until the first clear (a context is current then)
    std::vector<Strip> strips_;
};

}  // namespace starnt::gl
