#include "methods/common/opaque_scene.hpp"

#include "methods/common/method_base.hpp"
#include "starnt/bindings.h"
#include "starnt/error.hpp"

namespace starnt {
namespace {

std::string sizeText(int w, int h) { return std::to_string(w) + "x" + std::to_string(h); }

// Throws unless `name` is a 2D texture of the frame size with a format of the wanted kind; returns
// what it is.
gl::TextureDescription checkTexture(const char* field, GLuint name, const FrameDesc& frame, bool depth) {
    const gl::TextureDescription d = gl::describeTexture(name, STARNT_UNIT_OPAQUE);
    const std::string what = std::string("FrameDesc::") + field + " (GL name " + std::to_string(name) + ")";
    if (!d.is2D) throw Error(what + " is not a GL_TEXTURE_2D texture of this context");
    if (d.width != frame.width || d.height != frame.height) {
        throw Error(what + " is " + sizeText(d.width, d.height) + ", not the frame size " +
                    sizeText(frame.width, frame.height));
    }
    if (depth && !gl::isDepthFormat(d.internalFormat)) {
        throw Error(what + " has no depth format (DEPTH_COMPONENT16/24/32F, DEPTH24_STENCIL8 or DEPTH32F_STENCIL8)");
    }
    if (!depth && (gl::isDepthFormat(d.internalFormat) || d.integer)) {
        throw Error(what + " must have a floating-point or normalised colour format (it is sampled as linear RGB)");
    }
    return d;
}

}  // namespace

void OpaqueScene::begin(const FrameDesc& frame) {
    end();  // (a no-op after a render() that ended)
    premultiplied_ = frame.premultipliedOutput;
    color_ = frame.background;
    depth_ = background_ = 0;
    clipWidth_ = clipHeight_ = 0;
    transmittanceInAlpha_ = false;
    depthFormat_ = 0;
    gl::TextureReadState depthRead, backgroundRead;
    if (frame.opaqueDepth) {
        const gl::TextureDescription d = checkTexture("opaqueDepth", frame.opaqueDepth, frame, true);
        // A copy needs a complete texture whatever its filter: immutable storage (else a full-screen pass).
        depthFormat_ = d.immutable ? d.internalFormat : 0;
        depthRead = d.read;
    }
    if (frame.backgroundTexture && !frame.premultipliedOutput) {
        backgroundRead = checkTexture("backgroundTexture", frame.backgroundTexture, frame, false).read;
    }
    depth_ = frame.opaqueDepth;
    background_ = frame.premultipliedOutput ? 0 : frame.backgroundTexture;
    // Every read is a texelFetch of level 0 as the checks above described it: an engine's base
    // level, stencil view or swizzle on its texture would change what it returns, and no sampler
    // object holds those; so they are the defaults for this frame, the engine's own back at end().
    // Both checks came first: nothing is changed for a frame that throws.
    if (depth_ && !(depthRead == gl::TextureReadState{})) restoreRead_.push_back({depth_, depthRead});
    if (background_ && !(backgroundRead == gl::TextureReadState{})) restoreRead_.push_back({background_, backgroundRead});
    for (const auto& [texture, read] : restoreRead_) gl::setTextureReadState(texture, STARNT_UNIT_OPAQUE, {});
    if (depth_ || background_) prepare();
    if (depth_ && !(clipDepth_.width() == frame.width && clipDepth_.height() == frame.height)) {
        clipDepth_ = gl::Texture2D(GL_DEPTH_COMPONENT32F, frame.width, frame.height);
        clipFb_ = gl::makeFramebuffer({}, &clipDepth_);
    }
}

void OpaqueScene::prepare() {
    if (fill_) return;
    fill_ = gl::buildProgram("opaque_depth", "#include \"methods/common/fullscreen.vert.glsl\"\n",
                             "#include \"methods/common/opaque_depth.frag.glsl\"\n");
    vao_ = gl::makeEmptyVertexArray();
    GLuint s = 0;
    glGenSamplers(1, &s);
    sampler_ = gl::SamplerHandle(s);
    glSamplerParameteri(s, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glSamplerParameteri(s, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glSamplerParameteri(s, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(s, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glSamplerParameteri(s, GL_TEXTURE_COMPARE_MODE, GL_NONE);
}

void OpaqueScene::bindOpaqueDepth(GLuint unit) const {
    gl::bindTexture(unit, depth_);
    glBindSampler(unit, sampler_.id());
    depthUnit_ = unit;
}

void OpaqueScene::end() {
    for (const auto& [texture, read] : restoreRead_) gl::setTextureReadState(texture, STARNT_UNIT_OPAQUE, read);
    restoreRead_.clear();
    if (!sampler_) return;
    glBindSampler(STARNT_UNIT_OPAQUE, 0);
    glBindSampler(depthUnit_, 0);
}

void OpaqueScene::writeDepth(int width, int height, int fullWidth, int fullHeight) {
    glUseProgram(fill_.id());
    glUniform2i(fill_.uniform("u_size"), width, height);
    glUniform2i(fill_.uniform("u_fullSize"), fullWidth, fullHeight);
    glUniform1i(fill_.uniform("u_reversed"), currentDepthConvention().reversed ? 1 : 0);
    bindOpaqueDepth();
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_ALWAYS);
    glDepthMask(GL_TRUE);
    gl::drawFullscreenTriangle(vao_);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);  // what resetPassState leaves, and every caller has
    glDepthFunc(GL_LESS);
    glDisable(GL_DEPTH_TEST);
    glBindSampler(STARNT_UNIT_OPAQUE, 0);
}

const gl::Program& OpaqueScene::clipInShader(SurfaceProgram& variants, int width, int height, int fullWidth,
                                             int fullHeight) const {
    if (!depth_) {
        glUseProgram(variants.id());
        return variants.plain();
    }
    const gl::Program& program = variants.clipping();
    glUseProgram(program.id());
    glUniform2i(program.uniform("u_opaqueSize"), width, height);
    glUniform2i(program.uniform("u_opaqueFullSize"), fullWidth, fullHeight);
    glUniform1i(program.uniform("u_opaqueReversed"), currentDepthConvention().reversed ? 1 : 0);
    bindOpaqueDepth();
    return program;
}

void OpaqueScene::beginDepthTest(GLuint framebuffer, int width, int height, int fullWidth, int fullHeight) {
    if (!depth_) return;
    if (clipWidth_ != width || clipHeight_ != height) {
        // The canonical opaque depth over this rectangle: a copy where the engine's texture already
        // holds it (DEPTH32F in the default convention, full size), else a full-screen pass.
        if (width == fullWidth && height == fullHeight && depthFormat_ == GL_DEPTH_COMPONENT32F &&
            !currentDepthConvention().reversed) {
            glCopyImageSubData(depth_, GL_TEXTURE_2D, 0, 0, 0, 0, clipDepth_.id(), GL_TEXTURE_2D, 0, 0, 0, 0, width, height, 1);
        } else {
            GLfloat viewport[4] = {0, 0, 0, 0};  // a reduced pass's is fractional
            glGetFloatv(GL_VIEWPORT, viewport);
            glBindFramebuffer(GL_FRAMEBUFFER, clipFb_.id());
            glViewport(0, 0, width, height);
            writeDepth(width, height, fullWidth, fullHeight);
            gl::setViewportF(viewport[0], viewport[1], viewport[2], viewport[3]);
        }
        clipWidth_ = width;
        clipHeight_ = height;
    }
    gl::bindTexture(STARNT_UNIT_OPAQUE, 0);  // the pass's shader must not sample what it tests against
    gl::attachTexture(framebuffer, GL_DEPTH_ATTACHMENT, clipDepth_.id());
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_FALSE);
}

void OpaqueScene::endDepthTest(GLuint framebuffer) {
    if (!depth_) return;
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    gl::attachTexture(framebuffer, GL_DEPTH_ATTACHMENT, 0);
}

void OpaqueScene::bindBackground(const gl::Program& program) const {
    glUniform3fv(program.uniform("u_background"), 1, &color_[0]);
    glUniform1i(program.uniform("u_backgroundSource"), premultiplied_ ? 2 : background_ ? 1 : 0);
    glUniform1i(program.uniform("u_transmittanceInAlpha"), transmittanceInAlpha_ ? 1 : 0);
    if (background_) {
        gl::bindTexture(STARNT_UNIT_OPAQUE, background_);
        glBindSampler(STARNT_UNIT_OPAQUE, sampler_.id());
    }
}

}  // namespace starnt
