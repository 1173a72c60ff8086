#include "methods/neural/neural_method.hpp"

#include <algorithm>
#include <map>

#include "gl/shader.hpp"
#include "methods/common/method_base.hpp"
#include "methods/neural/empty_pixels.hpp"
#include "methods/neural/neural_passes.hpp"
#include "methods/neural/temporal/temporal_frames.hpp"
#include "methods/neural/tiles/tile_constants.h"
#include "methods/neural/tiles/tile_rules.hpp"
#include "methods/neural/tiles/tiles_gpu.hpp"
#include "starnt/bindings.h"
#include "starnt/error.hpp"

namespace starnt {
namespace {

// Texture unit of the corner network outputs in infer_fill.frag.glsl (after the NeuralInputUnit units).
constexpr GLuint kUnitCornerNetwork = STARNT_UNIT_CORNER_NETWORK;

// DFAOIT's narrow layers (NeuralPasses, "Narrow layers"): only where every pass runs at full
// resolution and nothing but the inference reads the layers (no tiles, no scale guard, no temporal
// frames), since the tiles, the tail resolve and the reprojection read the alphas from the colour
// targets. (NeuralPasses ignores the request with 32-bit targets.)
bool narrowLayersApply(const NeuralMethodConfig& config, const MethodOptions& o, bool spatial, bool corners) {
    const bool fullScales = o.neural.fixedScale2 == 0.0f || (o.neural.fixedScale2 == 1.0f && o.neural.fixedScale3 == 1.0f);
    return config.kind == nn::NetworkKind::DFAOIT && !spatial && !corners && fullScales &&
           o.neural.temporalInterval == 1 && !o.neural.temporalAuto;
}

class NeuralMethod final : public MethodBase {
public:
    NeuralMethod(const NeuralMethodConfig& config, const SurfaceShader& surface, const MethodOptions& options)
        : MethodBase(surface),
          config_(config),
          options_(validated(config, options)),
          spatial_(options.neural.spatial.value_or(config.spatialByDefault)),
          corners_(options.neural.inference == NeuralOptions::Inference::Corners),
          network_(loadMethodNetwork(config, options)),
          // Only DFAOIT's inputs read the unweighted colour sum of pass 3 (docs/DESIGN.md, "Pipeline and formats").
          passes_(surface, opaque_, config.kind == nn::NetworkKind::DFAOIT, options_.neural.targets,
                  narrowLayersApply(config, options_, spatial_, corners_), config.tailMoments),
          layers_(correctedLayers(config, options_)),
          temporal_(options_, config.tailMoments, layers_, config.layeredEveryFrame) {
        if (spatial_ || corners_) tiles_ = std::make_unique<tiles::GpuTiles>();
        shadingRates_ = shadingRatesApply();
        if (shadingRates_) tiles_->enableShadingRates();
        if (config_.layeredEveryFrame) passes_.packedPassOnly();
        if (temporal_.interpolates() && temporal_.corrects()) {
            if (layers_ == 3) {
                passes_.findThreeLayers(options_.neural.compositeClearsTargets);
                if (passes_.compositeClearsTargets() && skipEmpty() && !tiles_ && !config_.layeredEveryFrame) {
                    inference("infer_full_clears", true);
                }
            }
            else if (layers_ == 2) passes_.findTwoLayers();
            if (options_.neural.correctedOnePass) passes_.preparePackedNearestAndSums();
            else passes_.prepareNearestAndSums();
            if (config_.tailMoments && fusedCaptureApplies()) {
                // (the plain capture only where pass 3 lacks the draw buffers: built on first need)
                passes_.prepareRealBehindMoments();
                inference("infer_full_capture_ordered", true);
            } else if (keepsCorrection() && options_.neural.fusedCorrectionCapture && !corners_) {
                inference("infer_full_capture", true);
            }
        }
        // Compile up front what the frames will need, so no frame pays for a shader compile: the
        // full-resolution variant for the first frame (no tile history) and fixed 100 % scales,
        // the upsampling one when scales below 1 can occur.
        if (config_.layeredEveryFrame) return;  // no real frame, no inference
        const bool fixedFull = options_.neural.fixedScale2 == 1.0f && options_.neural.fixedScale3 == 1.0f;
        const bool mayReduce = options_.neural.fixedScale2 > 0.0f ? !fixedFull : spatial_;
        for (const char* stage : {"infer_full", "infer_corners", "infer_fill"}) {
            if (std::string(stage) != "infer_full" && !corners_) continue;
            if (options_.neural.fixedScale2 == 0.0f || fixedFull) inference(stage, true);
            if (mayReduce) inference(stage, false);
        }
    }

