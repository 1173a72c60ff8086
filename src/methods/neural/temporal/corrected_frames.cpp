#include "methods/neural/temporal/corrected_frames.hpp"

#include <glm/gtc/type_ptr.hpp>

#include "methods/neural/temporal/reprojection_math.hpp"
#include "methods/neural/temporal/temporal_passes.hpp"
#include "methods/neural/temporal/reprojection_constants.h"
#include "starnt/error.hpp"

namespace starnt::temporal {

namespace {
const char* orderedDefine(bool ordered) { return ordered ? "#define STARNT_ORDERED_BEHIND\n" : ""; }
std::string packedCompositeDefines(bool ordered, int layers) {
    return std::string("#define STARNT_PACKED_NEAREST\n") + orderedDefine(ordered) +
           (ordered && layers >= 2 ? "#define STARNT_PACKED_TWO_LAYERS\n" : "") +
           (ordered && layers >= 3 ? "#define STARNT_PACKED_THREE_LAYERS\n" : "");
}
}  // namespace

CorrectedFrames::CorrectedFrames(bool ordered, int layers)
    : ordered_(ordered),
      twoLayers_(ordered && layers >= 2),
      threeLayers_(ordered && layers >= 3),
      capture_(buildTemporalPass("correction_capture", "reprojection_behind.frag.glsl", "#define STARNT_BEHIND_CORRECTION 1\n")),
      composite_(buildTemporalPass("correction_composite", "correction_composite.frag.glsl", orderedDefine(ordered))),
      compositePacked_(buildTemporalPass("correction_composite_packed", "correction_composite.frag.glsl",
                                         packedCompositeDefines(ordered, layers))),
      emptyVao_(gl::makeEmptyVertexArray()) {
    if (ordered) {
        referenceTilesPass_ = buildTemporalPass("corrected_reference_tiles", "reference_depth.frag.glsl");
        referenceAroundPass_ = buildTemporalPass("corrected_reference", "reference_depth.frag.glsl", "#define STARNT_REFERENCE_AROUND\n");
    }
    if (threeLayers_) {
        referencePackedTilesPass_ = buildTemporalPass("corrected_reference_packed_tiles", "reference_depth.frag.glsl",
                                                      "#define STARNT_REFERENCE_FROM_PACKED\n");
    }
}

void CorrectedFrames::allocateReference(int width, int height) {
    const int tilesX = (width + STARNT_ORDERED_REFERENCE_TILE - 1) / STARNT_ORDERED_REFERENCE_TILE;
    const int tilesY = (height + STARNT_ORDERED_REFERENCE_TILE - 1) / STARNT_ORDERED_REFERENCE_TILE;
    if (reference_.width() != tilesX || reference_.height() != tilesY) {
        referenceTiles_ = gl::Texture2D(GL_R32F, tilesX, tilesY);
        reference_ = gl::Texture2D(GL_R32F, tilesX, tilesY);
    }
}

void CorrectedFrames::startLayered(int width, int height) {
    if (!threeLayers_) throw Error("internal: frames layered every frame need three layers");
    if (width < 1 || height < 1) throw Error("corrected frames: empty frame size");
    allocateReference(width, height);
    drawIntoTexture(framebuffer_, reference_.id(), reference_.width(), reference_.height());
    const float farPlane[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    glClearBufferfv(GL_COLOR, 0, farPlane);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    width_ = width;
    height_ = height;
    viewProj_ = glm::mat4(1.0f);  // read only for the correction, which these frames never keep
    hasFrame_ = true;
    hasCorrection_ = false;
}

void CorrectedFrames::keepReference(GLuint depth, int width, int height, bool packed) {
    allocateReference(width, height);
    const int tilesX = reference_.width(), tilesY = reference_.height();
    const struct {
        const gl::Program& program;
        GLuint source, target;
        int sourceWidth, sourceHeight;
    } steps[] = {{packed ? referencePackedTilesPass_ : referenceTilesPass_, depth, referenceTiles_.id(), width, height},
                 {referenceAroundPass_, referenceTiles_.id(), reference_.id(), tilesX, tilesY}};
    for (const auto& step : steps) {
        drawIntoTexture(framebuffer_, step.target, tilesX, tilesY);
        glUseProgram(step.program.id());
        glUniform2i(step.program.uniform("u_sourceSize"), step.sourceWidth, step.sourceHeight);
        gl::bindTexture(0, step.source);
        gl::drawFullscreenTriangle(emptyVao_);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void CorrectedFrames::capture(GLuint composite, GLuint depth, GLuint nearest, GLuint sumAlphaColor, GLuint transmittance,
                              int width, int height, const glm::mat4& viewProj, const OpaqueScene& background) {
    if (width < 1 || height < 1) throw Error("corrected frames: empty frame size");
    const GLenum format = gl::textureInternalFormat(composite);
    if (format != GL_RGBA32F && format != GL_RGBA16F) throw Error("corrected frames: the composite must be RGBA32F or RGBA16F");
    width_ = width;
    height_ = height;
    viewProj_ = viewProj;
    hasFrame_ = true;
    // Ordered frames take their correction against the ordered closed form, whose moments only the
    // method's own pass 3 and composite have (the fused capture): this pass keeps none for them.
    hasCorrection_ = !ordered_ && sumAlphaColor != 0 && transmittance != 0;
    if (ordered_ && !referenceFresh_) keepReference(depth, width, height);
    referenceFresh_ = false;
    if (!hasCorrection_) return;
    if (correction_.width() != width || correction_.height() != height || correction_.format() != format) {
        correction_ = gl::Texture2D(format, width, height, GL_LINEAR);  // the composite's filtered fetch
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
        correction_ = gl::Texture2D(compositeFormat, width, height, GL_LINEAR);  // the composite's filtered fetch
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

GLuint CorrectedFrames::prepareReference(GLuint depth, int width, int height) {
    if (!ordered_) return 0;
    keepReference(depth, width, height);
    referenceFresh_ = true;
    return reference_.id();
}

void CorrectedFrames::endFusedCapture() {
    if (ordered_ && !referenceFresh_) keepReference(coverDepth_.id(), width_, height_);  // the copy of pass 1's depth
    referenceFresh_ = false;
    hasFrame_ = true;
    hasCorrection_ = true;
}

void CorrectedFrames::composite(const glm::mat4& newViewProj, GLuint nearest, GLuint depth, GLuint sumAlphaColor,
                                GLuint transmittance, const OpaqueScene& background, GLuint output, GLuint behindMoment1,
                                GLuint behindMoment2) {
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
    emptyPixels_.clearToBackground(background, halfOutput);  // the output is not read here
    setCompositeUniforms(composite_, newViewProj, background, halfOutput);
    bindComposite(nearest, depth, sumAlphaColor, transmittance, behindMoment1, behindMoment2);
    gl::drawFullscreenTriangle(emptyVao_);
    emptyPixels_.fillEmpty(background, halfOutput, emptyVao_);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void CorrectedFrames::compositePacked(const glm::mat4& newViewProj, GLuint packedNearest, GLuint coverDepth,
                                      GLuint sumAlphaColor, GLuint transmittance, const OpaqueScene& background,
                                      GLuint output, GLuint behindMoment1, GLuint behindMoment2, GLuint thirdLayer,
                                      std::span<const GLuint> clearTargets, bool keepNextReference) {
    if (!hasFrame_) throw Error("internal: a corrected frame before any real frame was captured");
    if (gl::textureInternalFormat(packedNearest) != (twoLayers_ ? GL_RGBA32UI : GL_RGBA32F)) {
        throw Error(twoLayers_ ? "internal: the packed two layers must be an RGBA32UI texture"
                               : "internal: the packed nearest fragment must be an RGBA32F texture");
    }
    if (threeLayers_ && (!thirdLayer || gl::textureInternalFormat(thirdLayer) != GL_RGBA32UI)) {
        throw Error("internal: the packed third layer must be an RGBA32UI texture");
    }
    if (!clearTargets.empty() && (!threeLayers_ || clearTargets.size() != 5)) {
        throw Error("internal: the composite clears the five targets of three layers' pass 3 only");
    }
    const bool halfOutput = gl::textureInternalFormat(output) == GL_RGBA16F;  // before any binding (ES)
    // The next interpolated frame's reference depth: this one's nearest layers, one frame behind the
    // view where the real frame's is up to K - 1 behind (the composite reads this frame's reference
    // beside the third layer, not from reference_; with clearTargets it writes the new one there).
    if (threeLayers_ && keepNextReference) keepReference(packedNearest, width_, height_, true);
    if (!clearTargets.empty() && !compositePackedClears_.id()) {
        compositePackedClears_ = buildTemporalPass("correction_composite_packed_clears", "correction_composite.frag.glsl",
                                                   packedCompositeDefines(ordered_, 3) + "#define STARNT_CLEARS_TARGETS\n");
    }
    emptyPixels_.bindCovered(output, coverDepth, width_, height_, 0, clearTargets);
    emptyPixels_.clearToBackground(background, halfOutput);  // the output is not read here
    // Pass 3's writes, read by the invocations that write the same texels back (GL 4.5 9.3.1).
    if (!clearTargets.empty()) glTextureBarrier();
    setCompositeUniforms(clearTargets.empty() ? compositePacked_ : compositePackedClears_, newViewProj, background, halfOutput);
    bindComposite(packedNearest, thirdLayer, sumAlphaColor, transmittance, behindMoment1, behindMoment2);
    gl::drawFullscreenTriangle(emptyVao_);
    emptyPixels_.fillEmpty(background, halfOutput, emptyVao_);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void CorrectedFrames::bindComposite(GLuint nearestOrPacked, GLuint depth, GLuint sumAlphaColor,
                                    GLuint transmittance, GLuint behindMoment1, GLuint behindMoment2) {
    if (ordered_ && (!behindMoment1 || !behindMoment2)) {
        throw Error("internal: ordered corrected frames need pass 3's moments behind the reference depth");
    }
    // correction_composite.frag.glsl's units: 0 pass 1's layer (or the packed layer), 1 its depth
    // (with the packed layers: the third layer, where found), 2 and 3 the sums, 4 the correction; ordered: 5 and 6 the
    // moments, 7 the reference depth.
    const GLuint inputs[] = {nearestOrPacked, depth, sumAlphaColor, transmittance, correction_.id(),
                             behindMoment1, behindMoment2, ordered_ ? reference_.id() : 0u};
    for (GLuint unit = 0; unit < 8; ++unit) gl::bindTexture(unit, inputs[unit]);
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
    // RGBA16F filters everywhere, RGBA32F on desktop GL (ES: only with OES_texture_float_linear).
    glUniform1i(program.uniform("u_filteredCorrection"), correction_.format() == GL_RGBA16F || !gl::isEs());
}

}  // namespace starnt::temporal
