#include "methods/neural/temporal/corrected_frames.hpp"

#include <glm/gtc/type_ptr.hpp>

#include "methods/neural/temporal/reprojection_math.hpp"
#include "methods/neural/temporal/temporal_passes.hpp"
#include "starnt/error.hpp"

namespace starnt::temporal {

CorrectedFrames::CorrectedFrames()
    : capture_(buildTemporalPass("correction_capture", "reprojection_behind.frag.glsl", "#define STARNT_BEHIND_CORRECTION 1\n")),
      composite_(buildTemporalPass("correction_composite", "correction_composite.frag.glsl")),
      compositePacked_(buildTemporalPass("correction_composite_packed", "correction_composite.frag.glsl",
                                         "#define STARNT_PACKED_NEAREST\n")),
      emptyVao_(gl::makeEmptyVertexArray()) {}

void CorrectedFrames::capture(GLuint composite, GLuint depth, GLuint nearest, GLuint sumAlphaColor, GLuint transmittance,
                              int width, int height, const glm::mat4& viewProj, const OpaqueScene& background) {
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
    drawIntoTexture(framebuffer_, correction_.id(), width_, height_);
    glUseProgram(capture_.id());
    glUniform2i(capture_.uniform("u_size"), width, height);
    glUniform4fv(capture_.uniform("u_sourceScale"), 1, glm::value_ptr(makeCorrectionMatrices(viewProj, viewProj).sourceScale));
    background.bindBackground(capture_);
    // reprojection_behind.frag.glsl's units: 0 composite, 1 depth, 3 nearest, 4 and 5 the sums.
    const GLuint inputs[] = {composite, depth, 0, nearest, sumAlphaColor, transmittance};
    for (GLuint unit = 0; unit < 6; ++unit) gl::bindTexture(unit, inputs[unit]);
    gl::drawFullscreenTriangle(emptyVao_);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

CorrectedFrames::FusedTargets CorrectedFrames::beginFusedCapture(GLenum compositeFormat, GLuint depth, int width, int height,
                                                                const glm::mat4& viewProj) {
    if (width < 1 || height < 1) throw Error("corrected frames: empty frame size");
    if (compositeFormat != GL_RGBA32F && compositeFormat != GL_RGBA16F) {
        throw Error("corrected frames: the composite must be RGBA32F or RGBA16F");
    }
    if (correction_.width() != width || correction_.height() != height || correction_.format() != compositeFormat) {
        correction_ = gl::Texture2D(compositeFormat, width, height);
    }
    if (coverDepth_.width() != width || coverDepth_.height() != height) {
        coverDepth_ = gl::Texture2D(GL_DEPTH_COMPONENT32F, width, height);
    }
    glCopyImageSubData(depth, GL_TEXTURE_2D, 0, 0, 0, 0, coverDepth_.id(), GL_TEXTURE_2D, 0, 0, 0, 0, width, height, 1);
    width_ = width;
    height_ = height;
    viewProj_ = viewProj;
    hasFrame_ = false;  // until endFusedCapture
    return {correction_.id(), coverDepth_.id(), makeCorrectionMatrices(viewProj, viewProj).sourceScale};
}

void CorrectedFrames::endFusedCapture() {
    hasFrame_ = true;
    hasCorrection_ = true;
}

void CorrectedFrames::composite(const glm::mat4& newViewProj, GLuint nearest, GLuint depth, GLuint sumAlphaColor,
                                GLuint transmittance, const OpaqueScene& background, GLuint output) {
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
    setCompositeUniforms(composite_, newViewProj, background, halfOutput);
    const GLuint inputs[] = {nearest, depth, sumAlphaColor, transmittance, correction_.id()};
    for (GLuint unit = 0; unit < 5; ++unit) gl::bindTexture(unit, inputs[unit]);
    gl::drawFullscreenTriangle(emptyVao_);
    emptyPixels_.fillEmpty(background, halfOutput, emptyVao_);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void CorrectedFrames::compositePacked(const glm::mat4& newViewProj, GLuint packedNearest, GLuint coverDepth,
                                      GLuint sumAlphaColor, GLuint transmittance, const OpaqueScene& background,
                                      GLuint output) {
    if (!hasFrame_) throw Error("internal: a corrected frame before any real frame was captured");
    if (gl::textureInternalFormat(packedNearest) != GL_RGBA32F) {
        throw Error("internal: the packed nearest fragment must be an RGBA32F texture");
    }
    const bool halfOutput = gl::textureInternalFormat(output) == GL_RGBA16F;  // before any binding (ES)
    emptyPixels_.bindCovered(output, coverDepth, width_, height_);
    setCompositeUniforms(compositePacked_, newViewProj, background, halfOutput);
    // correction_composite.frag.glsl's units with STARNT_PACKED_NEAREST: 0 packed, 2 and 3 the sums, 4 the correction.
    const GLuint inputs[] = {packedNearest, 0, sumAlphaColor, transmittance, correction_.id()};
    for (GLuint unit = 0; unit < 5; ++unit) gl::bindTexture(unit, inputs[unit]);
    gl::drawFullscreenTriangle(emptyVao_);
    emptyPixels_.fillEmpty(background, halfOutput, emptyVao_);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void CorrectedFrames::setCompositeUniforms(const gl::Program& program, const glm::mat4& newViewProj,
                                           const OpaqueScene& background, bool halfOutput) const {
    glUseProgram(program.id());
    const CorrectionMatrices m = makeCorrectionMatrices(viewProj_, newViewProj);
    glUniform2i(program.uniform("u_size"), width_, height_);
    glUniformMatrix4fv(program.uniform("u_newToOld"), 1, GL_FALSE, glm::value_ptr(m.newToOld));
    glUniform4fv(program.uniform("u_sourceScale"), 1, glm::value_ptr(m.sourceScale));
    background.bindBackground(program);
    glUniform1i(program.uniform("u_halfOutput"), halfOutput);
    glUniform1i(program.uniform("u_useCorrection"), hasCorrection_);
}

}  // namespace starnt::temporal
