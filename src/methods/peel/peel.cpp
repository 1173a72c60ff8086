// Front-to-back depth peeling: one geometry pass per layer, each layer added under the previous
// ones. With peelLayers = 0 it peels until a layer comes back empty (occlusion query), which is
// exact; with k > 0 it stops after k layers (exact when k >= the depth complexity D).
#include "methods/common/method_base.hpp"
#include "methods/registry.hpp"
#include "starnt/error.hpp"

namespace starnt {
namespace {

constexpr int kMaxLayers = 4096;

class PeelMethod final : public MethodBase {
public:
    PeelMethod(const SurfaceShader& surface, const MethodOptions& options)
        : MethodBase(surface),
          layersWanted_(options.peel.layers),
          layer_(surface_, "peel_layer", "methods/peel/peel_layer.frag.glsl"),
          accumulate_(buildFullscreenProgram("peel_accumulate", "methods/peel/peel_accumulate.frag.glsl")),
          composite_(buildFullscreenProgram("peel_composite", "methods/peel/peel_composite.frag.glsl")) {
        if (layersWanted_ < 0 || layersWanted_ > kMaxLayers) {
            throw Error("peel layers must be in 0.." + std::to_string(kMaxLayers) + " (0 = until empty)");
        }
        GLuint q = 0;
        glGenQueries(1, &q);
        query_ = gl::QueryHandle(q);
    }

    std::string name() const override { return "peel"; }
    size_t gpuMemoryBytes() const override {
        return outputBytes() + layerColor_.bytes() + depth_[0].bytes() + depth_[1].bytes() + accum_.bytes() + clears_.bytes();
    }
    FrameStats lastFrameStats() const override {
        FrameStats stats;
        stats.peel = PeelFrameStats{layersRendered_};
        return stats;
    }

    void renderFrame(const FrameDesc& frame, const DrawCallback& draw) override {
        if (resizeOutput(frame.width, frame.height)) {
            layerColor_ = gl::Texture2D(GL_RGBA32F, width_, height_);
            accum_ = gl::Texture2D(GL_RGBA32F, width_, height_);
            for (int i = 0; i < 2; ++i) {
                depth_[i] = gl::Texture2D(GL_DEPTH_COMPONENT32F, width_, height_);
                layerFb_[i] = gl::makeFramebuffer({&layerColor_}, &depth_[i]);
            }
            accumFb_ = gl::makeFramebuffer({&accum_});
        }
        checkNoOcclusionQueryActive();
        const gl::QueryBufferUnbound queryBuffer;  // (an engine's would receive the results)
        peelLayers(frame, draw);
    }

private:
    // GL allows one occlusion query at a time: with the engine's running, this method's would fail
    // (and its end would end the engine's), so it is refused by name.
    static void checkNoOcclusionQueryActive() {
        std::vector<std::pair<GLenum, const char*>> targets = {{GL_ANY_SAMPLES_PASSED, "GL_ANY_SAMPLES_PASSED"},
                                                                {GL_ANY_SAMPLES_PASSED_CONSERVATIVE, "GL_ANY_SAMPLES_PASSED_CONSERVATIVE"}};
        if (!gl::isEs()) targets.emplace_back(GL_SAMPLES_PASSED, "GL_SAMPLES_PASSED");
        for (const auto& [target, name] : targets) {
            GLint current = 0;
            glGetQueryiv(target, GL_CURRENT_QUERY, &current);
            if (current != 0) {
                throw Error(std::string("peel counts each layer's samples with an occlusion query, and the engine's ") + name +
                            " query is active: end it before render()");
            }
        }
    }

    void peelLayers(const FrameDesc& frame, const DrawCallback& draw) {
        resetPassState();
        glBindFramebuffer(GL_FRAMEBUFFER, accumFb_.id());
        glViewport(0, 0, width_, height_);
        const float start[4] = {0, 0, 0, 1};
        clears_.color(0, start);

        const int limit = layersWanted_ > 0 ? layersWanted_ : kMaxLayers;
        layersRendered_ = 0;
        for (int layer = 0; layer < limit; ++layer) {
            const int cur = layer & 1;
            GLuint anySamples = 0;
            {
                gl::ScopedPass timing(frame.timing, "peel");
                glBindFramebuffer(GL_FRAMEBUFFER, layerFb_[cur].id());
                const float clearColor[4] = {0, 0, 0, 0};
                const float clearDepth = 1.0f;
                clears_.color(0, clearColor);
                glClearBufferfv(GL_DEPTH, 0, &clearDepth);
                glEnable(GL_DEPTH_TEST);
                glDepthFunc(GL_LESS);
                glDepthMask(GL_TRUE);
                const gl::Program& program = opaque_.clipInShader(layer_, width_, height_, width_, height_);
                glUniform1i(program.uniform("u_firstLayer"), layer == 0 ? 1 : 0);
                gl::bindTexture(0, depth_[cur ^ 1].id());
                glBeginQuery(GL_ANY_SAMPLES_PASSED, query_.id());
                try {
                    runGeometryPass("peel", program, frame, draw);
                } catch (...) {
                    glEndQuery(GL_ANY_SAMPLES_PASSED);  // an engine's exception must not leave the query running
                    resetPassState();
                    throw;
                }
                glEndQuery(GL_ANY_SAMPLES_PASSED);
                resetPassState();
                glGetQueryObjectuiv(query_.id(), GL_QUERY_RESULT, &anySamples);
            }
            if (!anySamples) break;
            ++layersRendered_;
            gl::ScopedPass timing(frame.timing, "accumulate");
            glBindFramebuffer(GL_FRAMEBUFFER, accumFb_.id());
            glEnable(GL_BLEND);
            glBlendFuncSeparate(GL_DST_ALPHA, GL_ONE, GL_ZERO, GL_ONE_MINUS_SRC_ALPHA);
            glUseProgram(accumulate_.id());
            gl::bindTexture(0, layerColor_.id());
            drawFullscreen();
            resetPassState();
        }
        gl::ScopedPass timing(frame.timing, "composite");
        bindOutputFramebuffer();
        glUseProgram(composite_.id());
        gl::bindTexture(0, accum_.id());
        bindBackground(composite_);
        drawFullscreen();
    }

    int layersWanted_;
    int layersRendered_ = 0;
    SurfaceProgram layer_;  // clips by the opaque depth in its shader (its depth target is its own)
    gl::Program accumulate_, composite_;
    gl::Texture2D layerColor_, accum_, depth_[2];
    gl::FramebufferHandle layerFb_[2], accumFb_;
    gl::QueryHandle query_;
};

}  // namespace

std::unique_ptr<OitMethod> createPeelMethod(const SurfaceShader& surface, const MethodOptions& options) {
    return std::make_unique<PeelMethod>(surface, options);
}

}  // namespace starnt
