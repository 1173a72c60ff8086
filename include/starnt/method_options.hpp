// Options of the methods, one group per method family. createMethod reads the group of the method
// it builds and ignores the others, so one MethodOptions can configure every method of a
// comparison.
#pragma once
#include <cstddef>
#include <optional>
#include <string>

namespace starnt {

// abuffer: exact per-pixel fragment lists (the reference).
struct AbufferOptions {
    double initialNodesPerPixel = 4.0;              // initial pool size, 0..65536; it grows on overflow
    size_t memoryCapBytes = size_t(2) << 30;        // createMethod/render fail with a clear error beyond this
};

// peel: depth peeling.
struct PeelOptions {
    int layers = 0;  // number of layers; 0 peels until a layer comes back empty (exact)
};

// wboit: weighted blended OIT (McGuire & Bavoil 2013).
struct WboitOptions {
    std::string weight = "eq10";  // "eq10" (default), "eq7", "eq8", "eq9"
};

// mboit: moment-based OIT (Muenstermann et al. 2018), 32-bit float storage.
struct MboitOptions {
    std::string moments = "6";  // "4" or "6" power moments, "t2" or "t3" trigonometric moments
};

// starnt, dfaoit, hybrid, starnt-residual, hybrid-moments and starnt-d: the neural methods (three
// passes, docs/DESIGN.md, "Pipeline and formats") and their acceleration (docs/DESIGN.md, "Adaptive tiles and tile-guided resolution"; hybrid-moments and starnt-d run every pass at
// full resolution and refuse tiles, reduced scales, corner inference and joint upsampling).
// The longest fixed temporal interval K: SPEC 6's 4 doubled, because corrected frames with three
// layers take nothing from the real frame but a reference depth, and their error does not grow
// with K (docs/DESIGN.md, "The recommended configuration", "Why K = 8").
constexpr int kMaxTemporalInterval = 8;

struct NeuralOptions {
    // Weights file; empty = the shipped default for the method. hybrid and hybrid-moments have no
    // network.
    std::string weightsPath;

