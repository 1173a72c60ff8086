// Moment-based OIT (Muenstermann, Krumpen, Klein, Peters 2018): two geometry passes and a resolve.
//   pass 1 "moments":   additive, no depth test: b_0 and the power or trigonometric moments of
//                       optical depth over the warped depth (mboit_settings.hpp, mboit_moments.frag)
//   pass 2 "shade":     additive: sum a T(z) (C, 1), T reconstructed from the moments at the
//                       fragment's depth (mboit_reconstruct.glsl)
//   "resolve":          (1 - exp(-b_0)) * sum(a T C) / sum(a T) + exp(-b_0) * background
// 32-bit float targets throughout; no interlock or ordering needed.
#include <cmath>

#include "methods/common/method_base.hpp"
#include "methods/mboit/mboit_settings.hpp"
#include "methods/registry.hpp"
#include "starnt/error.hpp"

namespace starnt {
namespace {

using mboit::MomentSetting;

bool needsExtraTarget(const MomentSetting& s) { return s.count == 6 || s.count == 3; }

std::string defines(const MomentSetting& s) {
    return "#define MBOIT_TRIG " + std::to_string(s.trigonometric ? 1 : 0) + "\n#define MBOIT_COUNT " +
           std::to_string(s.count) + "\n#define MBOIT_ORDER " + std::to_string(s.order) + "\n#define MBOIT_EXTRA " +
           std::to_string(needsExtraTarget(s) ? 1 : 0) + "\n";
}

class MboitMethod final : public MethodBase {
public:
    MboitMethod(const SurfaceShader& surface, const MethodOptions& options)
        : MethodBase(surface),
          setting_(mboit::momentSetting(mboit::parseMomentKind(options.mboit.moments))),
          moments_(buildGeometryProgram("mboit_moments", "methods/mboit/mboit_moments.frag.glsl", defines(setting_))),
          shade_(buildGeometryProgram("mboit_shade", "methods/mboit/mboit_shade.frag.glsl", defines(setting_))),
          resolve_(buildFullscreenProgram("mboit_resolve", "methods/mboit/mboit_resolve.frag.glsl")) {}

    std::string name() const override { return "mboit"; }
    size_t gpuMemoryBytes() const override {
        return outputBytes() + b0_.bytes() + moments_tex_.bytes() + extra_.bytes() + accum_.bytes() + clears_.bytes();
    }
    MemoryTargets gpuMemoryTargets() const override {
        return {{"output", outputBytes()}, {"b0", b0_.bytes()}, {"moments", moments_tex_.bytes()},
                {"moments_extra", extra_.bytes()}, {"accum", accum_.bytes()}, {"clear_strips", clears_.bytes()}};
    }
    FrameStats lastFrameStats() const override {
        FrameStats stats;
        stats.mboit = MboitFrameStats{setting_.name};
        return stats;
    }

