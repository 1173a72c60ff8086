// The three geometry passes of the low-end neural OIT pipeline (no interlock, no per-pixel
// lists), shared by `starnt` and `dfaoit` (docs/DESIGN.md, "Pipeline and formats"):
//   pass 1: nearest fragment (colour+alpha, depth)        full resolution
//   pass 2: second-nearest by peeling against pass 1      scale s2 (against a max-downsampled depth)
//   pass 3: sums over all fragments                       scale s3
//   (then, if pass 2 or 3 was reduced, their tails: tail_resolve.frag.glsl)
// Passes 2 and 3 render into the lower-left ceil(W s) x ceil(H s) rectangle of full-size targets,
// so a change of scale from frame to frame never reallocates; the inference reads them back at
// full resolution through upsample.glsl.
// Target formats (docs/DESIGN.md, "Pipeline and formats"; NeuralOptions::Targets). Compact, the default, 36 bytes a pixel at full
// resolution for STAR-NT:
//   nearest / second colour RGBA16F (8 + 8), their depths DEPTH_COMPONENT32F (4 + 4: peeling
//   compares depths bit for bit), sum aC + sum a RGBA16F (8), N alone R16F (2; integers exact to
//   2048; DFAOIT: sum C + N RGBA16F, 8), transmittance R16 (2; unsigned normalised: see
//   compactTransmittanceFormat); the three pass-3 targets with
//   GL_LINEAR filtering, as the inference reads their reduced tails through the bilinear filter.
//   The output is written in place over one of them (outputSlot), so it costs nothing.
// Narrow layers (DFAOIT, compact, every pass at full resolution, no tiles, no temporal frames;
// `narrowLayers`): 36 bytes a pixel, so that DFAOIT fits the paper's 75 MB at 1080p. The layer
// colours go to RGB10_A2 (4 + 4; 10-bit unsigned normalised, clamped to [0, 1]), both alphas to one
// RG16F target (4; pass 1 writes .r, pass 2 .g under colour masks: 8-bit alphas biased DFAOIT's
// tail alpha sum a - a1 - a2 by up to 19 % MSE, docs/results/memory_compact_targets.md), and pass
// 2's depth buffer, which only ranks the fragments behind the nearest one, to DEPTH_COMPONENT16 (2;
// the peel itself still compares against pass 1's 32-bit depth). Measured against the 32-bit layout
// on the 13 suite scenes: docs/results/memory_compact_targets.md. Tiles, reduced passes and
// temporal frames read the layers' alpha from the colour targets, so they keep the RGBA16F layers.
// Float32: every colour target 32-bit float (the earlier layout).
// Passes 2 and 3 keep full-size targets even when they run reduced: the scale guard's probe frames
// run them at full resolution every 8th to 32nd real frame, so the full size is the peak anyway, and
// reallocating at every probe would only churn.
#pragma once
#include <array>
#include <functional>
#include <string>

#include "methods/common/method_base.hpp"
#include "starnt/method_options.hpp"
#include "methods/neural/reduced_grid.hpp"
#include "starnt/bindings.h"

namespace starnt {

// Texture units the composite shaders read the pass outputs from (starnt/bindings.h, shared with
// the GLSL).
enum NeuralInputUnit : GLuint {
    kUnitNearest = STARNT_UNIT_NEAREST,
    kUnitSecond = STARNT_UNIT_SECOND,
    kUnitAlphaColor = STARNT_UNIT_ALPHA_COLOR,
    kUnitColorCount = STARNT_UNIT_COLOR_COUNT,
    kUnitTransmittance = STARNT_UNIT_TRANSMITTANCE,
    kUnitNearestDepth = STARNT_UNIT_NEAREST_DEPTH,
};

// "#define STARNT_EPS_TRANSMITTANCE ..." and "STARNT_EPS_TAIL_ALPHA", from nn::kTransmittanceEpsilon
// and nn::kTailAlphaEpsilon, for the shaders that guard the same quotients as the CPU features.
std::string neuralEpsilonDefines();

// The tail resolve (tail_resolve.frag.glsl, CPU reference upsamplePassSums): turns the pass-3
// targets' sums into tails in place over the pass3 rectangle. Run when pass 2 or 3 was reduced.
// `pass3Framebuffer` has alphaColor, colorCount and transmittance attached, in that order.
gl::Program buildTailResolveProgram(const std::string& defines = {});
struct TailResolveInputs {
    const gl::Program* program;
    GLuint nearest, second, alphaColor, colorCount, transmittance;  // textures, as NeuralPasses has them
    Size2 full, pass2, pass3;
};
// OpenGL ES has no texture barrier, so there the resolve reads copies of the pass-3 rectangle
// (glCopyImageSubData) kept in `esCopies`, (re)allocated at the pass-3 size on first use; on
// desktop GL they stay empty and a glTextureBarrier makes the in-place loop defined.
struct TailResolveCopies {
    gl::Texture2D alphaColor, colorCount, transmittance;
    size_t bytes() const { return alphaColor.bytes() + colorCount.bytes() + transmittance.bytes(); }
};
void resolveTails(const TailResolveInputs& inputs, GLuint pass3Framebuffer, const gl::VertexArrayHandle& emptyVao,
                  TailResolveCopies& esCopies);

class NeuralPasses {
public:
    // Default peel epsilon: 1e-6 in window depth, about 16 float steps near the far plane. The
    // same fragment reproduces its pass-1 depth bit for bit (invariant gl_Position), so any
    // epsilon >= 0 removes it; the small margin also merges surfaces closer than that, which
    // would otherwise flicker between first and second with rounding.
    static constexpr float kDefaultPeelEpsilon = 1e-6f;

