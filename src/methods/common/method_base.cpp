#include "methods/common/method_base.hpp"

#include "starnt/error.hpp"

namespace starnt {

MethodBase::MethodBase(SurfaceShader surface)
    : surface_(std::move(surface)), fullscreenVao_(gl::makeEmptyVertexArray()) {}

gl::Program buildSurfaceProgram(const SurfaceShader& surface, const std::string& label, const std::string& fragmentFile,
                                const std::string& defines) {
    std::string fragment = surface.fragment + "\n#include \"methods/common/surface_fetch.glsl\"\n" +
                           "#include \"" + fragmentFile + "\"\n";
    return gl::buildProgram(label, surface.vertex, fragment, defines);
}

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
    gl::checkFrameSize(frame.width, frame.height);
    opaque_.begin(frame);
    try {
        renderFrame(frame, draw);
    } catch (...) {
        opaque_.end();
        throw;
    }
    opaque_.end();
}

bool MethodBase::resizeOutput(int width, int height) {
    const bool changed = setFrameSize(width, height) || !output_;
    allocateOutput(GL_RGBA32F);
    return changed;
}

bool MethodBase::setFrameSize(int width, int height) {
    // Every render() starts here: no GL call before these checks (docs/INTEGRATION.md, "Misuse").
    if (!gl::hasCurrentContext()) throw Error("render(): no OpenGL context is current on this thread");
    if (width == width_ && height == height_) return false;
    gl::checkFrameSize(width, height);
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
    if (frame.timing) frame.timing->beginGeometry(name);
    draw(GeometryPass{name, program.id()});
    if (frame.timing) frame.timing->endGeometry();
}

void MethodBase::bindOutputFramebuffer() const {
    glBindFramebuffer(GL_FRAMEBUFFER, outputFb_.id());
    glViewport(0, 0, width_, height_);
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
    if (!gl::isEs()) glPolygonMode(GL_FRONT_AND_BACK, GL_FILL);
    glDisable(GL_POLYGON_OFFSET_FILL);
    glDepthRangef(0.0f, 1.0f);
}

}  // namespace starnt