    std::string name() const override { return config_.name; }
    // The output of the last frame: a texture of its own or, mostly, a pass target it was written
    // over in place (NeuralPasses::outputSlot). Valid until the next render().
    GLuint outputTexture() const override { return out_.texture; }
    size_t gpuMemoryBytes() const override {
        return outputBytes() + passes_.gpuMemoryBytes() + cornerNetwork_.bytes() + overlay_.bytes() +
               (tiles_ ? tiles_->gpuMemoryBytes() : 0) + temporal_.gpuMemoryBytes();
    }
    MemoryTargets gpuMemoryTargets() const override {
        MemoryTargets out = {{"output", outputBytes()}};
        passes_.addMemoryTargets(out);
        out.emplace_back("corner_network", cornerNetwork_.bytes());
        if (tiles_) tiles_->addMemoryTargets(out);
        temporal_.addMemoryTargets(out);
        // Debug only: allocated on the first tileOverlayTexture() call (--tiles-image, the bench's
        // tile images, the viewer's tile view).
        out.emplace_back("tile_overlay_debug", overlay_.bytes());
        return out;
    }

    FrameStats lastFrameStats() const override {
        NeuralFrameStats n;
        n.network = nn::kindName(network_.kind);
        n.weightsTrainingSamples = network_.trainingSamples;
        n.peelEpsilon = NeuralPasses::kDefaultPeelEpsilon;
        n.spatial = spatial_;
        n.cornerInference = corners_;
        n.cornerInferenceUsed = cornersUsed_;
        // kbuffer-moments' frames are all of one kind, its own: none is interpolated.
        n.interpolated = temporal_.lastWasInterpolated() && !config_.layeredEveryFrame;
        n.temporalInterval = config_.layeredEveryFrame ? 1 : temporal_.interval();
        n.temporalMode = temporal_.mode();
        n.realFrameMsAverage = temporal_.averageRealFrameMs();
        n.interpolatedFrameMsAverage = temporal_.averageInterpolatedFrameMs();
        n.scalePass2 = scale2_;
        n.scalePass3 = scale3_;
        n.pass2Size = {passes_.pass2Size().width, passes_.pass2Size().height};
        n.pass3Size = {passes_.pass3Size().width, passes_.pass3Size().height};
        n.targets = options_.neural.targets;
        n.outputTarget = out_.name;
        if (tiles_) {
            tiles_->pollHistogram();
            NeuralFrameStats::Tiles t;
            if (tiles_->hasHistogram()) t.wBar = tiles_->wBar();
            t.levels = tiles_->histogram();
            t.scaleRule = options_.neural.scaleRule;
            t.tileSignal = options_.neural.tileSignal;
            t.upsample = options_.neural.upsample;
            t.scaleGuard = guarded();
            if (guarded()) {
                t.probeFrame = probe_ && !temporal_.lastWasInterpolated();
                t.probeInterval = probeInterval();
                // Asked for: whether this frame's pass 3 ran with the rates (false where the
                // driver lacks them, so a report cannot take the plain tiles for them).
                if (options_.neural.shadingRateImage != NeuralOptions::ShadingRateImage::Off) {
                    t.shadingRateImage = pass3Rates_ != 0 && !temporal_.lastWasInterpolated();
                }
                if (shadingRates_) t.shadingRateTiles = tiles_->shadingRateTiles();
                if (tiles_->hasGuard()) {
                    const tiles::ScaleGuard& g = tiles_->guard();
                    t.guard = NeuralFrameStats::Guard{g.occupied, g.energy2, g.energy3, g.loss2, g.loss3};
                }
            }
            n.tiles = t;
        }
        FrameStats stats;
        stats.neural = n;
        return stats;
    }

    GLuint tileOverlayTexture() override {
        if (!tiles_ || !out_.texture) return 0;
        if (overlay_.width() != width_ || overlay_.height() != height_) overlay_ = gl::Texture2D(GL_RGBA32F, width_, height_);
        tiles_->renderOverlay(out_.texture, overlay_.id());
        return overlay_.id();
    }

    void resetHistory() override {
        if (tiles_) tiles_->reset();
        realFramesSinceProbe_ = 0;
        fullProbes_ = 0;
        temporal_.reset();
    }

