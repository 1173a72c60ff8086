// The temporal part of a neural method (docs/DESIGN.md, "Temporal reprojection") behind one small interface: which frames
// are real, a copy of the last real frame, its reprojection on interpolated frames, and the
// real- and interpolated-frame timing that `--temporal auto` needs.
//
//   TemporalFrames temporal(options);                    // with a current GL context
//   if (temporal.beginFrame(w, h)) {                     // real frame: full pipeline
//       ... passes, inference, composite into output, tiles ...
//       temporal.endRealFrame(output, nearestDepth, proj * view, w, h);
//   } else {
//       temporal.interpolate(proj * view, output, frame.timing);   // no geometry, no inference
//   }
#pragma once
#include <memory>

#include <glm/glm.hpp>

#include "gl/gpu_timer.hpp"
#include "methods/neural/temporal/corrected_frames.hpp"
#include "methods/neural/temporal/frame_clock.hpp"
#include "methods/neural/temporal/reprojector.hpp"
#include "methods/neural/temporal/temporal_schedule.hpp"

namespace starnt {

class TemporalFrames {
public:
    // Throws starnt::Error for an interval outside 1..4 or a bad target rate. Needs a current GL
    // context (builds the reprojection programs; picks the timing source from the renderer).
    explicit TemporalFrames(const MethodOptions& options);

    // Starts a frame of the given size; true = render it for real. Always true for the first frame,
    // after reset(), and when the size differs from the kept real frame's.
    bool beginFrame(int width, int height);
    // After a real frame: keeps copies of its composite (RGBA32F) and pass-1 depth
    // (DEPTH_COMPONENT32F, 1 = far plane where no transparent fragment) with the view-projection it
    // used, and ends the real-frame time measurement (which includes this copy).
    // In refresh and correct modes `nearestTexture` (pass-1 colour + alpha) is required. In correct
    // mode `sumAlphaColor` / `transmittance` are pass 3's full-resolution sums (0 when pass 3 ran
    // reduced: the frame is kept without a correction) and `background` the frame's.
    void endRealFrame(GLuint compositeTexture, GLuint nearestDepthTexture, const glm::mat4& viewProj, int width,
                      int height, GLuint nearestTexture = 0, GLuint sumAlphaColor = 0, GLuint transmittance = 0,
                      const glm::vec3& background = glm::vec3(0.0f));
    // An interpolated frame: the kept real frame reprojected to `viewProj`, rendered into
    // `outputTexture` (a colour-renderable RGBA texture of the frame size; the framebuffer binding is
    // 0 afterwards). Timed as pass "reproject" when a timer is given.
    // Corrected frames only: the real frame's composite captures the correction itself
    // (CorrectedFrames::beginFusedCapture); endRealFrameFused then keeps the frame instead of
    // endRealFrame.
    temporal::CorrectedFrames::FusedTargets beginFusedCapture(GLenum compositeFormat, GLuint depth, int width, int height,
                                                             const glm::mat4& viewProj);
    void endRealFrameFused();
    void interpolate(const glm::mat4& viewProj, GLuint outputTexture, PassTimingHook* timer = nullptr);
    // A refresh frame: `nearestTexture` is pass 1 rendered at `viewProj` (the caller renders it) and
    // `nearestDepth` its depth;
    // what lay behind the kept frame's nearest layer is reprojected under it. Timed as "reproject".
    void interpolateRefresh(const glm::mat4& viewProj, GLuint nearestTexture, GLuint nearestDepth,
                            const glm::vec3& background, GLuint outputTexture, PassTimingHook* timer = nullptr);
    // A corrected frame (correct mode): `nearest` / `nearestDepth` pass 1 and `sumAlphaColor` /
    // `transmittance` pass 3 at full resolution, rendered at `viewProj` by the caller. Timed as
    // "reproject".
    void interpolateCorrected(const glm::mat4& viewProj, GLuint nearest, GLuint nearestDepth, GLuint sumAlphaColor,
                              GLuint transmittance, const glm::vec3& background, GLuint outputTexture,
                              PassTimingHook* timer = nullptr);
    NeuralOptions::TemporalMode mode() const { return mode_; }
    // Interpolated frames render pass 1 fresh (refresh, correct) and pass 3 too (correct).
    bool refreshes() const { return mode_ == NeuralOptions::TemporalMode::Refresh; }
    bool corrects() const { return mode_ == NeuralOptions::TemporalMode::Correct; }

    // False for a fixed interval of 1: then nothing is kept (no copy, no memory).
    bool interpolates() const { return schedule_.isAuto() || schedule_.interval() > 1; }
    bool lastWasInterpolated() const { return lastInterpolated_; }
    // The interval of the current group (1 real + interval-1 interpolated frames).
    int interval() const { return schedule_.groupInterval(); }
    // Means of the recent real- and interpolated-frame times auto mode uses (0 before the first
    // measurement). An interpolated frame is timed from beginFrame to the end of interpolate /
    // interpolateRefresh, so a refresh frame's pass 1 counts.
    double averageRealFrameMs() const { return schedule_.averageRealFrameMs(); }
    double averageInterpolatedFrameMs() const { return schedule_.averageInterpolatedFrameMs(); }
    // Forgets the kept frame and the timing; the next frame is real.
    void reset();
    size_t gpuMemoryBytes() const {
        return (reprojector_ ? reprojector_->gpuMemoryBytes() : 0) + (corrected_ ? corrected_->gpuMemoryBytes() : 0);
    }
    void addMemoryTargets(OitMethod::MemoryTargets& out) const {
        if (corrected_) corrected_->addMemoryTargets(out);
        if (reprojector_) reprojector_->addMemoryTargets(out);
    }

private:
    TemporalSchedule schedule_;
    bool hasKeptFrame() const {
        return corrected_ ? corrected_->hasFrame() : reprojector_ && reprojector_->hasFrame();
    }
    // The one the mode uses, built only when frames are interpolated (its programs compile then).
    std::unique_ptr<temporal::Reprojector> reprojector_;     // warp and refresh modes
    std::unique_ptr<temporal::CorrectedFrames> corrected_;  // correct mode
    temporal::FrameClock clock_;
    bool lastInterpolated_ = false;
    NeuralOptions::TemporalMode mode_;
    bool skipEmptyPixels_ = true;  // NeuralOptions::skipEmptyPixels
};

}  // namespace starnt
