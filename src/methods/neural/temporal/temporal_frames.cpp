#include "methods/neural/temporal/temporal_frames.hpp"

#include "starnt/error.hpp"

namespace starnt {

TemporalFrames::TemporalFrames(const MethodOptions& options)
    : schedule_(options),
      clock_(gl::wallClockTimingNeeded()),
      refresh_(options.neural.temporalMode == NeuralOptions::TemporalMode::Refresh),
      skipEmptyPixels_(options.neural.skipEmptyPixels) {}

bool TemporalFrames::beginFrame(int width, int height) {
    if (auto m = clock_.take()) {
        if (m->real) schedule_.recordRealFrameMs(m->ms);
        else schedule_.recordInterpolatedFrameMs(m->ms);
    }
    // A frame of another size cannot be reprojected from the kept one.
    if (reprojector_.hasFrame() && (width != reprojector_.width() || height != reprojector_.height())) reset();
    bool real = schedule_.nextFrameIsReal();
    // The schedule cannot know whether the kept frame exists (e.g. a real frame that threw).
    if (!real && !reprojector_.hasFrame()) {
        schedule_.reset();
        real = schedule_.nextFrameIsReal();
    }
    lastInterpolated_ = !real;
    // Only the fixed schedule needs no timing; measuring costs a glFinish on software.
    if (schedule_.isAuto()) clock_.start(real);
    return real;
}

void TemporalFrames::endRealFrame(GLuint compositeTexture, GLuint nearestDepthTexture, const glm::mat4& viewProj,
                                  int width, int height, GLuint nearestTexture) {
    if (lastInterpolated_) throw Error("internal: TemporalFrames::endRealFrame on an interpolated frame");
    if (!interpolates()) return;  // every frame is real: nothing to keep
    if (refresh_ && !nearestTexture) throw Error("internal: refresh frames need the real frame's nearest layer");
    reprojector_.capture(compositeTexture, nearestDepthTexture, width, height, viewProj, refresh_ ? nearestTexture : 0);
    clock_.stop();
}

void TemporalFrames::interpolate(const glm::mat4& viewProj, GLuint outputTexture, PassTimingHook* timer) {
    if (!lastInterpolated_) throw Error("internal: TemporalFrames::interpolate on a real frame");
    {
        gl::ScopedPass timing(timer, "reproject");
        reprojector_.reproject(viewProj, outputTexture);
    }
    clock_.stop();
}

void TemporalFrames::interpolateRefresh(const glm::mat4& viewProj, GLuint nearestTexture, GLuint nearestDepth,
                                        const glm::vec3& background, GLuint outputTexture, PassTimingHook* timer) {
    if (!lastInterpolated_) throw Error("internal: TemporalFrames::interpolateRefresh on a real frame");
    {
        gl::ScopedPass timing(timer, "reproject");
        reprojector_.reprojectRefresh(viewProj, nearestTexture, skipEmptyPixels_ ? nearestDepth : 0, background,
                                      outputTexture);
    }
    clock_.stop();
}

void TemporalFrames::reset() {
    schedule_.reset();
    reprojector_.reset();
    clock_.take();  // a measurement of before the reset no longer applies
    lastInterpolated_ = false;
}

}  // namespace starnt