    // One displayed frame: real (passes -> upsample -> infer -> tiles) or, with temporal
    // reprojection, interpolated from the last real frame (no geometry, no inference; the tiles
    // and scales keep the last real frame's state).
    void renderFrame(const FrameDesc& frame, const DrawCallback& draw) override {
        if (setFrameSize(frame.width, frame.height)) {
            out_ = {};
            if (tiles_) tiles_->resize(frame.width, frame.height);
        }
        const glm::mat4 viewProjection = frame.projection * frame.view;
        // Warp and refresh frames reuse the last real frame's composite: with an opaque scene it is
        // kept premultiplied, so that they composite over their own frame's background (docs/DESIGN.md,
        // "Opaque geometry").
        const bool premultipliedHistory = temporal_.interpolates() && !temporal_.corrects() && opaque_.active();
        if (!temporal_.beginFrame(frame.width, frame.height)) {
            if (config_.layeredEveryFrame) {
                if (!out_.texture) chooseOutput(false);
                // The first frame makes the reference depth its moments are taken behind, then renders.
                if (temporal_.takeLayeredPriming()) renderInterpolated(frame, draw, viewProjection);
            }
            renderInterpolated(frame, draw, viewProjection);
            return;
        }
        const bool transmittanceInAlpha = premultipliedHistory && !frame.premultipliedOutput;
        opaque_.setTransmittanceInAlpha(transmittanceInAlpha);
        renderReal(frame, draw);
        opaque_.setTransmittanceInAlpha(false);
        if (fusedCaptured_) {
            temporal_.endRealFrameFused();
        } else if (temporal_.interpolates()) {
            gl::ScopedPass timing(frame.timing, "temporal_capture");
            // Corrected frames need this frame's pass-3 sums at full resolution (none when it ran reduced).
            const bool sums = passes_.pass3Size() == Size2{frame.width, frame.height};
            temporal_.endRealFrame(out_.texture, temporalTargets(sums), viewProjection, frame.width, frame.height, opaque_,
                                   premultipliedHistory);
        }
        if (transmittanceInAlpha) {
            // The history has the transmittance; the output's alpha is 1 (OitMethod::outputTexture).
            glBindFramebuffer(GL_FRAMEBUFFER, out_.framebuffer);
            glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_TRUE);
            const float opaqueAlpha[4] = {0.0f, 0.0f, 0.0f, 1.0f};
            glClearBufferfv(GL_COLOR, 0, opaqueAlpha);
            glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
        }
    }

private:
    // An interpolated frame (kbuffer-moments: every frame): the passes the temporal mode asks for,
    // fresh at this camera, then the temporal frames' composite (no inference, no tiles).
    void renderInterpolated(const FrameDesc& frame, const DrawCallback& draw, const glm::mat4& viewProjection) {
        switch (temporal_.interpolatedPasses()) {
            case TemporalFrames::Passes::NearestAndSums:
                passes_.runNearestAndSums(frame, draw, temporal_.behindReference());
                break;
            case TemporalFrames::Passes::PackedNearestAndSums:
                passes_.runPackedNearestAndSums(frame, draw, temporal_.behindReference());
                break;
            case TemporalFrames::Passes::Nearest: passes_.runNearest(frame, draw); break;
            case TemporalFrames::Passes::None: break;
        }
        TemporalPassTargets targets = temporalTargets(true);
        if (temporal_.interpolatedPasses() == TemporalFrames::Passes::PackedNearestAndSums) {
            targets.packedNearest = passes_.packedNearest();
            targets.thirdLayer = passes_.thirdLayer();
            if (passes_.compositeClearsTargets()) targets.clearByComposite = passes_.packedTargets();
        }
        targets.behindMoment1 = passes_.behindMoment1();
        targets.behindMoment2 = passes_.behindMoment2();
        temporal_.interpolate(viewProjection, targets, opaque_, out_.texture, frame.timing);
        if (targets.clearByComposite[0]) passes_.targetsClearedByComposite();
    }

    // This frame's pass targets for the temporal frames; pass 3's only with `sums`.
    TemporalPassTargets temporalTargets(bool sums) const {
        return {passes_.nearest().id(), passes_.nearestDepth().id(), sums ? passes_.alphaColor().id() : 0u,
                sums ? passes_.transmittance().id() : 0u};
    }

    void renderReal(const FrameDesc& frame, const DrawCallback& draw) {
        chooseScales();
        const Size2 full{frame.width, frame.height};
        // The tail-moment methods' corrected frames: pass 3 also sums the moments the interpolated
        // frames will, behind a reference depth made from this frame's pass 1, and the fused capture
        // takes the correction against the closed form they make (docs/DESIGN.md, "Corrected frames:
        // depth order behind the nearest layer").
        std::function<GLuint()> behindReference;
        if (config_.tailMoments && fusedCaptureApplies()) {
            behindReference = [&] {
                gl::ScopedPass timing(frame.timing, "reference_depth");
                return temporal_.prepareReference(passes_.nearestDepth().id(), frame.width, frame.height);
            };
        }
        passes_.setPass3ShadingRates(pass3Rates_);
        passes_.run(frame, draw, NeuralPasses::kDefaultPeelEpsilon,
                    {tiles::scaledSize(full.width, scale2_), tiles::scaledSize(full.height, scale2_)},
                    {tiles::scaledSize(full.width, scale3_), tiles::scaledSize(full.height, scale3_)}, behindReference);
        // With the guard, the tiles only look at probe frames: on a reduced frame the image behind
        // the nearest layer is an interpolation, smoother than the scene, so measuring it would
        // lower the levels and the scales further with every frame.
        const bool tilesUpdate = tiles_ && (!guarded() || probe_);
        chooseOutput(!tilesUpdate && !temporal_.interpolates());
        infer(frame);
        if (tilesUpdate) {
            gl::ScopedPass timing(frame.timing, "tiles");
            tiles_->update(out_.texture, passes_.nearest().id(), options_.neural.tileSignal,
                           guarded() ? passes_.second().id() : 0);
            // The rasteriser may cache the rate image: after the image stores, only this makes the
            // next frames' pass 3 read the new rates (NV_shading_rate_image).
            if (shadingRates_) glShadingRateImageBarrierNV(GL_TRUE);
        }
    }

