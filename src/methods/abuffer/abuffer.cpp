// A-buffer: exact ground truth. Per-pixel linked lists (abuffer_lists.*), then a full-screen
// resolve that composites each list in depth order.
#include "methods/abuffer/abuffer_lists.hpp"
#include "methods/registry.hpp"

namespace starnt {
namespace {

class AbufferMethod final : public MethodBase {
public:
    AbufferMethod(const SurfaceShader& surface, const MethodOptions& options)
        : MethodBase(surface),
          lists_(*this, false, options),
          build_(buildGeometryProgram("abuffer_build", "methods/abuffer/abuffer_build.frag.glsl")),
          resolve_(buildFullscreenProgram("abuffer_resolve", "methods/abuffer/abuffer_resolve.frag.glsl")) {}

    std::string name() const override { return "abuffer"; }
    size_t gpuMemoryBytes() const override { return outputBytes() + lists_.gpuMemoryBytes(); }

    nlohmann::json lastFrameStats() const override {
        return {{"max_fragments", maxFragments_},
                {"fragments", lists_.fragmentCount()},
                {"pool_capacity", lists_.capacity()},
                {"pool_regrows", lists_.regrows()}};
    }

    void render(const FrameDesc& frame, const DrawCallback& draw) override {
        resizeOutput(frame.width, frame.height);
        lists_.build(frame, draw, build_);
        gl::ScopedPass timing(frame.timer, "resolve");
        resetPassState();
        bindOutputFramebuffer();
        lists_.bindBuffers();
        glUseProgram(resolve_.id());
        glUniform1i(resolve_.uniform("u_width"), width_);
        glUniform3fv(resolve_.uniform("u_background"), 1, &frame.background[0]);
        drawFullscreen();
        glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
        GLuint counters[4] = {};
        glGetNamedBufferSubData(lists_.counters().id(), 0, sizeof(counters), counters);
        maxFragments_ = counters[1];
    }

private:
    ABufferLists lists_;
    gl::Program build_, resolve_;
    unsigned maxFragments_ = 0;
};

}  // namespace

std::unique_ptr<OitMethod> createAbufferMethod(const SurfaceShader& surface, const MethodOptions& options) {
    return std::make_unique<AbufferMethod>(surface, options);
}

}  // namespace starnt
