// Unsorted over-blending in submission order: what an engine gets without sorting. One pass
// straight into the output target, which starts as the background.
#include "methods/common/method_base.hpp"
#include "methods/registry.hpp"

namespace starnt {
namespace {

class UnsortedMethod final : public MethodBase {
public:
    explicit UnsortedMethod(const SurfaceShader& surface)
        : MethodBase(surface), program_(buildGeometryProgram("unsorted", "methods/unsorted/unsorted.frag.glsl")) {}

    std::string name() const override { return "unsorted"; }
    size_t gpuMemoryBytes() const override { return outputBytes(); }

    void render(const FrameDesc& frame, const DrawCallback& draw) override {
        resizeOutput(frame.width, frame.height);
        gl::ScopedPass timing(frame.timing, "blend");
        resetPassState();
        bindOutputFramebuffer();
        const float clear[4] = {frame.background.r, frame.background.g, frame.background.b, 1.0f};
        glClearBufferfv(GL_COLOR, 0, clear);
        glEnable(GL_BLEND);
        glBlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ZERO, GL_ONE);
        runGeometryPass("unsorted", program_, frame, draw);
        resetPassState();
    }

private:
    gl::Program program_;
};

}  // namespace

std::unique_ptr<OitMethod> createUnsortedMethod(const SurfaceShader& surface, const MethodOptions&) {
    return std::make_unique<UnsortedMethod>(surface);
}

}  // namespace starnt