    // Where this real frame's output goes (NeuralPasses::outputSlot): in place over a pass target
    // when one is free, else a texture of its own, allocated on first need and kept (so the memory
    // reported is the peak).
    // With corrected frames the output has a texture of its own: their capture reads pass 3's sums
    // after the inference, the probe frames' tiles read pass 2's colour after it, and the corrected
    // frames render their passes again while the output must stay.
    void chooseOutput(bool nearestFree) {
        const bool corrected = temporal_.interpolates() && temporal_.corrects();
        out_ = corrected ? NeuralPasses::OutputSlot{} : passes_.outputSlot(nearestFree);
        if (!out_.texture) {
            allocateOutput(passes_.outputFormat());
            out_ = {output_.id(), outputFb_.id(), "output"};
        }
    }

    // The composite draws shade only the pixels pass 1 covered (empty_pixels.hpp), except with
    // joint upsampling, whose shaders sample pass 1's depth.
    bool skipEmpty() const { return options_.neural.skipEmptyPixels && !joint(); }

    // `moreTargets` (0 for none; the empty-pixel skip only): pass targets the composite writes
    // back into after reading them (clearsSharedSums).
    void bindOutput(const std::array<GLuint, 3>& moreTargets = {}) {
        const bool more = moreTargets[0] != 0;
        if (skipEmpty()) {
            emptyPixels_.bindCovered(out_.texture, passes_.nearestDepth().id(), width_, height_, 0,
                                     more ? std::span<const GLuint>(moreTargets) : std::span<const GLuint>());
            // Not in place over a pass target, which the composite reads.
            if (out_.texture == output_.id()) emptyPixels_.clearToBackground(opaque_, compactOutput());
        } else {
            if (more) throw Error("internal: the composite writes pass targets back only with the empty-pixel skip");
            glBindFramebuffer(GL_FRAMEBUFFER, out_.framebuffer);
            glViewport(0, 0, width_, height_);
        }
        // In place, or writing pass targets back: each fragment reads its own texel of a target it
        // writes, once; the barrier makes the earlier passes' writes visible to those reads (GL 4.5
        // texture barrier rules).
        if (out_.texture != output_.id() || more) glTextureBarrier();
    }

    // After the composite: the background into the pixels it skipped.
    void finishOutput() {
        if (skipEmpty()) emptyPixels_.fillEmpty(opaque_, compactOutput(), fullscreenVao_);
    }
    bool compactOutput() const { return options_.neural.targets == NeuralOptions::Targets::Compact; }

    // Real frames from one probe to the next (tile_constants.h: doubled after each probe in a row
    // that kept full resolution, up to 32).
    int probeInterval() const {
        return STARNT_SCALE_PROBE_INTERVAL << std::min(fullProbes_, STARNT_SCALE_PROBE_BACKOFF);
    }

    // The scale guard applies to the adaptive scales only (not to fixed --scales).
    bool guarded() const { return spatial_ && options_.neural.scaleGuard && options_.neural.fixedScale2 == 0.0f; }

    // Per-tile pass-3 shading rates (docs/DESIGN.md, "Per-tile shading rates on GPUs"): they need
    // the guard's per-tile sums and the driver's shading-rate image; `on` without either is an
    // error naming what is missing, `auto` falls back to the whole-pass scales.
    bool shadingRatesApply() const {
        using S = NeuralOptions::ShadingRateImage;
        const S mode = options_.neural.shadingRateImage;
        if (mode == S::Off) return false;
        std::string missing;
        if (!guarded()) {
            missing = "the adaptive tiles with the scale guard (--spatial on, --scale-guard on, --scales auto)";
        } else if (temporal_.interpolates()) {
            // The corrected frames' capture and the warp read pass 3's full sums, which the
            // coarse copies of layers 1 and 2 would spoil (docs/DESIGN.md, "Per-tile shading rates on GPUs").
            missing = "no temporal frames (--temporal off)";
        } else {
            const gl::ShadingRateImageSupport support =
                gl::shadingRateImageSupport(STARNT_TILE_SIZE, STARNT_SHADING_RATE_CLASSES);
            if (!support.usable) missing = support.missing + " in this OpenGL context";
        }
        if (missing.empty()) return true;
        if (mode == S::On) throw Error("--shading-rate-image on needs " + missing);
        return false;
    }

