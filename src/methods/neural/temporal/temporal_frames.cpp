#include "methods/neural/temporal/temporal_frames.hpp"

#include "starnt/error.hpp"

namespace starnt {

TemporalFrames::TemporalFrames(const MethodOptions& options, bool orderedBehind, int layers, bool layeredEveryFrame)
    : schedule_(options),
      clock_(gl::wallClockTimingNeeded()),
      mode_(options.neural.temporalMode),
      skipEmptyPixels_(options.neural.skipEmptyPixels),
      onePass_(options.neural.correctedOnePass || layeredEveryFrame),
      layered_(layeredEveryFrame) {
    if (layered_ && (!orderedBehind || layers != 3)) throw Error("internal: frames layered every frame need three ordered layers");
    if (!interpolates()) return;
    if (corrects()) corrected_ = std::make_unique<temporal::CorrectedFrames>(orderedBehind, layers);
    else reprojector_ = std::make_unique<temporal::Reprojector>();
}

bool TemporalFrames::beginFrame(int width, int height) {
    if (auto m = clock_.take()) {
        if (m->real) schedule_.recordRealFrameMs(m->ms);
        else schedule_.recordInterpolatedFrameMs(m->ms);
    }
    // A frame of another size cannot be reprojected from the kept one.
    const int keptWidth = corrected_ ? corrected_->width() : reprojector_ ? reprojector_->width() : 0;
    const int keptHeight = corrected_ ? corrected_->height() : reprojector_ ? reprojector_->height() : 0;
    if (hasKeptFrame() && (width != keptWidth || height != keptHeight)) reset();
    if (layered_) {
        if (!corrected_->hasFrame()) {
            corrected_->startLayered(width, height);
            priming_ = true;
        }
        lastInterpolated_ = true;
        return false;
    }
    bool real = schedule_.nextFrameIsReal();
    // The schedule cannot know whether the kept frame exists (e.g. a real frame that threw).
    if (!real && !hasKeptFrame()) {
        schedule_.reset();
        real = schedule_.nextFrameIsReal();
    }
    lastInterpolated_ = !real;
    // Only the fixed schedule needs no timing; measuring costs a glFinish on software.
    if (schedule_.isAuto()) clock_.start(real);
    return real;
}

void TemporalFrames::endRealFrame(GLuint compositeTexture, const TemporalPassTargets& passes, const glm::mat4& viewProj,
                                  int width, int height, const OpaqueScene& background, bool premultipliedHistory) {
    if (lastInterpolated_) throw Error("internal: TemporalFrames::endRealFrame on an interpolated frame");
    if (!interpolates()) return;  // every frame is real: nothing to keep
    if ((refreshes() || corrects()) && !passes.nearest) {
        throw Error("internal: refresh and corrected frames need the real frame's nearest layer");
    }
    if (corrects()) {
        corrected_->capture(compositeTexture, passes.nearestDepth, passes.nearest, passes.sumAlphaColor, passes.transmittance,
                           width, height, viewProj, background);
    } else {
        reprojector_->capture(compositeTexture, passes.nearestDepth, width, height, viewProj, refreshes() ? passes.nearest : 0,
                              premultipliedHistory ? &background : nullptr);
    }
    clock_.stop();
}

TemporalFrames::Passes TemporalFrames::interpolatedPasses() const {
    if (corrects()) return onePass_ ? Passes::PackedNearestAndSums : Passes::NearestAndSums;
    return refreshes() ? Passes::Nearest : Passes::None;
}

void TemporalFrames::interpolate(const glm::mat4& viewProj, const TemporalPassTargets& passes, const OpaqueScene& background,
                                 GLuint outputTexture, PassTimingHook* timer) {
    if (!lastInterpolated_) throw Error("internal: TemporalFrames::interpolate on a real frame");
    {
        gl::ScopedPass timing(timer, "reproject");
        if (corrects()) {
            // Corrected: the closed form behind the fresh nearest layer plus the kept correction.
            if (passes.packedNearest) {
                // The next frame's reference depth only where a next interpolated frame reads it: the
                // frame after a group's last is real, and makes its own (K = 2: never).
                corrected_->compositePacked(viewProj, passes.packedNearest, passes.nearestDepth, passes.sumAlphaColor,
                                            passes.transmittance, background, outputTexture, passes.behindMoment1,
                                            passes.behindMoment2, passes.thirdLayer,
                                            passes.clearByComposite[0] ? std::span<const GLuint>(passes.clearByComposite)
                                                                       : std::span<const GLuint>(),
                                            layered_ || !schedule_.lastOfGroup());
            } else {
                corrected_->composite(viewProj, passes.nearest, passes.nearestDepth, passes.sumAlphaColor, passes.transmittance,
                                      background, outputTexture, passes.behindMoment1, passes.behindMoment2);
            }
        } else if (refreshes()) {
            // Refresh: the fresh nearest layer over what lay behind it, reprojected.
            reprojector_->reprojectRefresh(viewProj, passes.nearest, skipEmptyPixels_ ? passes.nearestDepth : 0, background,
                                          outputTexture);
        } else {
            reprojector_->reproject(viewProj, outputTexture, background);  // warp: the kept composite alone
        }
    }
    clock_.stop();
}

temporal::CorrectedFrames::FusedTargets TemporalFrames::beginFusedCapture(GLenum compositeFormat, GLuint depth, int width,
                                                                         int height, const glm::mat4& viewProj) {
    if (lastInterpolated_ || !corrected_) throw Error("internal: a fused capture outside a real frame with corrected frames");
    return corrected_->beginFusedCapture(compositeFormat, depth, width, height, viewProj);
}

void TemporalFrames::endRealFrameFused() {
    if (lastInterpolated_ || !corrected_) throw Error("internal: a fused capture outside a real frame with corrected frames");
    corrected_->endFusedCapture();
    clock_.stop();
}

void TemporalFrames::reset() {
    schedule_.reset();
    if (reprojector_) reprojector_->reset();
    if (corrected_) corrected_->reset();
    clock_.take();  // a measurement of before the reset no longer applies
    lastInterpolated_ = false;
    priming_ = false;
}

}  // namespace starnt
