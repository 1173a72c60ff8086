// The temporal part of a neural method (docs/DESIGN.md, "Temporal reprojection") behind one small interface: which frames
// are real, a copy of the last real frame, its reprojection on interpolated frames, and the
// real- and interpolated-frame timing that `--temporal auto` needs.
//
//   TemporalFrames temporal(options);                    // with a current GL context
//   if (temporal.beginFrame(w, h)) {                     // real frame: full pipeline
//       ... passes, inference, composite into output, tiles ...
//       temporal.endRealFrame(output, targets, proj * view, w, h, background);
//   } else {
//       ... the passes temporal.interpolatedPasses() names, at this frame's camera ...
//       temporal.interpolate(proj * view, targets, background, output, frame.timing);
//   }
// The mode (warp, refresh, correct) is TemporalFrames' business: the caller renders the passes it
// asks for and hands over the targets.
#pragma once
#include <array>
#include <memory>

#include <glm/glm.hpp>

#include "gl/gpu_timer.hpp"
#include "methods/neural/temporal/corrected_frames.hpp"
#include "methods/neural/temporal/frame_clock.hpp"
#include "methods/neural/temporal/reprojector.hpp"
#include "methods/neural/temporal/temporal_schedule.hpp"

namespace starnt {

// The pass targets of a frame, as the temporal frames read them (0 where that pass did not run).
struct TemporalPassTargets {
    GLuint nearest = 0;        // pass 1: C1, a1 (full resolution)
    GLuint nearestDepth = 0;   // pass 1: DEPTH_COMPONENT32F, 1 = far plane where nothing was drawn
    GLuint sumAlphaColor = 0;  // pass 3 at full resolution: sum a C, sum a (0 when it ran reduced)
    GLuint transmittance = 0;  // pass 3 at full resolution: prod (1 - a)
    // Corrected frames in one pass: pass 3's nearest fragment (packed_nearest.glsl); nearestDepth
    // then holds pass 3's cover depth (below 1 where a fragment was kept).
    GLuint packedNearest = 0;
    // Corrected frames of the tail-moment methods: pass 3's moments behind the reference depth
    // (ordered_behind.glsl).
    GLuint behindMoment1 = 0, behindMoment2 = 0;
    // Three layers (packedNearest the nearest two): pass 3's third layer and the reference depth, RGBA32UI.
    GLuint thirdLayer = 0;
    // Three layers, where the composite clears pass 3's targets (NeuralPasses::compositeClearsTargets):
    // NeuralPasses::packedTargets(); all 0 where pass 3 clears them itself.
    std::array<GLuint, 5> clearByComposite{};
};

class TemporalFrames {
public:
    // Throws starnt::Error for an interval outside 1..kMaxTemporalInterval or a bad target rate. Needs a current GL
    // context (builds the reprojection programs; picks the timing source from the renderer).
    // `orderedBehind`: the method has tail moments, and its corrected frames weigh what lies behind
    // the nearest layer by depth (CorrectedFrames' `ordered`).
    // orderedBehind, layers: temporal::CorrectedFrames' ordered and layers.
    // `layeredEveryFrame` (kbuffer-moments; layers 3): every frame is interpolated in this sense, its
    // one pass and composite the three-layer corrected frame's, with no real frame: the reference
    // depth of a frame's moments is made from the last frame's layers (startLayered).
    explicit TemporalFrames(const MethodOptions& options, bool orderedBehind = false, int layers = 1,
                            bool layeredEveryFrame = false);

    // Starts a frame of the given size; true = render it for real. Always true for the first frame,
    // after reset(), and when the size differs from the kept real frame's.
    bool beginFrame(int width, int height);
    // After a real frame: keeps what its interpolated frames need of its composite (RGBA32F or
    // RGBA16F) and `passes` with the view-projection it used, and ends the real-frame time
    // measurement (which includes this). Every mode needs pass 1's depth; refresh and correct modes
    // pass 1's colour; correct mode pass 3's sums (without them the frame is kept without a
    // correction) and the frame's `background`.
    void endRealFrame(GLuint compositeTexture, const TemporalPassTargets& passes, const glm::mat4& viewProj, int width,
                      int height, const OpaqueScene& background = OpaqueScene(), bool premultipliedHistory = false);
    // The passes an interpolated frame renders at its own camera before interpolate(): none (warp),
    // pass 1 (refresh), passes 1 and 3 (correct with NeuralOptions::correctedOnePass off; pass 3
    // with its sums only), pass 3 alone finding the nearest fragment too (correct, the default).
    enum class Passes { None, Nearest, NearestAndSums, PackedNearestAndSums };
    Passes interpolatedPasses() const;
    // An interpolated frame at `viewProj` from the kept real frame and the passes
    // interpolatedPasses() named (`passes`, rendered at `viewProj` by the caller), into
    // `outputTexture` (a colour-renderable RGBA texture of the frame size; the framebuffer binding is
    // 0 afterwards). Timed as pass "reproject" when a timer is given.
    void interpolate(const glm::mat4& viewProj, const TemporalPassTargets& passes, const OpaqueScene& background,
                     GLuint outputTexture, PassTimingHook* timer = nullptr);
    // Corrected frames only: the real frame's composite captures the correction itself
    // (CorrectedFrames::beginFusedCapture); endRealFrameFused then keeps the frame instead of
    // endRealFrame.
    temporal::CorrectedFrames::FusedTargets beginFusedCapture(GLenum compositeFormat, GLuint depth, int width, int height,
                                                             const glm::mat4& viewProj);
    void endRealFrameFused();
    NeuralOptions::TemporalMode mode() const { return mode_; }
    // Ordered corrected frames: the depth an interpolated frame's pass 3 takes its moments behind
    // (CorrectedFrames::reference()); 0 otherwise.
    GLuint behindReference() const { return corrected_ ? corrected_->reference() : 0; }
    // Ordered corrected frames, in a real frame: CorrectedFrames::prepareReference.
    GLuint prepareReference(GLuint depth, int width, int height) {
        return corrected_ ? corrected_->prepareReference(depth, width, height) : 0;
    }
    // Interpolated frames render pass 1 fresh (refresh, correct) and pass 3 too (correct).
    bool refreshes() const { return mode_ == NeuralOptions::TemporalMode::Refresh; }
    bool corrects() const { return layered_ || mode_ == NeuralOptions::TemporalMode::Correct; }

    // False for a fixed interval of 1: then nothing is kept (no copy, no memory).
    bool interpolates() const { return layered_ || schedule_.isAuto() || schedule_.interval() > 1; }
    // Layered every frame: true once after the first frame, a reset or a new size, when no last
    // frame made the reference depth yet; the caller then renders the frame's pass and composite
    // twice, the first only to make it (its output is drawn over).
    bool takeLayeredPriming() {
        const bool priming = priming_;
        priming_ = false;
        return priming;
    }
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
    bool onePass_ = true;          // NeuralOptions::correctedOnePass
    bool layered_ = false;         // layeredEveryFrame
    bool priming_ = false;         // takeLayeredPriming
};

}  // namespace starnt