    // How many layers the interpolated frames find exactly (NeuralOptions::correctedLayers; docs/DESIGN.md,
    // "Corrected frames: the second layer by framebuffer fetch" and "... three layers and no
    // correction"). With two, their real frames sum the moments behind pass 2's layer and the kept
    // correction is taken against the closed form with both layers exact; with three, the real
    // frames keep no correction (keepsCorrection). `2` or `3` without what it needs is an error
    // naming it; `auto` takes the most the context allows, else one layer.
    static int correctedLayers(const NeuralMethodConfig& config, const MethodOptions& o) {
        using L = NeuralOptions::CorrectedLayers;
        if (config.layeredEveryFrame) return layeredLayers(config);
        if (o.neural.correctedLayers == L::One) return 1;
        const bool corrected = (o.neural.temporalInterval > 1 || o.neural.temporalAuto) &&
                               o.neural.temporalMode == NeuralOptions::TemporalMode::Correct;
        std::string missing;
        if (!config.tailMoments) {
            missing = "a tail-moment method (hybrid-moments, starnt-d, recommended)";
        } else if (!corrected) {
            missing = "corrected frames (--temporal 2..8 or auto with --temporal-mode correct)";
        } else if (!o.neural.correctedOnePass) {
            missing = "corrected frames in one geometry pass (--corrected-passes 1)";
        } else if (!epoxy_has_gl_extension("GL_EXT_shader_framebuffer_fetch")) {
            missing = "GL_EXT_shader_framebuffer_fetch in this OpenGL context";
        }
        if (!missing.empty()) {
            if (o.neural.correctedLayers == L::Two) throw Error("--corrected-layers 2 needs " + missing);
            if (o.neural.correctedLayers == L::Three) throw Error("--corrected-layers 3 needs " + missing);
            return 1;
        }
        if (o.neural.correctedLayers == L::Two) return 2;
        // The third layer is a fifth target of the interpolated frames' pass 3.
        GLint drawBuffers = 0;
        glGetIntegerv(GL_MAX_DRAW_BUFFERS, &drawBuffers);
        if (drawBuffers >= 5) return 3;
        if (o.neural.correctedLayers == L::Three) {
            throw Error("--corrected-layers 3 needs 5 draw buffers (GL_MAX_DRAW_BUFFERS is " + std::to_string(drawBuffers) + ")");
        }
        return 2;
    }

    // kbuffer-moments keeps three layers by framebuffer fetch in five draw buffers, or is refused
    // with what the context lacks. (A path through GL_ARB_fragment_shader_interlock for desktop
    // GPUs without fetch is not built: docs/DESIGN.md, "kbuffer-moments".)
    static int layeredLayers(const NeuralMethodConfig& config) {
        if (!epoxy_has_gl_extension("GL_EXT_shader_framebuffer_fetch")) {
            throw Error(config.name + " needs GL_EXT_shader_framebuffer_fetch (GL_ARB_fragment_shader_interlock is not used) "
                        "in this OpenGL context: on a desktop GPU without it, take recommended or starnt-d");
        }
        GLint drawBuffers = 0;
        glGetIntegerv(GL_MAX_DRAW_BUFFERS, &drawBuffers);
        if (drawBuffers < 5) {
            throw Error(config.name + " needs 5 draw buffers (GL_MAX_DRAW_BUFFERS is " + std::to_string(drawBuffers) + ")");
        }
        return 3;
    }