    // Adaptive screen-space tiles evaluated after every real frame; their level histogram (w_bar)
    // sets the pass 2/3 scales of the next real frame. Unset: on for starnt (and hybrid,
    // starnt-residual), off for dfaoit, hybrid-moments and starnt-d.
    std::optional<bool> spatial;
    // Fixed pass 2/3 scales per axis in [0.25, 1] for ablations; 0 = chosen by the tiles (1 when
    // spatial is off).
    float fixedScale2 = 0.0f;
    float fixedScale3 = 0.0f;
    // How the tiles' w_bar becomes the scales (docs/DESIGN.md, "Adaptive tiles and tile-guided resolution"): Snapped (default) = the paper's value
    // snapped to 1, 1/2 or 1/4 (integer ratios keep reduced samples on pixel centres);
    // Continuous = the paper's formula as printed; Step = the authors' release.
    enum class ScaleRule { Snapped, Continuous, Step };
    ScaleRule scaleRule = ScaleRule::Snapped;
    // What the tiles measure (docs/DESIGN.md, "Adaptive tiles and tile-guided resolution"): Back (default) = the composite minus the nearest layer's
    // own term, C - a1 C1, what the reduced passes produce; Composite = the paper.
    enum class TileSignal { Back, Composite };
    TileSignal tileSignal = TileSignal::Back;
    // Scale guard (beyond the paper): passes 2/3 run at full resolution on probe frames (the first
    // real frames after a reset, then every 8th real frame); there the tiles update and the loss
    // of each reduced scale is predicted from the full-resolution image, and a pass is reduced
    // only as far as that loss stays within a fixed share of what the pass adds. It keeps thin
    // structures (hair, strands) that fall between tile corners at full resolution. Off: the
    // tiles update on every real frame and the rule alone decides (the paper).
    bool scaleGuard = true;
    // How reduced passes 2/3 come back to full resolution (docs/DESIGN.md, "Adaptive tiles and tile-guided resolution"): Bilinear = the four nearest
    // reduced samples by distance; Joint = joint bilateral, the same taps weighted down where the
    // nearest surface at a tap's sample lies at another depth than at the pixel.
    enum class Upsample { Bilinear, Joint };
    Upsample upsample = Upsample::Bilinear;
    // Full: the network at every pixel. Corners: only at quadtree leaf corners, bilinear inside each
    // leaf (beyond the paper; needs the tiles, so it turns them on).
    enum class Inference { Full, Corners };
    Inference inference = Inference::Full;
    // Temporal reprojection: one real frame, then temporalInterval - 1 interpolated frames
    // (1 = off, at most kMaxTemporalInterval = 8). temporalAuto picks the largest interval up to 4
    // (SPEC 6's rule) whose group (one real frame, interval - 1 interpolated ones, at their measured
    // costs) fits in one frame at targetFps.
    int temporalInterval = 1;
    bool temporalAuto = false;
    // What an interpolated frame renders (docs/DESIGN.md, "Temporal reprojection"): Warp = the paper (the last real frame's
    // composite reprojected; no geometry pass); Refresh = pass 1 at the current camera, so the
    // nearest layer is exact, over what lay behind it in the last real frame, reprojected;
    // Correct = the nearest layer and pass 3's sums at the current camera (one geometry pass, see
    // correctedOnePass), what lies behind the nearest layer in closed
    // form from those sums plus the network's correction of the last real frame, reprojected
    // (beyond the paper and docs/DESIGN.md, "Temporal reprojection"; docs/DESIGN.md, "Corrected frames").
    enum class TemporalMode { Warp, Refresh, Correct };
    // The default: Correct, which measured best on quality against time (docs/DESIGN.md, "Corrected frames").
    TemporalMode temporalMode = TemporalMode::Correct;
    // Corrected frames render one geometry pass: pass 3 finds the nearest fragment too, by
    // blending a packed (depth, colour) with GL_MIN (docs/DESIGN.md, "Corrected frames in one
    // geometry pass"); off: pass 1 for the nearest fragment, then pass 3 (two geometry passes).
    bool correctedOnePass = true;
    // Layers an interpolated frame of the tail-moment methods (hybrid-moments, starnt-d,
    // recommended) finds exactly in its one geometry pass (docs/DESIGN.md, "Corrected frames: the
    // second layer by framebuffer fetch" and "... three layers"): Three = the nearest three
    // fragments, every fragment reading and rewriting two packed targets in draw order (needs
    // GL_EXT_shader_framebuffer_fetch and 5 draw buffers), the ordered closed form behind the third
    // and no correction from the real frames (which then render as at K = 1); Two = the nearest two
    // the same way, the real frames' network correction added; One = the nearest, by MIN blending;
    // Auto = the most the driver allows (Mesa's llvmpipe, most mobile GPUs: Three), One elsewhere.
    enum class CorrectedLayers { Auto, One, Two, Three };
    CorrectedLayers correctedLayers = CorrectedLayers::Auto;
    double targetFps = 60.0;
    // Precision of the pass targets and the output (docs/DESIGN.md, "Pipeline and formats"): Compact (default) = 16-bit float
    // colours, sums and count, a 16-bit unsigned normalised transmittance, 32-bit depths, and the
    // output written in place into a pass target the inference no longer needs (36 bytes a pixel at
    // full resolution; DFAOIT at full resolution without tiles or temporal frames: 10-bit layer
    // colours, 16-bit alphas apart, a 16-bit pass-2 depth, 36 bytes too);
    // Float32 = every colour target 32-bit float (the earlier layout, for comparison).
    enum class Targets { Compact, Float32 };
    Targets targets = Targets::Compact;
    // The composite passes shade only the pixels where pass 1 saw a fragment and write the
    // background into the others (bit for bit the same image; methods/neural/empty_pixels.hpp).
    // Off only to compare against shading every pixel. Joint upsampling always shades every pixel.
    bool skipEmptyPixels = true;
    // Corrected frames: the real frame's composite writes the correction they keep as a second
    // output, instead of a capture pass of its own (docs/DESIGN.md, "Corrected frames"). Falls back
    // to the pass where the composite cannot (corner inference, joint upsampling, reduced pass 3,
    // skipEmptyPixels off). false: always the pass, for comparison.
    bool fusedCorrectionCapture = true;
    // Corrected frames with three layers, on desktop GL with a software rasteriser (llvmpipe): the
    // interpolated frame's composite writes the clear values back into the targets of its pass 3
    // at every pixel it shades, so that the next frame's pass 3 skips their clears, a real frame's
    // too for the three targets both kinds of frame sum into; a real frame's inference writes 0
    // back into those three, so that the interpolated frame after it skips them as well
    // (docs/DESIGN.md, "Corrected frames: the composite clears pass 3's targets"). The same images;
    // false: the clears, for comparison. On a GPU (clears are free there) and on OpenGL ES it has no
    // effect.
    bool compositeClearsTargets = true;
    // Per-tile shading rates for pass 3 through the driver's shading-rate image (docs/DESIGN.md,
    // "Per-tile shading rates on GPUs"; GL_NV_shading_rate_image, a GPU feature): with the adaptive
    // tiles and the scale guard, each 16x16 tile's pass-3 fragments are shaded once per pixel, per
    // 2x2 or per 4x4 pixels, as the guard's prediction for that tile allows, instead of one reduced
    // scale for the whole pass (that pass 3 then sums only what lies behind the second layer). Not
    // with temporal frames. Off (default: not yet measured on a GPU); Auto: where the driver offers
    // it, else the whole-pass scales as with Off; On: required (an error without it).
    enum class ShadingRateImage { Off, Auto, On };
    ShadingRateImage shadingRateImage = ShadingRateImage::Off;
};

struct MethodOptions {
    AbufferOptions abuffer;
    PeelOptions peel;
    WboitOptions wboit;
    MboitOptions mboit;
    NeuralOptions neural;
};

}  // namespace starnt