    // Builds the three geometry-pass programs around the engine's surface shader. Without
    // `colorSums` pass 3 keeps the fragment count alone in an R32F target instead of sum C and N in
    // an RGBA32F one (STARNT_COUNT_ONLY): the STAR-NT inputs never read sum C, only DFAOIT's do.
    // `narrowLayers` (compact targets only): the narrow layers above.
    // `tailMoments` (hybrid-moments; every pass at full resolution): pass 3 also sums, over the
    // fragments behind pass 2's layer, a C u, a u, a C u^2 and a u^2 with u a logarithmic depth behind
    // z2 (window depth, z2 read from pass 2's depth; tail_moments_constants.h), into two RGBA32F targets (32 bytes a pixel: 16-bit sums cannot
    // be centred on the tail's mean depth; tail_moments_constants.h), and keeps sum a C, sum a and
    // the transmittance in 32-bit float (+10 bytes), since the centring and the weights read them.
    // `opaque`: the method's view of the engine's opaque scene (OpaqueScene), which clips every
    // pass; it outlives this object.
    NeuralPasses(const SurfaceShader& surface, OpaqueScene& opaque, bool colorSums = true,
                 NeuralOptions::Targets targets = NeuralOptions::Targets::Compact, bool narrowLayers = false,
                 bool tailMoments = false);
    // The define the programs that read pass 3 (neural_inputs.glsl, the tail resolve) need.
    const char* countLayoutDefine() const { return colorSums_ ? "" : "#define STARNT_COUNT_ONLY\n"; }
    // "#define STARNT_SPLIT_ALPHA" for the programs that read the narrow layers' alphas apart.
    static const char* layerDefine(bool narrowLayers) { return narrowLayers ? "#define STARNT_SPLIT_ALPHA\n" : ""; }
    const char* layerDefine() const { return layerDefine(narrowLayers_); }
    bool narrowLayers() const { return narrowLayers_; }
    // The define of the programs that write into the targets or the output (half_targets.glsl).
    static const char* targetsDefine(NeuralOptions::Targets targets) {
        return targets == NeuralOptions::Targets::Compact ? "#define STARNT_HALF_TARGETS\n" : "";
    }
    const char* targetsDefine() const { return targetsDefine(targets_); }

