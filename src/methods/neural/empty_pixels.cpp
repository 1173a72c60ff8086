#include "methods/neural/empty_pixels.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#include "methods/common/method_base.hpp"
#include "starnt/error.hpp"

namespace starnt {

const GLenum EmptyPixelSkip::kDrawBuffers[EmptyPixelSkip::kMaxTargets] = {
    GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2, GL_COLOR_ATTACHMENT3,
    GL_COLOR_ATTACHMENT4, GL_COLOR_ATTACHMENT5, GL_COLOR_ATTACHMENT6, GL_COLOR_ATTACHMENT7};

EmptyPixelSkip::EmptyPixelSkip()
    : background_(gl::buildProgram("infer_background", gl::embeddedSource("methods/common/fullscreen.vert.glsl"),
                                   gl::embeddedSource("methods/neural/infer_background.frag.glsl"))) {}

void EmptyPixelSkip::bindCovered(GLuint colorTexture, GLuint pass1Depth, int width, int height, GLuint secondColor,
                                 std::span<const GLuint> moreTargets) {
    if (!framebuffer_) framebuffer_ = gl::makeFramebufferName();
    // Attached on every call: the textures are the caller's and may have been reallocated. The
    // attachments a call does not use are detached, so that none keeps a texture alive.
    std::vector<GLuint> colors{colorTexture};
    if (secondColor) colors.push_back(secondColor);
    colors.insert(colors.end(), moreTargets.begin(), moreTargets.end());
    if (colors.size() > kMaxTargets) throw Error("internal: more composite targets than EmptyPixelSkip attaches");
    for (size_t i = 0; i < std::max(colors.size(), attached_); ++i) {
        gl::attachTexture(framebuffer_.id(), GLenum(GL_COLOR_ATTACHMENT0 + i), i < colors.size() ? colors[i] : 0u);
    }
    attached_ = colors.size();
    second_ = secondColor != 0;
    if (gl::attachTexture(framebuffer_.id(), GL_DEPTH_ATTACHMENT, pass1Depth) != GL_FRAMEBUFFER_COMPLETE) {
        throw Error("internal: the output and pass-1 depth do not form a complete framebuffer");
    }
    cleared_ = false;
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.id());
    glDrawBuffers(GLsizei(attached_), kDrawBuffers);
    glViewport(0, 0, width, height);
    glDisable(GL_BLEND);
    glDisable(GL_SCISSOR_TEST);
    glEnable(GL_DEPTH_TEST);
    glDepthMask(GL_FALSE);
    glDepthFunc(GL_GREATER);
    // The full-screen triangle at window depth 1 whatever the clip control and the depth convention
    // (a reversed depth range would put clip z = w at 0).
    glDepthRangef(1.0f, 1.0f);
}

namespace {
// half_targets.glsl's nearestHalf: to the nearest 16-bit float, ties to even, at most 65504.
float nearestHalf(float v) {
    const float h = float(static_cast<_Float16>(std::min(std::abs(v), 65504.0f)));
    return v < 0.0f ? -h : h;
}
}  // namespace

bool EmptyPixelSkip::clearToBackground(const OpaqueScene& background, bool halfOutput) {
    std::optional<glm::vec4> value = background.uniformBackground();
    if (!value) return false;
    if (halfOutput) *value = glm::vec4(nearestHalf(value->r), nearestHalf(value->g), nearestHalf(value->b), nearestHalf(value->a));
    glClearBufferfv(GL_COLOR, 0, &(*value)[0]);
    const float hidden[4] = {0.0f, 0.0f, 0.0f, -1.0f};  // infer_background.frag.glsl's second output
    if (second_) glClearBufferfv(GL_COLOR, 1, hidden);
    cleared_ = true;
    return true;
}

void EmptyPixelSkip::fillEmpty(const OpaqueScene& background, bool halfOutput, const gl::VertexArrayHandle& emptyVao) {
    glDrawBuffers(second_ ? 2 : 1, kDrawBuffers);  // the background program writes nothing else
    if (!cleared_) {
        glDepthFunc(GL_LEQUAL);
        glUseProgram(background_.id());
        background.bindBackground(background_);
        glUniform1i(background_.uniform("u_halfOutput"), halfOutput ? 1 : 0);
        gl::drawFullscreenTriangle(emptyVao);
    }
    cleared_ = false;
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_DEPTH_TEST);
    resetPassState();  // the frame's depth range back, among the rest
}

}  // namespace starnt
