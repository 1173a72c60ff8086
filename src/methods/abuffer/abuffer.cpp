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
          lists_(false, options),
          build_(buildGeometryProgram("abuffer_build", "methods/abuffer/abuffer_build.frag.glsl")),
          resolve_(gl::buildComputeProgram("abuffer_resolve", gl::embeddedSource("methods/abuffer/abuffer_resolve.comp.glsl"))) {}

    std::string name() const override { return "abuffer"; }
    size_t gpuMemoryBytes() const override { return outputBytes() + lists_.gpuMemoryBytes(); }
    MemoryTargets gpuMemoryTargets() const override { return {{"output", outputBytes()}, {"fragment_lists", lists_.gpuMemoryBytes()}}; }

    FrameStats lastFrameStats() const override {
        FrameStats stats;
        stats.abuffer = AbufferFrameStats{uint64_t(lists_.fragmentCount()), uint64_t(lists_.capacity()),
                                          uint32_t(lists_.regrows())};
        return stats;
    }

    void renderFrame(const FrameDesc& frame, const DrawCallback& draw) override {
        resizeOutput(frame.width, frame.height);
        lists_.build(frame, draw, build_, &opaque_);
        gl::ScopedPass timing(frame.timing, "resolve");
        lists_.bindBuffers();
        glUseProgram(resolve_.id());
        glUniform2i(resolve_.uniform("u_size"), width_, height_);
        bindBackground(resolve_);
        glBindImageTexture(0, output_.id(), 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA32F);
        glDispatchCompute(GLuint((width_ + 7) / 8), GLuint((height_ + 7) / 8), 1);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_FRAMEBUFFER_BARRIER_BIT);
    }

private:
    ABufferLists lists_;
    gl::Program build_, resolve_;
};

}  // namespace

std::unique_ptr<OitMethod> createAbufferMethod(const SurfaceShader& surface, const MethodOptions& options) {
    return std::make_unique<AbufferMethod>(surface, options);
}

}  // namespace starnt
