// Shared plumbing of the OIT methods: program building around the engine's surface shader, the
// full-resolution output target, and the full-screen triangle.
#pragma once
#include "gl/gl_util.hpp"
#include "gl/gpu_timer.hpp"
#include "gl/shader.hpp"
#include "gl/target_clears.hpp"
#include "methods/common/opaque_scene.hpp"
#include "methods/common/surface_program.hpp"
#include "starnt/oit_method.hpp"

namespace starnt {

class MethodBase : public OitMethod {
public:
    GLuint outputTexture() const override { return output_.id(); }
    // Checks the frame (a current context, its size, its opaque scene: nothing is drawn when one
    // is wrong), then renderFrame; the method's sampler is unbound at the end either way.
    void render(const FrameDesc& frame, const DrawCallback& draw) final;

    // Binds `program` with the per-pass uniforms every geometry pass has and calls the engine.
    static void runGeometryPass(const char* name, const gl::Program& program, const FrameDesc& frame,
                                const DrawCallback& draw);

protected:
    explicit MethodBase(SurfaceShader surface);
    virtual void renderFrame(const FrameDesc& frame, const DrawCallback& draw) = 0;

    // Geometry-pass program: engine vertex shader; fragment = engine surface code +
    // methods/common/surface_fetch.glsl + `fragmentFile` (which has main()).
    gl::Program buildGeometryProgram(const std::string& label, const std::string& fragmentFile,
                                     const std::string& defines = {}) const;
    // Full-screen program: methods/common/fullscreen.vert.glsl + `fragmentFile`.
    gl::Program buildFullscreenProgram(const std::string& label, const std::string& fragmentFile,
                                       const std::string& defines = {}) const;
    // The same with several fragment files concatenated in order (e.g. features + a main).
    gl::Program buildFullscreenProgram(const std::string& label, const std::vector<std::string>& fragmentFiles,
                                       const std::string& defines = {}) const;

    // (Re)allocates the output target (RGBA32F) when the size changed; returns true when it did, so
    // the method reallocates its own targets too.
    bool resizeOutput(int width, int height);
    // The same in two steps, for methods that may write their output elsewhere (the neural methods
    // write it in place over a pass target when they can): setFrameSize records the size (true when
    // it changed, dropping output_), allocateOutput allocates output_ at it when it is missing.
    bool setFrameSize(int width, int height);
    void allocateOutput(GLenum format);
    void drawFullscreen() const { gl::drawFullscreenTriangle(fullscreenVao_); }
    void bindOutputFramebuffer() const;
    size_t outputBytes() const { return output_.bytes(); }
    // Sets a composite program's background uniforms (background.glsl).
    void bindBackground(const gl::Program& program) const { opaque_.bindBackground(program); }

    SurfaceShader surface_;
    int width_ = 0, height_ = 0;
    gl::Texture2D output_;
    gl::FramebufferHandle outputFb_;
    gl::VertexArrayHandle fullscreenVao_;
    OpaqueScene opaque_;  // this frame's opaque depth and background
    gl::TargetClears clears_;  // the targets' clears (gl/target_clears.hpp: copies on llvmpipe)

private:
    gl::ContextToken context_;  // the context (share group) the method was created in
};

// Starts a pass that accumulates into `framebuffer` (width x height, from the origin): draw buffer 0
// a sum (cleared to 0, blend ONE, ONE), draw buffer 1 a product (cleared to 1, blend ZERO,
// `productFactor`), clipped by the frame's opaque depth. End it with opaque.endDepthTest and
// resetPassState. WBOIT's accumulation and the corrected frames' sums.
void beginSumAndProduct(GLuint framebuffer, int width, int height, OpaqueScene& opaque, GLenum productFactor,
                        gl::TargetClears& clears);

// Restores the GL state every pass may change to the defaults the methods assume (the depth range
// of the current frame's depth convention).
void resetPassState();

// How the engine's depth maps to window depth (docs/INTEGRATION.md, "Depth conventions"). The
// methods work in one canonical convention, OpenGL's default: clip z in [-w, w] with the near plane
// at -w, window depth 0 (near) to 1 (far). An engine's reversed Z (near at the larger depth) and
// clip control GL_ZERO_TO_ONE are met by the depth range the passes run with (1, 0 when reversed)
// and by the projection the methods compute with, `toCanonical * projection`, so that every depth a
// pass writes or compares is canonical whatever the engine's vertex shader produces. Clip control's
// GL_UPPER_LEFT origin puts window y the other way up: the canonical projection then has its y
// negated, so that the methods' own mapping from clip space to pixels (the lower-left one: temporal
// reprojection) lands where the engine's draws did. The methods draw nothing with that projection
// themselves (their full-screen passes cover the viewport either way up and read gl_FragCoord).
struct DepthConvention {
    bool zeroToOne = false;  // the context's GL_CLIP_DEPTH_MODE is GL_ZERO_TO_ONE
    bool upperLeft = false;  // the context's GL_CLIP_ORIGIN is GL_UPPER_LEFT
    bool reversed = false;   // the projection puts the near plane at the larger depth
    glm::mat4 toCanonical{1.0f};
};
// Reads the context's clip control and the projection's depth direction. Throws starnt::Error when
// the projection maps every depth to one value (a perspective with near = 0): nothing to order by.
DepthConvention readDepthConvention(const glm::mat4& projection);
// Makes `convention` the one resetPassState applies, on this thread, and returns `frame` with the
// canonical projection. MethodBase::render calls it; so do tools that run passes outside render().
FrameDesc beginDepthConvention(const FrameDesc& frame);
// The current convention (the last beginDepthConvention on this thread).
const DepthConvention& currentDepthConvention();

}  // namespace starnt
