#include "methods/neural/empty_pixels.hpp"

#include <glm/gtc/type_ptr.hpp>

#include "starnt/error.hpp"

namespace starnt {

EmptyPixelSkip::EmptyPixelSkip()
    : background_(gl::buildProgram("infer_background", gl::embeddedSource("methods/common/fullscreen.vert.glsl"),
                                   gl::embeddedSource("methods/neural/infer_background.frag.glsl"))) {}

void EmptyPixelSkip::bindCovered(GLuint colorTexture, GLuint pass1Depth, int width, int height) {
    if (!framebuffer_) framebuffer_ = gl::makeFramebufferName();
    // Attached on every call: the textures are the caller's and may have been reallocated.
    gl::attachTexture(framebuffer_.id(), GL_COLOR_ATTACHMENT0, colorTexture);
    if (gl::attachTexture(framebuffer_.id(), GL_DEPTH_ATTACHMENT, pass1Depth) != GL_FRAMEBUFFER_COMPLETE) {
        throw Error("internal: the output and pass-1 depth do not form a complete framebuffer");
    }
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
    glViewport(0, 0, width, height);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glDepthFunc(GL_GREATER);
}

void EmptyPixelSkip::fillEmpty(const glm::vec3& background, bool halfOutput, const gl::VertexArrayHandle& emptyVao) const {
    glDepthFunc(GL_LEQUAL);
    glUseProgram(background_.id());
    glUniform3fv(background_.uniform("u_background"), 1, glm::value_ptr(background));
    glUniform1i(background_.uniform("u_halfOutput"), halfOutput ? 1 : 0);
    gl::drawFullscreenTriangle(emptyVao);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_DEPTH_TEST);
}

}  // namespace starnt
