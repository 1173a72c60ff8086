#include "methods/neural/temporal/reprojector.hpp"

#include <glm/gtc/type_ptr.hpp>

#include "methods/neural/temporal/reprojection_bindings.h"
#include "methods/neural/temporal/reprojection_reference.hpp"
#include "starnt/error.hpp"

namespace starnt::temporal {
namespace {

gl::Program buildPass(const char* name) {
    const std::string file = std::string("methods/neural/temporal/") + name + ".comp.glsl";
    return gl::buildComputeProgram(name, gl::embeddedSource(file));
}

void bindStorage(GLuint binding, const gl::Buffer& buffer) {
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding, buffer.id());
}

}  // namespace

Reprojector::Reprojector()
    : capture_(buildPass("temporal_capture")),
      clear_(buildPass("reprojection_clear")),
      splat_(buildPass("reprojection_splat")),
      pick_(buildPass("reprojection_pick")),
      gather_(buildPass("reprojection_gather")) {}

void Reprojector::dispatch(const gl::Program& program) const {
    glUseProgram(program.id());
    glUniform2i(program.uniform("u_size"), width_, height_);
    glDispatchCompute(GLuint((width_ + 7) / 8), GLuint((height_ + 7) / 8), 1);
}

void Reprojector::capture(GLuint colorTexture, GLuint depthTexture, int width, int height, const glm::mat4& viewProj) {
    if (width < 1 || height < 1) throw Error("temporal capture: empty frame size");
    if (width != width_ || height != height_ || !color_) {
        const size_t pixels = size_t(width) * size_t(height);
        color_ = gl::Buffer(pixels * sizeof(glm::vec4));
        depth_ = gl::Buffer(pixels * sizeof(float));
        splats_ = gl::Buffer(pixels * 2 * sizeof(uint32_t));
        winnerKey_ = gl::Buffer(pixels * sizeof(uint32_t));
        winnerSource_ = gl::Buffer(pixels * sizeof(uint32_t));
        width_ = width;
        height_ = height;
    }
    bindStorage(STARNT_SSBO_TEMPORAL_COLOR, color_);
    bindStorage(STARNT_SSBO_TEMPORAL_DEPTH, depth_);
    glBindTextureUnit(0, colorTexture);
    glBindTextureUnit(1, depthTexture);
    dispatch(capture_);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    viewProj_ = viewProj;
    hasFrame_ = true;
}

void Reprojector::reproject(const glm::mat4& newViewProj, GLuint outputTexture) const {
    if (!hasFrame_) throw Error("internal: temporal reprojection before any real frame was captured");
    const Reprojection reprojection = makeReprojection(viewProj_, newViewProj);
    bindStorage(STARNT_SSBO_TEMPORAL_COLOR, color_);
    bindStorage(STARNT_SSBO_TEMPORAL_DEPTH, depth_);
    bindStorage(STARNT_SSBO_TEMPORAL_SPLATS, splats_);
    bindStorage(STARNT_SSBO_TEMPORAL_WINNER_KEY, winnerKey_);
    bindStorage(STARNT_SSBO_TEMPORAL_WINNER_SOURCE, winnerSource_);

    dispatch(clear_);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glUseProgram(splat_.id());
    glUniformMatrix4fv(splat_.uniform("u_reprojection"), 1, GL_FALSE, glm::value_ptr(reprojection.matrix));
    glUniform4fv(splat_.uniform("u_sourceScale"), 1, glm::value_ptr(reprojection.sourceScale));
    dispatch(splat_);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    dispatch(pick_);
    glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
    glBindImageTexture(0, outputTexture, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
    dispatch(gather_);
    // The output is next sampled, read back or blitted.
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT |
                    GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
}

size_t Reprojector::gpuMemoryBytes() const {
    return color_.bytes() + depth_.bytes() + splats_.bytes() + winnerKey_.bytes() + winnerSource_.bytes();
}

}  // namespace starnt::temporal
