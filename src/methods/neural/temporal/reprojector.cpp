#include "methods/neural/temporal/reprojector.hpp"

#include <glm/gtc/matrix_access.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "methods/common/method_base.hpp"
#include "methods/neural/temporal/reprojection_constants.h"
#include "methods/neural/temporal/reprojection_math.hpp"
#include "methods/neural/temporal/temporal_passes.hpp"
#include "starnt/error.hpp"

namespace starnt::temporal {

Reprojector::Reprojector()
    : blockSeeds_(buildTemporalPass("reprojection_block_seeds", "reprojection_seeds.frag.glsl", "#define STARNT_SEEDS_BLOCK 1\n")),
      dilateSeeds_(buildTemporalPass("reprojection_dilate_seeds", "reprojection_seeds.frag.glsl")),
      search_(buildTemporalPass("reprojection_search", "reprojection_search.frag.glsl")),
      searchRefresh_(buildTemporalPass("reprojection_refresh", "reprojection_search.frag.glsl", "#define STARNT_REFRESH 1\n")),
      behindProgram_(buildTemporalPass("reprojection_behind", "reprojection_behind.frag.glsl")),
      emptyVao_(gl::makeEmptyVertexArray()) {}

void Reprojector::capture(GLuint colorTexture, GLuint depthTexture, int width, int height, const glm::mat4& viewProj,
                          GLuint nearestTexture, const OpaqueScene* premultiply) {
    if (width < 1 || height < 1) throw Error("temporal capture: empty frame size");
    const GLenum colorFormat = gl::textureInternalFormat(colorTexture), depthFormat = gl::textureInternalFormat(depthTexture);
    // The history keeps the composite's own precision (RGBA16F with the compact targets).
    if (colorFormat != GL_RGBA32F && colorFormat != GL_RGBA16F) {
        throw Error("temporal capture: the composite must be an RGBA32F or RGBA16F texture");
    }
    if (depthFormat != GL_DEPTH_COMPONENT32F && depthFormat != GL_R32F) {
        throw Error("temporal capture: the depth must be a DEPTH_COMPONENT32F or R32F texture");
    }
    if (width != width_ || height != height_ || !color_ || color_.format() != colorFormat || depth_.format() != depthFormat) {
        color_ = gl::Texture2D(colorFormat, width, height);
        depth_ = gl::Texture2D(depthFormat, width, height);
        const int blocksX = (width + STARNT_TEMPORAL_SEED_BLOCK - 1) / STARNT_TEMPORAL_SEED_BLOCK;
        const int blocksY = (height + STARNT_TEMPORAL_SEED_BLOCK - 1) / STARNT_TEMPORAL_SEED_BLOCK;
        blockMinMax_ = gl::Texture2D(GL_RG32F, blocksX, blocksY);
        seeds_ = gl::Texture2D(GL_RG32F, blocksX, blocksY);
        width_ = width;
        height_ = height;
    }
    const GLenum nearestFormat = nearestTexture ? gl::textureInternalFormat(nearestTexture) : GLenum(GL_RGBA32F);
    if (nearestFormat != GL_RGBA32F && nearestFormat != GL_RGBA16F) {
        throw Error("temporal capture: the nearest layer must be an RGBA32F or RGBA16F texture");
    }
    if (nearestTexture && (keptNearest_.width() != width || keptNearest_.height() != height || keptNearest_.format() != nearestFormat)) {
        keptNearest_ = gl::Texture2D(nearestFormat, width, height);
    }
    hasNearest_ = nearestTexture != 0;
    if (hasNearest_) {
        glCopyImageSubData(nearestTexture, GL_TEXTURE_2D, 0, 0, 0, 0, keptNearest_.id(), GL_TEXTURE_2D, 0, 0, 0, 0, width,
                           height, 1);
    }
    // Plain copies: the method overwrites its own targets on the next real frame.
    premultiplied_ = premultiply != nullptr;
    if (premultiplied_) {
        if (!premultiply_) premultiply_ = buildTemporalPass("history_premultiplied", "history_premultiplied.frag.glsl");
        drawIntoTexture(framebuffer_, color_.id(), width, height);
        glUseProgram(premultiply_.id());
        premultiply->bindBackground(premultiply_);
        gl::bindTexture(0, colorTexture);
        gl::drawFullscreenTriangle(emptyVao_);
    } else {
        glCopyImageSubData(colorTexture, GL_TEXTURE_2D, 0, 0, 0, 0, color_.id(), GL_TEXTURE_2D, 0, 0, 0, 0, width, height, 1);
    }
    glCopyImageSubData(depthTexture, GL_TEXTURE_2D, 0, 0, 0, 0, depth_.id(), GL_TEXTURE_2D, 0, 0, 0, 0, width, height, 1);
    // The seeds: (min, max) depth per block, then over the 3x3 blocks around.
    const int blocksX = seeds_.width(), blocksY = seeds_.height();
    drawIntoTexture(framebuffer_, blockMinMax_.id(), blocksX, blocksY);
    glUseProgram(blockSeeds_.id());
    glUniform2i(blockSeeds_.uniform("u_sourceSize"), width, height);
    gl::bindTexture(0, depth_.id());
    gl::drawFullscreenTriangle(emptyVao_);
    drawIntoTexture(framebuffer_, seeds_.id(), blocksX, blocksY);
    glUseProgram(dilateSeeds_.id());
    glUniform2i(dilateSeeds_.uniform("u_sourceSize"), blocksX, blocksY);
    gl::bindTexture(0, blockMinMax_.id());
    gl::drawFullscreenTriangle(emptyVao_);
    if (hasNearest_) {
        if (behind_.width() != width || behind_.height() != height || behind_.format() != colorFormat) {
            behind_ = gl::Texture2D(colorFormat, width, height);
        }
        drawIntoTexture(framebuffer_, behind_.id(), width, height);
        glUseProgram(behindProgram_.id());
        glUniform2i(behindProgram_.uniform("u_size"), width, height);
        const Reprojection r = makeReprojection(viewProj, viewProj);
        glUniform4fv(behindProgram_.uniform("u_sourceScale"), 1, glm::value_ptr(r.sourceScale));
        gl::bindTexture(0, color_.id());
        gl::bindTexture(1, depth_.id());
        gl::bindTexture(3, keptNearest_.id());
        gl::drawFullscreenTriangle(emptyVao_);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    viewProj_ = viewProj;
    hasFrame_ = true;
}

void Reprojector::setSearchUniforms(const gl::Program& program, const glm::mat4& newViewProj) const {
    const Reprojection r = makeReprojection(viewProj_, newViewProj);
    glUseProgram(program.id());
    glUniform2i(program.uniform("u_size"), width_, height_);
    glUniform4fv(program.uniform("u_row0"), 1, glm::value_ptr(r.row0));
    glUniform4fv(program.uniform("u_row1"), 1, glm::value_ptr(r.row1));
    glUniform4fv(program.uniform("u_row3"), 1, glm::value_ptr(r.row3));
    glUniform4fv(program.uniform("u_row2"), 1, glm::value_ptr(glm::row(newViewProj * glm::inverse(viewProj_), 2)));
    glUniform1i(program.uniform("u_premultipliedHistory"), premultiplied_ ? 1 : 0);
    glUniform4fv(program.uniform("u_sourceScale"), 1, glm::value_ptr(r.sourceScale));
    gl::bindTexture(0, color_.id());
    gl::bindTexture(1, depth_.id());
    gl::bindTexture(2, seeds_.id());
}

void Reprojector::reproject(const glm::mat4& newViewProj, GLuint outputTexture, const OpaqueScene& background) {
    if (!hasFrame_) throw Error("internal: temporal reprojection before any real frame was captured");
    // Queried before any binding: on OpenGL ES the query binds the texture to the active unit.
    const bool halfOutput = gl::textureInternalFormat(outputTexture) == GL_RGBA16F;
    drawIntoTexture(framebuffer_, outputTexture, width_, height_);
    setSearchUniforms(search_, newViewProj);
    glUniform1i(search_.uniform("u_halfOutput"), halfOutput);
    background.bindBackground(search_);
    glUniform1i(search_.uniform("u_opaqueClip"), background.clips() ? 1 : 0);
    glUniform1i(search_.uniform("u_opaqueReversed"), currentDepthConvention().reversed ? 1 : 0);
    if (background.clips()) background.bindOpaqueDepth(6);
    gl::drawFullscreenTriangle(emptyVao_);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void Reprojector::reprojectRefresh(const glm::mat4& newViewProj, GLuint nearestTexture, GLuint nearestDepth,
                                   const OpaqueScene& background, GLuint outputTexture) {
    if (!hasFrame_) throw Error("internal: temporal reprojection before any real frame was captured");
    if (!hasNearest_) throw Error("internal: a refresh frame needs the kept frame's nearest layer");
    const bool halfOutput = gl::textureInternalFormat(outputTexture) == GL_RGBA16F;  // before any binding (ES)
    if (nearestDepth) emptyPixels_.bindCovered(outputTexture, nearestDepth, width_, height_);
    else drawIntoTexture(framebuffer_, outputTexture, width_, height_);
    setSearchUniforms(searchRefresh_, newViewProj);
    gl::bindTexture(3, keptNearest_.id());
    gl::bindTexture(4, nearestTexture);
    gl::bindTexture(5, behind_.id());
    background.bindBackground(searchRefresh_);
    glUniform1i(searchRefresh_.uniform("u_halfOutput"), halfOutput);
    gl::drawFullscreenTriangle(emptyVao_);
    if (nearestDepth) emptyPixels_.fillEmpty(background, halfOutput, emptyVao_);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace starnt::temporal
