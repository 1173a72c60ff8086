// A-buffer: exact ground truth. Per-pixel linked lists (abuffer_lists.*), then a full-screen
// resolve that sorts each list and composites it.
#include "methods/abuffer/abuffer_lists.hpp"
#include "methods/registry.hpp"
#include "starnt/error.hpp"

namespace starnt {
namespace {

// Largest per-pixel list the resolve sorts; a pixel deeper than this is an error, never a silently
// truncated list.
constexpr unsigned kMaxResolveArray = 8192;

class AbufferMethod final : public MethodBase {
public:
    AbufferMethod(const SurfaceShader& surface, const MethodOptions& options)
        : MethodBase(surface),
          lists_(*this, false, options),
          build_(buildGeometryProgram("abuffer_build", "methods/abuffer/abuffer_build.frag.glsl")) {
        buildResolve(64);
    }

    std::string name() const override { return "abuffer"; }
    size_t gpuMemoryBytes() const override { return outputBytes() + lists_.gpuMemoryBytes(); }

    nlohmann::json lastFrameStats() const override {
        return {{"max_fragments", maxFragments_},
                {"fragments", lists_.fragmentCount()},
                {"pool_capacity", lists_.capacity()},
                {"pool_regrows", lists_.regrows()},
                {"resolve_array", resolveArray_}};
    }

    void render(const FrameDesc& frame, const DrawCallback& draw) override {
        resizeOutput(frame.width, frame.height);
        lists_.build(frame, draw, build_);
        for (;;) {
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
            if (counters[2] == 0) break;
            unsigned needed = resolveArray_;
            while (needed < counters[2]) needed *= 2;
            if (needed > kMaxResolveArray) {
                throw Error("a pixel has " + std::to_string(counters[2]) + " fragments; the A-buffer resolve sorts at most " +
                            std::to_string(kMaxResolveArray));
            }
            buildResolve(needed);
            const GLuint zero = 0;
            glClearNamedBufferSubData(lists_.counters().id(), GL_R32UI, 8, 4, GL_RED_INTEGER, GL_UNSIGNED_INT, &zero);
        }
    }

private:
    void buildResolve(unsigned arraySize) {
        resolve_ = buildFullscreenProgram("abuffer_resolve", "methods/abuffer/abuffer_resolve.frag.glsl",
                                          "#define STARNT_ABUFFER_MAX_SORT " + std::to_string(arraySize) + "\n");
        resolveArray_ = arraySize;
    }

    ABufferLists lists_;
    gl::Program build_, resolve_;
    unsigned resolveArray_ = 0;
    unsigned maxFragments_ = 0;
};

}  // namespace

std::unique_ptr<OitMethod> createAbufferMethod(const SurfaceShader& surface, const MethodOptions& options) {
    return std::make_unique<AbufferMethod>(surface, options);
}

}  // namespace starnt
