// Weighted blended OIT: one geometry pass into two targets, one full-screen resolve.
#include "methods/common/method_base.hpp"
#include "methods/registry.hpp"
#include "starnt/error.hpp"

namespace starnt {
namespace {

int parseWeightFunction(const std::string& name) {
    if (name == "eq7") return 7;
    if (name == "eq8") return 8;
    if (name == "eq9") return 9;
    if (name == "eq10" || name.empty()) return 10;
    throw Error("unknown WBOIT weight function '" + name + "' (valid: eq7, eq8, eq9, eq10)");
}

class WboitMethod final : public MethodBase {
public:
    WboitMethod(const SurfaceShader& surface, const MethodOptions& options)
        : MethodBase(surface),
          weightFunction_(parseWeightFunction(options.wboit.weight)),
          accumulate_(buildGeometryProgram("wboit_accumulate", "methods/wboit/wboit_accumulate.frag.glsl")),
          composite_(buildFullscreenProgram("wboit_composite", "methods/wboit/wboit_composite.frag.glsl")) {}

    std::string name() const override { return "wboit"; }
    size_t gpuMemoryBytes() const override { return outputBytes() + accum_.bytes() + reveal_.bytes() + clears_.bytes(); }
    MemoryTargets gpuMemoryTargets() const override {
        return {{"output", outputBytes()}, {"accum", accum_.bytes()}, {"revealage", reveal_.bytes()}, {"clear_strips", clears_.bytes()}};
    }

    void renderFrame(const FrameDesc& frame, const DrawCallback& draw) override {
        if (resizeOutput(frame.width, frame.height)) {
            accum_ = gl::Texture2D(GL_RGBA32F, width_, height_);
            reveal_ = gl::Texture2D(GL_R32F, width_, height_);
            fb_ = gl::makeFramebuffer({&accum_, &reveal_});
        }
        resetPassState();
        {
            gl::ScopedPass timing(frame.timing, "accumulate");
            beginSumAndProduct(fb_.id(), width_, height_, opaque_, GL_ONE_MINUS_SRC_COLOR, clears_);  // weighted sums; revealage
            glUseProgram(accumulate_.id());
            glUniform1i(accumulate_.uniform("u_weightFunction"), weightFunction_);
            glUniform2f(accumulate_.uniform("u_projZ"), frame.projection[2][2], frame.projection[3][2]);
            runGeometryPass("wboit_accumulate", accumulate_, frame, draw);
            opaque_.endDepthTest(fb_.id());
            resetPassState();
        }
        {
            gl::ScopedPass timing(frame.timing, "composite");
            bindOutputFramebuffer();
            glUseProgram(composite_.id());
            gl::bindTexture(0, accum_.id());
            gl::bindTexture(1, reveal_.id());
            bindBackground(composite_);
            drawFullscreen();
        }
    }

private:
    int weightFunction_;
    gl::Program accumulate_, composite_;
    gl::Texture2D accum_, reveal_;
    gl::FramebufferHandle fb_;
};

}  // namespace

std::unique_ptr<OitMethod> createWboitMethod(const SurfaceShader& surface, const MethodOptions& options) {
    return std::make_unique<WboitMethod>(surface, options);
}

}  // namespace starnt