    static const MethodOptions& validated(const NeuralMethodConfig& config, const MethodOptions& o) {
        auto scaleOk = [](float s) { return s == 0.0f || (s >= float(STARNT_SCALE_MIN) && s <= 1.0f); };
        if (!scaleOk(o.neural.fixedScale2) || !scaleOk(o.neural.fixedScale3) || ((o.neural.fixedScale2 == 0.0f) != (o.neural.fixedScale3 == 0.0f))) {
            throw Error("fixed pass scales must both be 0 (from the tiles) or both within 0.25..1");
        }
        if (o.neural.temporalInterval < 1 || o.neural.temporalInterval > kMaxTemporalInterval) {
            throw Error("temporal interval must be within 1.." + std::to_string(kMaxTemporalInterval));
        }
        if (config.layeredEveryFrame) {
            using L = NeuralOptions::CorrectedLayers;
            if (o.neural.temporalInterval != 1 || o.neural.temporalAuto || o.neural.temporalMode != NeuralOptions::TemporalMode::Correct ||
                (o.neural.correctedLayers != L::Auto && o.neural.correctedLayers != L::Three) || !o.neural.correctedOnePass) {
                throw Error(config.name + " renders every frame in one pass of its own: temporal options (--temporal, "
                            "--temporal-mode, --corrected-layers, --corrected-passes) do not apply to it");
            }
        }
        if (config.tailMoments) {
            // Its moments are relative to pass 2's depth at the same pixel: no reduced pass, no upsampling.
            const bool reduced = o.neural.fixedScale2 > 0.0f && !(o.neural.fixedScale2 == 1.0f && o.neural.fixedScale3 == 1.0f);
            if (o.neural.spatial.value_or(config.spatialByDefault) || reduced ||
                o.neural.inference == NeuralOptions::Inference::Corners || o.neural.upsample == NeuralOptions::Upsample::Joint) {
                throw Error(config.name + " runs every pass at full resolution: spatial on, fixed scales below 1, corner inference and joint upsampling "
                            "(--spatial on, --scales below 100, --inference corners, --upsample joint) are not available with it");
            }
        }
        return o;
    }

    // The inference programs: stage x (passes 2/3 at full resolution or not), built on first use.
    const gl::Program& inference(const std::string& stage, bool fullResolutionInputs) {
        auto& slot = inferencePrograms_[{stage, fullResolutionInputs}];
        if (!slot) slot = buildInference(stage, fullResolutionInputs);
        return slot;
    }

    gl::Program buildInference(std::string stage, bool fullResolutionInputs) const {
        // infer_full with the fused capture (corrected frames), against the ordered closed form
        // (the tail-moment methods).
        const bool ordered = stage == "infer_full_capture_ordered";
        const bool capture = ordered || stage == "infer_full_capture";
        const bool clearsSums = stage == "infer_full_clears";
        if (capture || clearsSums) stage = "infer_full";
        const std::string defines = std::string(fullResolutionInputs ? "#define STARNT_INPUTS_FULL_RESOLUTION\n" : "") +
                                    (capture ? "#define STARNT_CAPTURE_CORRECTION\n" : "") +
                                    (ordered ? "#define STARNT_CAPTURE_ORDERED\n" : "") +
                                    (ordered && layers_ == 2 ? "#define STARNT_CAPTURE_TWO_LAYERS\n" : "") +
                                    (clearsSums ? "#define STARNT_CLEARS_SHARED_SUMS\n" : "") +
                                    (joint() ? "#define STARNT_UPSAMPLE_JOINT\n" : "") + passes_.countLayoutDefine() + passes_.targetsDefine() +
                                    passes_.layerDefine() +
                                    neuralEpsilonDefines() + nn::generateInferenceGlsl(network_);
        return buildFullscreenProgram(config_.name + "_" + stage + (capture ? "_capture" : "") + (ordered ? "_ordered" : "") +
                                          (clearsSums ? "_clears" : "") +
                                          (fullResolutionInputs ? "" : "_upsampled"),
                                      {config_.compositeShader, "methods/neural/" + stage + ".frag.glsl"}, defines);
    }

