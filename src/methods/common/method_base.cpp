#include "methods/common/method_base.hpp"

#include "gl/pass_blend.hpp"
#include "starnt/bindings.h"
#include "starnt/error.hpp"

#include <cmath>

namespace starnt {

MethodBase::MethodBase(SurfaceShader surface)
    : surface_(std::move(surface)), fullscreenVao_(gl::makeEmptyVertexArray()) {}

gl::Program MethodBase::buildGeometryProgram(const std::string& label, const std::string& fragmentFile,
                                             const std::string& defines) const {
    return buildSurfaceProgram(surface_, label, fragmentFile, defines);
}

gl::Program MethodBase::buildFullscreenProgram(const std::string& label, const std::string& fragmentFile,
                                               const std::string& defines) const {
    return buildFullscreenProgram(label, std::vector<std::string>{fragmentFile}, defines);
}

gl::Program MethodBase::buildFullscreenProgram(const std::string& label, const std::vector<std::string>& fragmentFiles,
                                               const std::string& defines) const {
    std::string fragment;
    for (const auto& file : fragmentFiles) fragment += "#include \"" + file + "\"\n";
    return gl::buildProgram(label, "#include \"methods/common/fullscreen.vert.glsl\"\n", fragment, defines);
}

void MethodBase::render(const FrameDesc& frame, const DrawCallback& draw) {
    // No GL call before these checks (docs/INTEGRATION.md, "Misuse").
    if (!gl::hasCurrentContext()) throw Error("render(): no OpenGL context is current on this thread");
    if (!context_.current()) {
        throw Error("render(): the current OpenGL context is not the one this method was created in (its framebuffers and vertex arrays are in no other)");
    }
    // A new size is checked against the context's limits before anything of it is allocated
    // (setFrameSize); the same size was checked when it was new (before the first frame the size is
    // 0x0, which is never valid).
    if (frame.width != width_ || frame.height != height_ || width_ < 1) gl::checkFrameSize(frame.width, frame.height);
    const FrameDesc canonical = beginDepthConvention(frame);
    opaque_.begin(canonical);
    // State an engine may leave set that no pass sets for itself (docs/INTEGRATION.md, "State"):
    // a sampler object on a unit the methods read from overrides their textures' nearest filter
    // (an integer target with a linear filter is incomplete, and fetches 0), rasterizer discard
    // drops every clear and draw, a logic op replaces blending.
    for (GLuint unit = 0; unit < STARNT_UNIT_OPAQUE; ++unit) glBindSampler(unit, 0);
    glDisable(GL_RASTERIZER_DISCARD);
    if (!gl::isEs()) glDisable(GL_COLOR_LOGIC_OP);
    // The engine gets the default depth range back: a reversed-Z engine rarely sets it itself.
    auto finish = [this] {
        opaque_.end();
        glDepthRangef(0.0f, 1.0f);
    };
    try {
        renderFrame(canonical, draw);
    } catch (...) {
        finish();
        throw;
    }
    finish();
}

bool MethodBase::resizeOutput(int width, int height) {
    const bool changed = setFrameSize(width, height) || !output_;
    allocateOutput(GL_RGBA32F);
    return changed;
}

bool MethodBase::setFrameSize(int width, int height) {
    // render() checked the context and a new size before calling renderFrame.
    if (width == width_ && height == height_) return false;
    width_ = width;
    height_ = height;
    output_ = gl::Texture2D();
    outputFb_ = gl::FramebufferHandle();
    return true;
}

void MethodBase::allocateOutput(GLenum format) {
    if (output_) return;
    output_ = gl::Texture2D(format, width_, height_);
    outputFb_ = gl::makeFramebuffer({&output_});
}

void MethodBase::runGeometryPass(const char* name, const gl::Program& program, const FrameDesc& frame,
                                 const DrawCallback& draw) {
    glUseProgram(program.id());
    glUniform1f(program.uniform("u_alphaCutoff"), frame.alphaCutoff);
    // OpenGL ES blends 32-bit float targets only with GL_EXT_float_blend: without it the draw would
    // be an INVALID_OPERATION and the frame silently wrong, so a method that needs it says so.
    gl::checkFloatBlend(std::string("geometry pass '") + name + "'");
    if (frame.timing) frame.timing->beginGeometry(name);
    try {
        draw(GeometryPass{name, program.id()});
    } catch (...) {
        // The hook's calls stay nested (docs/INTEGRATION.md, "Timing"): a hook that brackets the
        // geometry with a query must see it end, or its next frame begins inside it.
        if (frame.timing) frame.timing->endGeometry();
        // What the callback drew before it threw may still be writing storage buffers and images
        // (the A-buffer's lists), and the barrier that follows a finished pass is skipped: without
        // this one the next frame's clears of those buffers are not ordered after the writes (on
        // llvmpipe the aborted frame's fragments then land in the next frame's lists).
        glMemoryBarrier(GL_ALL_BARRIER_BITS);
        throw;
    }
    if (frame.timing) frame.timing->endGeometry();
}

void MethodBase::bindOutputFramebuffer() const {
    glBindFramebuffer(GL_FRAMEBUFFER, outputFb_.id());
    glViewport(0, 0, width_, height_);
}

void beginSumAndProduct(GLuint framebuffer, int width, int height, OpaqueScene& opaque, GLenum productFactor,
                        gl::TargetClears& clears) {
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer);
    glViewport(0, 0, width, height);
    const float zero[4] = {0, 0, 0, 0}, one[4] = {1, 1, 1, 1};
    clears.color(0, zero);
    clears.color(1, one);
    opaque.beginDepthTest(framebuffer, width, height, width, height);
    glEnable(GL_BLEND);
    glBlendFunci(0, GL_ONE, GL_ONE);
    glBlendFunci(1, GL_ZERO, productFactor);
}

