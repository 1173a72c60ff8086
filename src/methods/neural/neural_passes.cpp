#include "methods/neural/neural_passes.hpp"

namespace starnt {

NeuralPasses::NeuralPasses(const gl::Program& pass1, const gl::Program& pass2, const gl::Program& pass3)
    : pass1_(pass1), pass2_(pass2), pass3_(pass3) {}

void NeuralPasses::resize(int width, int height) {
    if (width == width_ && height == height_) return;
    width_ = width;
    height_ = height;
    nearest_ = gl::Texture2D(GL_RGBA32F, width, height);
    nearestDepth_ = gl::Texture2D(GL_DEPTH_COMPONENT32F, width, height);
    second_ = gl::Texture2D(GL_RGBA32F, width, height);
    secondDepth_ = gl::Texture2D(GL_DEPTH_COMPONENT32F, width, height);
    alphaColor_ = gl::Texture2D(GL_RGBA32F, width, height);
    colorCount_ = gl::Texture2D(GL_RGBA32F, width, height);
    transmittance_ = gl::Texture2D(GL_R32F, width, height);
    pass1Fb_ = gl::makeFramebuffer({&nearest_}, &nearestDepth_);
    pass2Fb_ = gl::makeFramebuffer({&second_}, &secondDepth_);
    pass3Fb_ = gl::makeFramebuffer({&alphaColor_, &colorCount_, &transmittance_});
}

size_t NeuralPasses::gpuMemoryBytes() const {
    return nearest_.bytes() + nearestDepth_.bytes() + second_.bytes() + secondDepth_.bytes() + alphaColor_.bytes() +
           colorCount_.bytes() + transmittance_.bytes();
}

void NeuralPasses::run(const FrameDesc& frame, const DrawCallback& draw, float peelEpsilon) {
    resize(frame.width, frame.height);
    const float zero[4] = {0, 0, 0, 0}, one[4] = {1, 1, 1, 1}, farDepth = 1.0f;
    resetPassState();
    glViewport(0, 0, width_, height_);
    {
        gl::ScopedPass timing(frame.timer, "pass1");
        glBindFramebuffer(GL_FRAMEBUFFER, pass1Fb_.id());
        glClearBufferfv(GL_COLOR, 0, zero);
        glClearBufferfv(GL_DEPTH, 0, &farDepth);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        MethodBase::runGeometryPass("pass1", pass1_, frame, draw);
        resetPassState();
    }
    {
        gl::ScopedPass timing(frame.timer, "pass2");
        glBindFramebuffer(GL_FRAMEBUFFER, pass2Fb_.id());
        glClearBufferfv(GL_COLOR, 0, zero);
        glClearBufferfv(GL_DEPTH, 0, &farDepth);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glUseProgram(pass2_.id());
        glUniform1f(pass2_.uniform("u_peelEpsilon"), peelEpsilon);
        glBindTextureUnit(0, nearestDepth_.id());
        MethodBase::runGeometryPass("pass2", pass2_, frame, draw);
        resetPassState();
    }
    {
        gl::ScopedPass timing(frame.timer, "pass3");
        glBindFramebuffer(GL_FRAMEBUFFER, pass3Fb_.id());
        glClearBufferfv(GL_COLOR, 0, zero);
        glClearBufferfv(GL_COLOR, 1, zero);
        glClearBufferfv(GL_COLOR, 2, one);
        glEnable(GL_BLEND);
        // Per-target blend functions: core in GL 4.0 and GLES 3.2 (EXT_draw_buffers_indexed on 3.1).
        glBlendFunci(0, GL_ONE, GL_ONE);
        glBlendFunci(1, GL_ONE, GL_ONE);
        glBlendFunci(2, GL_ZERO, GL_ONE_MINUS_SRC_ALPHA);
        MethodBase::runGeometryPass("pass3", pass3_, frame, draw);
        resetPassState();
    }
}

void NeuralPasses::bindInputs() const {
    glBindTextureUnit(kUnitNearest, nearest_.id());
    glBindTextureUnit(kUnitSecond, second_.id());
    glBindTextureUnit(kUnitAlphaColor, alphaColor_.id());
    glBindTextureUnit(kUnitColorCount, colorCount_.id());
    glBindTextureUnit(kUnitTransmittance, transmittance_.id());
    glBindTextureUnit(kUnitNearestDepth, nearestDepth_.id());
}

}  // namespace starnt