    // Scales of this frame (docs/DESIGN.md, "Adaptive tiles and tile-guided resolution"): fixed for ablations, else from the newest tile histogram
    // (the last real frame's, or one older if the GPU has not finished it), else full resolution.
    void chooseScales() {
        if (options_.neural.fixedScale2 > 0.0f) {
            scale2_ = options_.neural.fixedScale2;
            scale3_ = options_.neural.fixedScale3;
        } else if (spatial_ && tiles_) {
            tiles_->pollHistogram();
            const double wBar = tiles_->hasHistogram() ? tiles_->wBar() : 3.0;  // no history yet: full resolution
            scale2_ = tiles::ruleScale(options_.neural.scaleRule, wBar, STARNT_SCALE_DELTA_PASS2);
            scale3_ = tiles::ruleScale(options_.neural.scaleRule, wBar, STARNT_SCALE_DELTA_PASS3);
            if (guarded()) {
                // A reading with nothing to measure (an empty draw, nothing behind the nearest
                // layer) is no verdict: it must not choose the scales of the frames after it, so
                // every real frame probes until a reading measures something.
                const bool verdict = tiles_->hasGuard() && tiles::guardMeasured(tiles_->guard());
                probe_ = tiles_->updates() < STARNT_SCALE_SETTLE_FRAMES || realFramesSinceProbe_ + 1 >= probeInterval() ||
                         (tiles_->hasGuard() && !verdict);
                realFramesSinceProbe_ = probe_ ? 0 : realFramesSinceProbe_ + 1;
                pass3Rates_ = 0;
                if (probe_ || !verdict) {
                    scale2_ = scale3_ = 1.0f;
                } else if (shadingRates_) {
                    // Per-tile rates for pass 3 instead of whole-pass scales; pass 2 at full resolution.
                    scale2_ = scale3_ = 1.0f;
                    const auto& n = tiles_->shadingRateTiles();
                    const bool reduced = n[STARNT_SHADING_RATE_HALF] + n[STARNT_SHADING_RATE_QUARTER] > 0;
                    // Only where the newest readback reduced a tile (the image may be a probe
                    // newer: at worst one frame binds an all-1x1 image or skips a reduced one).
                    pass3Rates_ = reduced ? tiles_->shadingRateImage() : 0;
                    if (tiles_->guardReadings() != guardReadingsSeen_) {
                        guardReadingsSeen_ = tiles_->guardReadings();
                        fullProbes_ = reduced ? 0 : fullProbes_ + 1;
                    }
                } else {
                    // The guard decides (measured: w_bar of the tiles stays near 3 on the built-in
                    // scenes, where halving pass 3 loses 0.02-2 % of what it adds).
                    const tiles::PassScales s = tiles::guardScales(tiles_->guard(), STARNT_SCALE_GUARD_BUDGET);
                    scale2_ = s.pass2;
                    scale3_ = s.pass3;
                    if (tiles_->guardReadings() != guardReadingsSeen_) {  // a new probe's verdict
                        guardReadingsSeen_ = tiles_->guardReadings();
                        fullProbes_ = s.pass2 == 1.0f && s.pass3 == 1.0f ? fullProbes_ + 1 : 0;
                    }
                }
            }
        } else {
            scale2_ = scale3_ = 1.0f;
        }
    }

    bool joint() const { return options_.neural.upsample == NeuralOptions::Upsample::Joint; }

    // The real frame's composite captures the corrected frames' correction itself (beside corner
    // inference and reduced passes, which the caller checks per frame).
    bool fusedCaptureApplies() const {
        return temporal_.interpolates() && temporal_.corrects() && keepsCorrection() && skipEmpty() &&
               options_.neural.fusedCorrectionCapture;
    }
    // Whether this real frame's inference writes 0 back into the pass-3 targets the interpolated
    // frames sum into as well (NeuralPasses::sharedSumTargets): with three layers, where the
    // composite of the interpolated frames clears them (NeuralPasses::compositeClearsTargets), when
    // it reads them at its own pixel only (every pass at full resolution), shades every pixel pass
    // 1 covered (the empty-pixel skip), writes its output apart (corrected frames do) and nothing
    // reads pass 3's sums after it (no tiles; three layers keep no correction to capture).
    bool clearsSharedSums(bool fullResolution) const {
        return passes_.compositeClearsTargets() && fullResolution && skipEmpty() && !tiles_ && !keepsCorrection() &&
               out_.texture == output_.id();
    }
    // Whether the real frames keep the network's correction for the interpolated frames: not with
    // three layers, whose closed form alone measured nearer the A-buffer than the real frames
    // (docs/DESIGN.md, "Corrected frames: three layers and no correction"); those real frames then
    // render as at K = 1 and keep only the reference depth.
    bool keepsCorrection() const { return layers_ != 3; }

    void setCommonUniforms(const gl::Program& program, const FrameDesc& frame) const {
        glUseProgram(program.id());
        passes_.bindInputs(program);
        if (joint()) {
            // View z from window depth needs rows 2 and 3 of the inverse projection, z and w columns
            // only (a perspective or orthographic projection, off-centre or not, has no x/y terms there).
            const glm::mat4 inverse = glm::inverse(frame.projection);
            glUniform4f(program.uniform("u_depthUnproject"), inverse[2][2], inverse[3][2], inverse[2][3], inverse[3][3]);
        }
        bindBackground(program);
        glUniform2i(program.uniform("u_tiles"), tiles_ ? tiles_->tilesX() : 0, tiles_ ? tiles_->tilesY() : 0);
    }