    void resize(int width, int height);
    // Renders the three passes; pass2Size / pass3Size are the reduced sizes (the full size for s = 1).
    // `behindReference`, the tail-moment methods' real frames with corrected frames
    // (CorrectedFrames::prepareReference): called after pass 2; a non-zero reference makes pass 3
    // (at full resolution) also sum the moments behind that reference over every fragment, as an
    // interpolated frame's pass 3 sums them (ordered_behind.glsl; realBehindMoment1(),
    // behindMomentsSummed()), for the capture of an ordered correction. Needs 6 draw buffers; with
    // fewer it sums none.
    void run(const FrameDesc& frame, const DrawCallback& draw, float peelEpsilon, Size2 pass2Size, Size2 pass3Size,
             const std::function<GLuint()>& behindReference = {});
    // Per-tile shading rates for the next real frames' pass 3 at full resolution: an R8UI image of
    // STARNT_SHADING_RATE_* classes, one texel per 16x16 tile (GpuTiles::shadingRateImage), through
    // GL_NV_shading_rate_image; 0 = one invocation per pixel.
    // Such a pass 3 sums only the fragments behind pass 2's layer (pass3HoldsTails()), which
    // setPass3TailsOnly gives without the rates (tests).
    void setPass3ShadingRates(GLuint rateImage) { pass3Rates_ = rateImage; }
    void setPass3TailsOnly(bool tailsOnly) { pass3TailsOnly_ = tailsOnly; }
    // The last run's pass-3 targets hold each pixel's tail (sums minus layers 1 and 2) rather than
    // its sums, as after the tail resolve of reduced passes: the inference reads them so.
    bool pass3HoldsTails() const { return pass3HoldsTails_; }
    void prepareRealBehindMoments();
    bool behindMomentsSummed() const { return behindSummed_; }
    // (sum a C u, sum a u) in realBehindMoment1(), sum a u^2 in colorCount()'s .g, behind
    // realBehindReference() (the reference depth pass 3 read).
    GLuint realBehindMoment1() const { return packedNearest_.id(); }
    GLuint realBehindReference() const { return behindReference_; }
    // Pass 1 alone (nearest() and nearestDepth()), for refresh frames.
    void runNearest(const FrameDesc& frame, const DrawCallback& draw);
    // Pass 1 and pass 3, both at full resolution (alphaColor() and transmittance() hold the sums
    // over every fragment), for corrected interpolated frames (no pass 2, no tail resolve).
    // The tail-moment methods sum their moments behind `reference` too, the transmittance then as
    // an optical depth in behindMoment2()'s .g rather than in transmittance() (ordered_behind.glsl:
    // behindMoment1(), behindMoment2(); `reference` the corrected frames' reference depth,
    // CorrectedFrames::reference()).
    void runNearestAndSums(const FrameDesc& frame, const DrawCallback& draw, GLuint reference = 0);
    // Compiles runNearestAndSums' pass 3 now rather than in the first frame that needs it.
    void prepareNearestAndSums();
    // Pass 3 alone at full resolution, finding the nearest fragment by blending as well: the sums
    // as runNearestAndSums leaves them and packedNearest() (packed_nearest.glsl), for corrected
    // interpolated frames in one geometry pass (a target of its own, allocated on first need);
    // nearestDepth() then holds a depth below 1 exactly where a fragment was kept (not the nearest).
    // The moments behind `reference` as runNearestAndSums.
    void runPackedNearestAndSums(const FrameDesc& frame, const DrawCallback& draw, GLuint reference = 0);
    void preparePackedNearestAndSums();
    GLuint packedNearest() const { return twoLayers_ ? packedLayers_.id() : packedNearest_.id(); }
    // From now on runPackedNearestAndSums finds the nearest two fragments (the tail-moment methods,
    // GL_EXT_shader_framebuffer_fetch; packed_nearest.h): packedNearest() is then RGBA32UI. Call
    // before preparePackedNearestAndSums.
    void findTwoLayers() { twoLayers_ = tailMoments_; }
    // The same and the third layer in an RGBA32UI target of its own, beside the reference depth (thirdLayer(); needs 5 draw
    // buffers): docs/DESIGN.md, "Corrected frames: three layers and no correction".
    // `compositeClears`: NeuralOptions::compositeClearsTargets (compositeClearsTargets() below).
    void findThreeLayers(bool compositeClears = false);
    // kbuffer-moments: only the packed pass ever runs (runPackedNearestAndSums), so resize allocates
    // only its targets (no pass-1 colour, pass 2, transmittance or second tail-moment target).
    // Before the first frame.
    void packedPassOnly() { packedOnly_ = true; }
    GLuint thirdLayer() const { return threeLayers_ ? thirdLayer_.id() : 0u; }
    // Three layers on desktop GL with a software rasteriser, unless turned off (findThreeLayers;
    // docs/DESIGN.md, "Corrected frames: the composite clears pass 3's targets"): there clears of
    // runPackedNearestAndSums' five targets took 5-8 ms of a 14-20 ms interpolated frame at
    // 1280x720, where the composite, which reads all five at each pixel any fragment reached, can
    // write their clear values back for a fraction of that. When the composite did so after a
    // runPackedNearestAndSums (targetsClearedByComposite()), the next one clears only its depth.
    bool compositeClearsTargets() const { return compositeClears_; }
    // The five targets the composite writes the clear values of runPackedNearestAndSums back into,
    // in its draw-buffer order after its output: packedNearest(), thirdLayer(), alphaColor(),
    // behindMoment1(), behindMoment2().
    std::array<GLuint, 5> packedTargets() const;
    // Says that the composite wrote the clear values at every pixel the last
    // runPackedNearestAndSums reached (its cover depth below 1). Any other pass into those targets
    // (a real frame's, a reallocation) undoes it.
    void targetsClearedByComposite();
    // The three of those targets that a real frame's pass 3 writes too (alphaColor(),
    // colorCount(), tailMoment1: their clear value is 0 in both kinds of frame). With
    // compositeClearsTargets(), a real frame's pass 3 skips their clears after a clearing
    // composite, and its inference may write 0 back into them at every pixel it shades
    // (sharedSumsClearedByInference()), so that the interpolated frame after it skips them too
    // (docs/DESIGN.md, "Corrected frames: the composite clears pass 3's targets").
    std::array<GLuint, 3> sharedSumTargets() const { return {alphaColor_.id(), colorCount_.id(), tailMoment1_.id()}; }
    // Says that the inference after the last run() wrote 0 into sharedSumTargets() at every pixel
    // pass 1 covered; pass 3 sums no fragment elsewhere (it drops those on the far plane, which
    // pass 1's depth test drops).
    void sharedSumsClearedByInference();
    // The moments an interpolated frame of a tail-moment method summed behind its reference (targets
    // its real frames' inference has read by then): (sum a C u, sum a u) in the first tail-moment
    // target, and in the count's (RG32F) sum a u^2 in .r and the optical depth sum -ln(1 - a) in .g
    // (its transmittance() is not written then; ordered_behind.glsl); 0 for the others.
    GLuint behindMoment1() const { return tailMoments_ ? tailMoment1_.id() : 0; }
    GLuint behindMoment2() const { return tailMoments_ ? colorCount_.id() : 0; }
    // Binds the pass outputs to the NeuralInputUnit units and sets the upsample uniforms of
    // `program` (which includes neural_inputs.glsl).
    void bindInputs(const gl::Program& program) const;
    size_t gpuMemoryBytes() const;
    // Format of an output texture of the method's own (RGBA16F or RGBA32F, as the targets).
    GLenum outputFormat() const;
    // The compact layout's transmittance target: GL_R16 (GL_R16F on ES without EXT_texture_norm16).
    static GLenum compactTransmittanceFormat();