void resetPassState() {
    glDisable(GL_BLEND);
    glDisable(GL_DEPTH_TEST);
    glDepthMask(GL_TRUE);
    glDepthFunc(GL_LESS);
    glDisable(GL_CULL_FACE);
    glDisable(GL_SCISSOR_TEST);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glBlendEquation(GL_FUNC_ADD);
    // State an engine commonly leaves set that would change what the passes rasterise or the
    // window depths they compare (docs/INTEGRATION.md, "State"): filled polygons, no depth offset,
    // the full depth range.
    if (!gl::isEs()) {
        glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
        // Mesa's llvmpipe applies an enabled line or point offset to filled triangles too.
        glDisable(GL_POLYGON_OFFSET_LINE);
        glDisable(GL_POLYGON_OFFSET_POINT);
    }
    glDisable(GL_POLYGON_OFFSET_FILL);
    // Canonical window depth (DepthConvention): the near plane at 0 whatever the engine's projection.
    if (currentDepthConvention().reversed) glDepthRangef(1.0f, 0.0f);
    else glDepthRangef(0.0f, 1.0f);
}

namespace {
thread_local DepthConvention currentConvention;
}  // namespace

DepthConvention readDepthConvention(const glm::mat4& projection) {
    DepthConvention c;
    GLint mode = GL_NEGATIVE_ONE_TO_ONE;
    // Desktop 4.5 has clip control; ES only with the extension (asked on the first ES context only,
    // not on whichever context came first in a process that has both: the extension walk queries
    // every extension string).
    bool clipControl = !gl::isEs();
    if (!clipControl) {
        static const bool esClipControl = epoxy_has_gl_extension("GL_EXT_clip_control");
        clipControl = esClipControl;
    }
    GLint origin = GL_LOWER_LEFT;
    if (clipControl) {
        glGetIntegerv(GL_CLIP_DEPTH_MODE, &mode);
        glGetIntegerv(GL_CLIP_ORIGIN, &origin);
    }
    c.zeroToOne = mode == GL_ZERO_TO_ONE;
    c.upperLeft = origin == GL_UPPER_LEFT;
    // A perspective's clip w grows along its view direction (-z for OpenGL's usual matrices): its
    // normalised depth at distances 1 and 10 that way tells whether the near plane gets the smaller
    // depth. An affine projection (orthographic, or none) has no view direction of its own: its
    // normalised depth is taken as OpenGL's, smaller = nearer.
    const bool perspective = projection[2][3] != 0.0f;
    const float forward = projection[2][3] < 0.0f ? -1.0f : 1.0f;
    auto ndcDepth = [&](float distance) {
        const glm::vec4 clip = projection * glm::vec4(0.0f, 0.0f, forward * distance, 1.0f);
        return clip.z / clip.w;
    };
    const float nearer = ndcDepth(1.0f), farther = ndcDepth(10.0f);
    if (!(std::abs(farther - nearer) > 1e-7f)) {
        throw Error("FrameDesc::projection gives every depth the same window depth (a perspective with its near plane at 0?): "
                    "the methods cannot order the layers");
    }
    c.reversed = perspective && farther < nearer;
    // Canonical clip z = a z + b w: what maps the engine's normalised depth to [-1, 1], near at -1.
    const float a = c.zeroToOne ? (c.reversed ? -2.0f : 2.0f) : (c.reversed ? -1.0f : 1.0f);
    const float b = c.zeroToOne ? (c.reversed ? 1.0f : -1.0f) : 0.0f;
    c.toCanonical[2][2] = a;
    c.toCanonical[3][2] = b;
    if (c.upperLeft) c.toCanonical[1][1] = -1.0f;
    return c;
}

FrameDesc beginDepthConvention(const FrameDesc& frame) {
    currentConvention = readDepthConvention(frame.projection);
    FrameDesc canonical = frame;
    canonical.projection = currentConvention.toCanonical * frame.projection;
    return canonical;
}

const DepthConvention& currentDepthConvention() { return currentConvention; }

}  // namespace starnt