    void infer(const FrameDesc& frame) {
        gl::ScopedPass timing(frame.timing, "inference");
        resetPassState();
        // Corner inference needs the masks of a previous real frame; the first frame infers everywhere.
        cornersUsed_ = corners_ && tiles_->updates() > 0;
        const Size2 full{width_, height_};
        // (Per-tile shading rates leave pass 3's tails, read as after reduced passes.)
        const bool fullResolution = passes_.pass2Size() == full && passes_.pass3Size() == full && !passes_.pass3HoldsTails();
        // Corrected frames keep this frame's correction: written by the composite itself where it can.
        fusedCaptured_ = !cornersUsed_ && fusedCaptureApplies() && fullResolution;
        if (fusedCaptured_) {
            const auto targets = temporal_.beginFusedCapture(gl::textureInternalFormat(out_.texture), passes_.nearestDepth().id(),
                                                            width_, height_, frame.projection * frame.view);
            emptyPixels_.bindCovered(out_.texture, targets.coverDepth, width_, height_, targets.correction);
            emptyPixels_.clearToBackground(opaque_, compactOutput());  // its own output, not read here
            const bool ordered = passes_.behindMomentsSummed();
            const gl::Program& program = inference(ordered ? "infer_full_capture_ordered" : "infer_full_capture", true);
            setCommonUniforms(program, frame);
            if (ordered) {
                // infer_full.frag.glsl's u_behindMoment1 and u_captureReference (sum a u^2 is read beside the count)
                glBindImageTexture(0, passes_.realBehindMoment1(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA32F);
                glBindImageTexture(1, passes_.realBehindReference(), 0, GL_FALSE, 0, GL_READ_ONLY, GL_R32F);
            }
            glUniform4fv(program.uniform("u_sourceScale"), 1, &targets.sourceScale[0]);
            drawFullscreen();
            finishOutput();
            return;
        }
        if (!cornersUsed_) {
            // Corrected frames with three layers on a software rasteriser: the inference also writes
            // 0 back into the pass-3 targets the interpolated frame's pass 3 sums into, at the
            // pixels it shades, so that pass need not clear them (NeuralPasses::sharedSumTargets).
            const bool clearsSums = clearsSharedSums(fullResolution);
            bindOutput(clearsSums ? passes_.sharedSumTargets() : std::array<GLuint, 3>{});
            setCommonUniforms(inference(clearsSums ? "infer_full_clears" : "infer_full", fullResolution), frame);
            drawFullscreen();
            finishOutput();
            if (clearsSums) passes_.sharedSumsClearedByInference();
            return;
        }
        if (cornerNetwork_.width() != width_ || cornerNetwork_.height() != height_) {
            cornerNetwork_ = gl::Texture2D(GL_RGBA32F, width_, height_);
            cornerFb_ = gl::makeFramebuffer({&cornerNetwork_});
        }
        tiles_->bindMasks();
        glBindFramebuffer(GL_FRAMEBUFFER, cornerFb_.id());
        glViewport(0, 0, width_, height_);
        setCommonUniforms(inference("infer_corners", fullResolution), frame);
        drawFullscreen();

        bindOutput();
        setCommonUniforms(inference("infer_fill", fullResolution), frame);
        gl::bindTexture(kUnitCornerNetwork, cornerNetwork_.id());
        drawFullscreen();
        finishOutput();
    }

    NeuralMethodConfig config_;
    MethodOptions options_;
    bool spatial_, corners_;
    nn::Network network_;
    std::map<std::pair<std::string, bool>, gl::Program> inferencePrograms_;
    NeuralPasses passes_;
    int layers_;  // correctedLayers
    TemporalFrames temporal_;
    std::unique_ptr<tiles::GpuTiles> tiles_;
    EmptyPixelSkip emptyPixels_;
    gl::Texture2D cornerNetwork_, overlay_;
    gl::FramebufferHandle cornerFb_;
    float scale2_ = 1.0f, scale3_ = 1.0f;
    bool shadingRates_ = false;  // per-tile pass-3 shading rates (shadingRatesApply)
    GLuint pass3Rates_ = 0;      // this real frame's rate image (0: one invocation per pixel)
    bool cornersUsed_ = false;
    bool fusedCaptured_ = false;  // this real frame's composite captured the corrected frames' correction
    NeuralPasses::OutputSlot out_;  // this frame's output
    bool probe_ = false;            // this real frame is a guard probe (passes 2/3 at full resolution)
    int realFramesSinceProbe_ = 0;
    int fullProbes_ = 0;         // probes in a row whose guard kept both passes at full resolution
    int guardReadingsSeen_ = 0;  // tiles_->guardReadings() when fullProbes_ last changed
};

}  // namespace

nn::Network loadMethodNetwork(const NeuralMethodConfig& config, const MethodOptions& options) {
    // A closed form's shaders declare a network of its inputs' shape that they never call.
    if (!config.evaluatesNetwork) return nn::makeUntrained(config.kind, 1);
    if (!options.neural.weightsPath.empty()) return nn::loadWeights(options.neural.weightsPath, config.kind);
    return nn::parseWeights(gl::embeddedSource(config.defaultWeights), "shipped " + config.name + " weights", config.kind);
}

std::unique_ptr<OitMethod> createNeuralMethod(const NeuralMethodConfig& config, const SurfaceShader& surface,
                                              const MethodOptions& options) {
    return std::make_unique<NeuralMethod>(config, surface, options);
}

}  // namespace starnt
