#include "methods/neural/temporal/corrected_frames.hpp"

#include <glm/gtc/type_ptr.hpp>

#include "methods/neural/temporal/correction_reference.hpp"
#include "starnt/error.hpp"

namespace starnt::temporal {
namespace {

gl::Program buildPass(const char* label, const char* file) {
    return gl::buildProgram(label, gl::embeddedSource("methods/common/fullscreen.vert.glsl"),
                            gl::embeddedSource(std::string("methods/neural/temporal/") + file));
}

}  // namespace

CorrectedFrames::CorrectedFrames()
    : capture_(buildPass("correction_capture", "correction_capture.frag.glsl")),
      composite_(buildPass("correction_composite", "correction_composite.frag.glsl")),
      emptyVao_(gl::makeEmptyVertexArray()) {}

void CorrectedFrames::drawInto(GLuint texture) {
    if (!framebuffer_) framebuffer_ = gl::makeFramebufferName();
    if (gl::attachTexture(framebuffer_.id(), GL_COLOR_ATTACHMENT0, texture) != GL_FRAMEBUFFER_COMPLETE) {
        throw Error("corrected frames: the output texture is not colour-renderable");
    }
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
    glViewport(0, 0, width_, height_);
    glDisable(GL_DEPTH_TEST);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
}

void CorrectedFrames::capture(GLuint composite, GLuint depth, GLuint nearest, GLuint sumAlphaColor, GLuint transmittance,
                              int width, int height, const glm::mat4& viewProj, const glm::vec3& background) {
    if (width < 1 || height < 1) throw Error("corrected frames: empty frame size");
    const GLenum format = gl::textureInternalFormat(composite);
    if (format != GL_RGBA32F && format != GL_RGBA16F) throw Error("corrected frames: the composite must be RGBA32F or RGBA16F");
    width_ = width;
    height_ = height;
    viewProj_ = viewProj;
    hasFrame_ = true;
    hasCorrection_ = sumAlphaColor != 0 && transmittance != 0;
    if (!hasCorrection_) return;
    if (correction_.width() != width || correction_.height() != height || correction_.format() != format) {
        correction_ = gl::Texture2D(format, width, height);
    }
    drawInto(correction_.id());
    glUseProgram(capture_.id());
    glUniform2i(capture_.uniform("u_size"), width, height);
    glUniform4fv(capture_.uniform("u_sourceScale"), 1, glm::value_ptr(makeCorrectionMatrices(viewProj, viewProj).sourceScale));
    glUniform3fv(capture_.uniform("u_background"), 1, glm::value_ptr(background));
    const GLuint inputs[] = {composite, depth, nearest, sumAlphaColor, transmittance};
    for (GLuint unit = 0; unit < 5; ++unit) gl::bindTexture(unit, inputs[unit]);
    gl::drawFullscreenTriangle(emptyVao_);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void CorrectedFrames::composite(const glm::mat4& newViewProj, GLuint nearest, GLuint depth, GLuint sumAlphaColor,
                                GLuint transmittance, const glm::vec3& background, GLuint output) {
    if (!hasFrame_) throw Error("internal: a corrected frame before any real frame was captured");
    const bool halfOutput = gl::textureInternalFormat(output) == GL_RGBA16F;  // before any binding (ES)
    if (gl::textureInternalFormat(depth) != GL_DEPTH_COMPONENT32F) {
        throw Error("corrected frames: pass 1's depth must be a DEPTH_COMPONENT32F texture");
    }
    if (coverDepth_.width() != width_ || coverDepth_.height() != height_) {
        coverDepth_ = gl::Texture2D(GL_DEPTH_COMPONENT32F, width_, height_);
    }
    glCopyImageSubData(depth, GL_TEXTURE_2D, 0, 0, 0, 0, coverDepth_.id(), GL_TEXTURE_2D, 0, 0, 0, 0, width_, height_, 1);
    emptyPixels_.bindCovered(output, coverDepth_.id(), width_, height_);
    glUseProgram(composite_.id());
    const CorrectionMatrices m = makeCorrectionMatrices(viewProj_, newViewProj);
    glUniform2i(composite_.uniform("u_size"), width_, height_);
    glUniformMatrix4fv(composite_.uniform("u_newToOld"), 1, GL_FALSE, glm::value_ptr(m.newToOld));
    glUniform4fv(composite_.uniform("u_sourceScale"), 1, glm::value_ptr(m.sourceScale));
    glUniform3fv(composite_.uniform("u_background"), 1, glm::value_ptr(background));
    glUniform1i(composite_.uniform("u_halfOutput"), halfOutput);
    glUniform1i(composite_.uniform("u_useCorrection"), hasCorrection_);
    const GLuint inputs[] = {nearest, depth, sumAlphaColor, transmittance, correction_.id()};
    for (GLuint unit = 0; unit < 5; ++unit) gl::bindTexture(unit, inputs[unit]);
    gl::drawFullscreenTriangle(emptyVao_);
    emptyPixels_.fillEmpty(background, halfOutput, emptyVao_);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace starnt::temporal
