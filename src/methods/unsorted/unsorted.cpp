// Unsorted over-blending in submission order: what an engine gets without sorting. One pass
// straight into the output target, which starts as the background.
#include "methods/common/method_base.hpp"
#include "methods/registry.hpp"

namespace starnt {
namespace {

class UnsortedMethod final : public MethodBase {
public:
    explicit UnsortedMethod(const SurfaceShader& surface)
        : MethodBase(surface),
          program_(buildGeometryProgram("unsorted", "methods/unsorted/unsorted.frag.glsl")),
          fill_(buildFullscreenProgram("background_fill", "methods/common/background_fill.frag.glsl")) {}

    std::string name() const override { return "unsorted"; }
    size_t gpuMemoryBytes() const override { return outputBytes(); }

    void renderFrame(const FrameDesc& frame, const DrawCallback& draw) override {
        resizeOutput(frame.width, frame.height);
        gl::ScopedPass timing(frame.timing, "blend");
        resetPassState();
        bindOutputFramebuffer();
        glUseProgram(fill_.id());
        bindBackground(fill_);
        drawFullscreen();
        opaque_.beginDepthTest(outputFb_.id(), width_, height_, width_, height_);
        glEnable(GL_BLEND);
        // Alpha: kept at 1, or the transmittance prod (1 - a) for a premultiplied output.
        glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO,
                            frame.premultipliedOutput ? GL_ONE_MINUS_SRC_ALPHA : GL_ONE);
        runGeometryPass("unsorted", program_, frame, draw);
        opaque_.endDepthTest(outputFb_.id());
        resetPassState();
    }

private:
    gl::Program program_, fill_;
};

}  // namespace

std::unique_ptr<OitMethod> createUnsortedMethod(const SurfaceShader& surface, const MethodOptions&) {
    return std::make_unique<UnsortedMethod>(surface);
}

}  // namespace starnt