    // Where the inference may write the output in place, after run(): a target that it reads at
    // the output pixel only, and that nothing reads after it. Pass 3's sums when pass 3 ran at full
    // resolution (nothing reads them after the inference), else pass 2's colour when pass 2 did
    // (the scale guard reads it, but only on probe frames, which run both at full resolution),
    // else pass 1's colour if the caller says nothing reads it later (`nearestFree`: no temporal
    // capture, no tiles update). None on OpenGL ES, which has no texture barrier to make the loop
    // defined. The texture keeps the output until the next run().
    struct OutputSlot {
        GLuint texture = 0, framebuffer = 0;
        const char* name = "output";  // the memory target it lives in
    };
    OutputSlot outputSlot(bool nearestFree) const;
    // Appends (name, bytes) of every target.
    void addMemoryTargets(OitMethod::MemoryTargets& out) const;
    const gl::Texture2D& nearest() const { return nearest_; }
    const gl::Texture2D& nearestDepth() const { return nearestDepth_; }
    const gl::Texture2D& second() const { return second_; }
    const gl::Texture2D& alphaColor() const { return alphaColor_; }
    const gl::Texture2D& colorCount() const { return colorCount_; }
    const gl::Texture2D& transmittance() const { return transmittance_; }
    bool tailMoments() const { return tailMoments_; }
    Size2 pass2Size() const { return pass2Size_; }
    Size2 pass3Size() const { return pass3Size_; }

private:
    void runSums(const FrameDesc& frame, const DrawCallback& draw, Size2 pass3Size, GLuint behindReference = 0);  // pass 3
    // The moments behind the reference (pass3_accumulate.frag.glsl, STARNT_BEHIND_MOMENTS): clears and
    // blends `target` of the bound framebuffer for (sum a C u, sum a u), binds `reference`;
    // beginSecondMomentAndOpticalDepth the interpolated frames' target of sum a u^2 and sum -ln(1 - a).
    // `clear` false: the target holds zeros already (compositeClearsTargets()).
    void beginBehindMoment(GLuint target, GLuint reference, bool clear = true);
    void beginSecondMomentAndOpticalDepth(GLuint target, bool clear = true);
    void makeSumsFramebuffer();
    // The count's target made RG32F (once; it stays so through resizes): the moments behind the
    // reference use its second channel (pass3_accumulate.frag.glsl).
    void widenCountBesideBehind();
    const char* behindMomentsDefine() const { return tailMoments_ ? "#define STARNT_BEHIND_MOMENTS\n" : ""; }
    OpaqueScene& opaque_;
    // (SurfaceProgram: the variant that clips by the opaque depth in its shader built where a frame has one.)
    SurfaceProgram pass1_;
    SurfaceProgram pass2_;
    SurfaceProgram pass2Reduced_;  // peels against the maximum over a reduced pixel's footprint; built on first need
    SurfaceProgram pass3_;
    gl::Program tailResolve_;
    gl::VertexArrayHandle emptyVao_;
    int width_ = 0, height_ = 0;
    Size2 pass2Size_, pass3Size_;
    gl::Texture2D nearest_, nearestDepth_, second_, secondDepth_, alphaColor_, colorCount_, transmittance_;
    gl::Texture2D layerAlpha_;  // narrow layers only: a1, a2
    gl::Texture2D tailMoment1_, tailMoment2_;  // tail moments only
    GLuint pass3Rates_ = 0;                    // setPass3ShadingRates
    bool pass3TailsOnly_ = false, pass3HoldsTails_ = false;
    gl::FramebufferHandle pass3TailFb_;        // pass 3's targets over pass 2's depth
    TailResolveCopies esResolveCopies_;  // OpenGL ES only: what the tail resolve reads
    gl::TargetClears clears_;            // gl/target_clears.hpp: copies on llvmpipe
    bool colorSums_ = true;
    NeuralOptions::Targets targets_;
    bool narrowLayers_ = false;
    bool tailMoments_ = false;
    gl::FramebufferHandle pass1Fb_, pass2Fb_, pass3Fb_;
    // runNearestAndSums' pass 3: sum a C, sum a and the transmittance only (12 bytes a fragment in
    // the compact layout, where a real frame of a tail-moment method blends 54).
    SurfaceShader surface_;  // for pass3Sums_, built on first need
    gl::Program pass3Sums_;
    gl::FramebufferHandle sumsFb_;
    // runPackedNearestAndSums' pass 3 and its targets: the sums and the packed nearest fragment.
    SurfaceProgram pass3Packed_;
    gl::Texture2D packedNearest_;  // allocated on first need
    bool twoLayers_ = false;       // findTwoLayers
    gl::Texture2D packedLayers_;   // the nearest two fragments (twoLayers_), allocated on first need
    bool threeLayers_ = false;     // findThreeLayers
    bool packedOnly_ = false;      // packedPassOnly
    // The tail-moment sums' and moments' format (4 or 2 channels): 32-bit floats, 16-bit in the
    // packed pass alone with compact targets.
    GLenum sumsFormat(int channels) const;
    bool compositeClears_ = false;  // compositeClearsTargets()
    // What holds its clear value at every texel, so that the next pass into it skips its clear
    // (compositeClears_ only): sharedSumTargets() (sumsClear_: after a clearing composite or
    // after the real frame's inference wrote 0 back); the packed layers and the third layer's
    // layers (layersClear_: after a clearing composite; a real frame writes neither). The third
    // layer's reference depth is the last interpolated frame's: a real frame makes a new one
    // (referenceStale_), which a full-screen pass writes there before the next pass 3.
    bool sumsClear_ = false, layersClear_ = false, referenceStale_ = false;
    // Three layers: the last pass into the targets was runPackedNearestAndSums, whose depth target
    // marks the pixels it wrote (below 1). Reset by any other pass into them.
    bool coverMarked_ = false;
    // New textures: nothing is known of them.
    void forgetTargets() { sumsClear_ = layersClear_ = coverMarked_ = false; }
    gl::Texture2D thirdLayer_;     // the third (threeLayers_) and the reference depth, allocated with packedLayers_
    // The third layer's clear: no layer and the reference depth of `reference` (packed_nearest.h),
    // everywhere or, `onlyMarked`, where the last pass 3 wrote (coverMarked_).
    void clearThirdLayer(GLuint reference, bool onlyMarked);
    gl::Program thirdLayerClear_;  // third_layer_clear.frag.glsl, built on first need
    gl::FramebufferHandle thirdLayerClearFb_, thirdLayerClearMarkedFb_;
    // A real frame's moments behind the reference (the first in packedNearest_, free then; the
    // second beside the count).
    SurfaceProgram pass3Behind_;
    gl::FramebufferHandle pass3BehindFb_;
    bool behindSummed_ = false;
    GLuint behindReference_ = 0;  // what the last behindSummed_ pass 3 read (not owned)
    bool behindMomentsFit_ = false;  // the context has the 6 draw buffers that pass 3 needs
    bool countBesideBehind_ = false;  // colorCount_ is RG32F: sum a v^2 beside the count
    void makePass3Framebuffer();
    void allocatePackedNearest();
    gl::FramebufferHandle packedFb_;
    gl::FramebufferHandle nearestOnlyFb_, secondOnlyFb_, alphaColorOnlyFb_;  // output slots
};

}  // namespace starnt
