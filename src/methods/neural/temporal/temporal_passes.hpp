// What the temporal full-screen passes share (reprojector.cpp, corrected_frames.cpp): their programs,
// built from this folder over the full-screen triangle, and a framebuffer drawing into one texture.
#pragma once
#include <string>

#include "gl/gl_util.hpp"
#include "gl/shader.hpp"
#include "starnt/error.hpp"

namespace starnt::temporal {

inline gl::Program buildTemporalPass(const char* label, const char* file, const std::string& defines = {}) {
    return gl::buildProgram(label, gl::embeddedSource("methods/common/fullscreen.vert.glsl"),
                            gl::embeddedSource(std::string("methods/neural/temporal/") + file), defines);
}

// Binds `framebuffer` (created on first use) drawing into `texture`, attached on every call (a
// texture name cached across calls could have been deleted and reused), with a width x height
// viewport and no depth test, blending or scissor. Throws starnt::Error if `texture` cannot be drawn into.
inline void drawIntoTexture(gl::FramebufferHandle& framebuffer, GLuint texture, int width, int height) {
    if (!framebuffer) framebuffer = gl::makeFramebufferName();
    if (gl::attachTexture(framebuffer.id(), GL_COLOR_ATTACHMENT0, texture) != GL_FRAMEBUFFER_COMPLETE) {
        throw Error("temporal frames: the output texture is not colour-renderable");
    }
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer.id());
    glViewport(0, 0, width, height);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
}

}  // namespace starnt::temporal