    void renderFrame(const FrameDesc& frame, const DrawCallback& draw) override {
        if (resizeOutput(frame.width, frame.height)) {
            b0_ = gl::Texture2D(GL_R32F, width_, height_);
            moments_tex_ = gl::Texture2D(GL_RGBA32F, width_, height_);
            if (needsExtraTarget(setting_)) {
                extra_ = gl::Texture2D(GL_RG32F, width_, height_);
                momentsFb_ = gl::makeFramebuffer({&b0_, &moments_tex_, &extra_});
            } else {
                momentsFb_ = gl::makeFramebuffer({&b0_, &moments_tex_});
            }
            accum_ = gl::Texture2D(GL_RGBA32F, width_, height_);
            accumFb_ = gl::makeFramebuffer({&accum_});
        }
        // near/far of a perspective projection for the logarithmic depth warp; an affine one
        // (orthographic: its clip w does not depend on depth) has depth linear in distance already,
        // and is warped linearly (mboit_common.glsl), as the MBOIT paper does for orthographic views.
        const float p22 = frame.projection[2][2], p32 = frame.projection[3][2];
        const bool affine = frame.projection[2][3] == 0.0f;
        float warp[2] = {0.0f, 1.0f};
        if (!affine) {
            const float nearPlane = p32 / (p22 - 1.0f);
            // An infinite far plane (p22 = -1): the warp's logarithm ends 10^7 near planes away.
            float farPlane = p32 / (p22 + 1.0f);
            if (!(farPlane > 0.0f && farPlane < nearPlane * 1e7f)) farPlane = nearPlane * 1e7f;
            if (!(nearPlane > 0.0f && farPlane > nearPlane)) throw Error("mboit: needs a perspective projection with 0 < near < far");
            warp[0] = std::log(nearPlane);
            warp[1] = 2.0f / std::log(farPlane / nearPlane);
        }
        auto setWarp = [&](const gl::Program& p) {
            glUniform2f(p.uniform("u_projZ"), p22, p32);
            glUniform1i(p.uniform("u_affine"), affine);
            glUniform2fv(p.uniform("u_warp"), 1, warp);
            glUniform1f(p.uniform("u_wrapAngle"), mboit::kWrappingZoneAngle);
        };
        const float zero[4] = {0, 0, 0, 0};
        resetPassState();
        {
            gl::ScopedPass timing(frame.timing, "moments");
            glBindFramebuffer(GL_FRAMEBUFFER, momentsFb_.id());
            glViewport(0, 0, width_, height_);
            for (int i = 0; i < (extra_ ? 3 : 2); ++i) clears_.color(i, zero);
            opaque_.beginDepthTest(momentsFb_.id(), width_, height_, width_, height_);
            glEnable(GL_BLEND);
            glBlendFunc(GL_ONE, GL_ONE);
            glUseProgram(moments_.id());
            setWarp(moments_);
            glUniform1f(moments_.uniform("u_maxAlpha"), mboit::kMaxAlpha);
            runGeometryPass("mboit_moments", moments_, frame, draw);
            opaque_.endDepthTest(momentsFb_.id());
            resetPassState();
        }
        {
            gl::ScopedPass timing(frame.timing, "shade");
            glBindFramebuffer(GL_FRAMEBUFFER, accumFb_.id());
            glViewport(0, 0, width_, height_);
            clears_.color(0, zero);
            opaque_.beginDepthTest(accumFb_.id(), width_, height_, width_, height_);
            glEnable(GL_BLEND);
            glBlendFunc(GL_ONE, GL_ONE);
            glUseProgram(shade_.id());
            setWarp(shade_);
            glUniform1f(shade_.uniform("u_momentBias"), setting_.bias);
            glUniform1fv(shade_.uniform("u_biasVector"), 6, setting_.biasVector);
            glUniform1f(shade_.uniform("u_overestimation"), mboit::kOverestimation);
            gl::bindTexture(0, b0_.id());
            gl::bindTexture(1, moments_tex_.id());
            if (extra_) gl::bindTexture(2, extra_.id());
            runGeometryPass("mboit_shade", shade_, frame, draw);
            opaque_.endDepthTest(accumFb_.id());
            resetPassState();
        }
        {
            gl::ScopedPass timing(frame.timing, "resolve");
            bindOutputFramebuffer();
            glUseProgram(resolve_.id());
            gl::bindTexture(0, b0_.id());
            gl::bindTexture(1, accum_.id());
            bindBackground(resolve_);
            drawFullscreen();
        }
    }

private:
    const MomentSetting& setting_;
    gl::Program moments_, shade_, resolve_;
    gl::Texture2D b0_, moments_tex_, extra_, accum_;
    gl::FramebufferHandle momentsFb_, accumFb_;
};

}  // namespace

std::unique_ptr<OitMethod> createMboitMethod(const SurfaceShader& surface, const MethodOptions& options) {
    return std::make_unique<MboitMethod>(surface, options);
}

}  // namespace starnt
