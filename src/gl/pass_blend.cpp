#include "gl/pass_blend.hpp"

#include <epoxy/gl.h>

#include <algorithm>

#include "gl/gl_util.hpp"
#include "starnt/error.hpp"

namespace starnt::gl {
namespace {

// The class of a target from what the driver says of its channels: component type and the widest
// channel (RGB10_A2 is "unorm10", R11F_G11F_B10F "float11").
std::string formatClass(GLint componentType, int widestBits) {
    const std::string bits = std::to_string(widestBits);
    switch (componentType) {
        case GL_FLOAT: return "float" + bits;
        case GL_UNSIGNED_NORMALIZED: return "unorm" + bits;
        case GL_SIGNED_NORMALIZED: return "snorm" + bits;
        case GL_UNSIGNED_INT: return "uint" + bits;
        case GL_INT: return "int" + bits;
        default: return "other" + bits;
    }
}

// One colour target of the bound draw framebuffer, as its attachment describes it.
struct DrawTarget {
    GLuint drawBuffer = 0;
    GLint componentType = GL_NONE;
    GLint bits[4] = {0, 0, 0, 0};  // red, green, blue, alpha
};

// Calls `visit(target)` for every draw buffer of the bound draw framebuffer that has an
// attachment (none for framebuffer 0).
template <class Visit>
void forEachDrawTarget(const Visit& visit) {
    GLint framebuffer = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &framebuffer);
    if (framebuffer == 0) return;
    GLint maxDrawBuffers = 0;
    glGetIntegerv(GL_MAX_DRAW_BUFFERS, &maxDrawBuffers);
    const GLenum sizes[4] = {GL_FRAMEBUFFER_ATTACHMENT_RED_SIZE, GL_FRAMEBUFFER_ATTACHMENT_GREEN_SIZE,
                             GL_FRAMEBUFFER_ATTACHMENT_BLUE_SIZE, GL_FRAMEBUFFER_ATTACHMENT_ALPHA_SIZE};
    for (GLint i = 0; i < maxDrawBuffers; ++i) {
        GLint attachment = GL_NONE;
        glGetIntegerv(GL_DRAW_BUFFER0 + i, &attachment);
        if (attachment == GL_NONE) continue;
        GLint objectType = GL_NONE;
        glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, GLenum(attachment), GL_FRAMEBUFFER_ATTACHMENT_OBJECT_TYPE,
                                              &objectType);
        if (objectType == GL_NONE) continue;
        DrawTarget target;
        target.drawBuffer = GLuint(i);
        for (int c = 0; c < 4; ++c) {
            glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, GLenum(attachment), sizes[c], &target.bits[c]);
        }
        glGetFramebufferAttachmentParameteriv(GL_DRAW_FRAMEBUFFER, GLenum(attachment), GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE,
                                              &target.componentType);
        visit(target);
    }
}

}  // namespace

PassBlend describeBoundColourTargets() {
    PassBlend out;
    forEachDrawTarget([&](const DrawTarget& target) {
        GLboolean mask[4] = {GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE};
        glGetBooleani_v(GL_COLOR_WRITEMASK, target.drawBuffer, mask);
        int written = 0;
        for (int c = 0; c < 4; ++c) {
            out.targetBitsPerPixel += target.bits[c];
            if (mask[c]) written += target.bits[c];
        }
        if (written == 0) return;
        const int widest = *std::max_element(target.bits, target.bits + 4);
        out.bytesByClass[formatClass(target.componentType, widest)] += double(written) / 8.0;
    });
    return out;
}

void checkFloatBlend(const std::string& pass) {
    if (floatBlendAvailable() || !blendsFloat32Target()) return;
    throw Error(pass + " blends 32-bit float targets, which needs GL_EXT_float_blend, and this OpenGL ES context lacks it. "
                "Methods that blend 16-bit targets run there: dfaoit, starnt, hybrid and starnt-residual without temporal "
                "frames, kbuffer-moments, recommended where it renders kbuffer-moments, and abuffer");
}

bool floatBlendAvailable() { return !isEs() || epoxy_has_gl_extension("GL_EXT_float_blend"); }

bool blendsFloat32Target() {
    bool blends = false;
    forEachDrawTarget([&](const DrawTarget& target) {
        blends = blends || (target.componentType == GL_FLOAT && target.bits[0] == 32 && glIsEnabledi(GL_BLEND, target.drawBuffer));
    });
    return blends;
}

}  // namespace starnt::gl
