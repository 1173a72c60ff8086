// Corrected interpolated frames on the GPU (`--temporal-mode correct`; correction_cpu.hpp
// states the method and is its CPU reference): what a real frame keeps (one RGBA texture: the
// network's correction of the closed form behind the nearest layer, and the texel's inverse view
// depth), and the composite of an interpolated frame from its own passes (pass 3 alone with the
// packed nearest layer, or passes 1 and 3).
#pragma once
#include <span>

#include <glm/glm.hpp>

#include "gl/gl_util.hpp"
#include "gl/shader.hpp"
#include "methods/neural/empty_pixels.hpp"
#include "starnt/oit_method.hpp"

namespace starnt::temporal {

class CorrectedFrames {
public:
    // Builds the programs; needs a current GL context. `ordered`: the tail-moment methods, whose
    // interpolated frames weigh what lies behind the nearest layer by depth (ordered_behind.glsl):
    // every kept frame then keeps a reference depth too (reference()), and the composites read the
    // moments pass 3 summed behind it.
    // ordered: the tail-moment methods' closed form (ordered_behind.glsl); layers (ordered only):
    // 2, their interpolated frames' packed target holds the nearest two fragments
    // (packed_nearest.h); 3, a second target the third (the real frames then keep no correction:
    // the interpolated frames composite the closed form behind the third layer alone).
    explicit CorrectedFrames(bool ordered = false, int layers = 1);

    // After a real frame: `composite` its output (RGBA16F or RGBA32F; the kept texture takes the same
    // format), `depth` its pass-1 depth (DEPTH_COMPONENT32F), `nearest` its pass-1 colour + alpha,
    // `sumAlphaColor` / `transmittance` its pass-3 sums at full resolution, all width x height.
    // Without sums (0: pass 3 ran reduced) the frame is kept without a correction: the interpolated
    // frames that follow composite the closed form alone.
    void capture(GLuint composite, GLuint depth, GLuint nearest, GLuint sumAlphaColor, GLuint transmittance, int width,
                 int height, const glm::mat4& viewProj, const OpaqueScene& background);
    // The same capture written by the real frame's own composite (infer_full.frag.glsl with
    // STARNT_CAPTURE_CORRECTION) instead of a pass of its own: beginFusedCapture copies pass 1's
    // `depth` for the composite's early empty-pixel test (the composite samples the original, see
    // composite() below) and returns {correction texture, depth copy} to attach; the composite's
    // second output writes what capture() would write at every shaded pixel, and the empty-pixel
    // fill writes "hidden" (alpha -1) everywhere else (EmptyPixelSkip::fillEmpty), so every texel
    // is written without a clear.
    // endFusedCapture keeps the frame. Same formats and rules as capture().
    struct FusedTargets {
        GLuint correction = 0, coverDepth = 0;
        glm::vec4 sourceScale{0.0f};  // u_sourceScale of the capture
    };
    FusedTargets beginFusedCapture(GLenum compositeFormat, GLuint depth, int width, int height, const glm::mat4& viewProj);
    void endFusedCapture();
    bool hasFrame() const { return hasFrame_; }
    // Three layers, with no real frame (kbuffer-moments): a frame of this size whose reference depth
    // is the far plane everywhere (depthBehindReference still orders the fragments in front of it),
    // for a first frame that only makes the reference of the next (TemporalFrames::takeLayeredPriming).
    void startLayered(int width, int height);
    int width() const { return width_; }
    int height() const { return height_; }

    // An interpolated frame at `newViewProj` from its own pass 1 (`nearest`, `depth`) and pass 3
    // (`sumAlphaColor`, `transmittance`, full resolution), into `output` (a colour-renderable RGBA
    // texture of the captured size; framebuffer binding 0 afterwards). Only the pixels pass 1
    // covered are shaded (empty_pixels.hpp), the background goes elsewhere; as the composite samples
    // pass 1's depth, the early test runs against a copy of it (a texture both sampled and attached
    // would be a rendering feedback loop, GL 4.5 section 9.3.1).
    // `behindMoment1`, `behindMoment2`: ordered only, pass 3's moments behind reference().
    void composite(const glm::mat4& newViewProj, GLuint nearest, GLuint depth, GLuint sumAlphaColor, GLuint transmittance,
                   const OpaqueScene& background, GLuint output, GLuint behindMoment1 = 0, GLuint behindMoment2 = 0);
    // The same from pass 3 alone: `packedNearest` holds the nearest fragment it found by blending
    // (packed_nearest.glsl), `coverDepth` (DEPTH_COMPONENT32F) a depth below 1 where pass 3 kept a
    // fragment, which the early empty-pixel test runs against (the composite does not sample it).
    // `clearTargets` (three layers only; NeuralPasses::compositeClearsTargets): the composite
    // writes the clear values of pass 3 into these (NeuralPasses::packedTargets: the packed layers,
    // the third layer, the sums and the two moment targets, the textures it reads) at every pixel
    // it shades; empty: it writes nothing but the output. `keepNextReference` (three layers): make
    // reference() again from this frame's layers, for a next interpolated frame; false when the
    // next frame is real (what the composite then writes beside the third layer is never read).
    void compositePacked(const glm::mat4& newViewProj, GLuint packedNearest, GLuint coverDepth, GLuint sumAlphaColor,
                         GLuint transmittance, const OpaqueScene& background, GLuint output, GLuint behindMoment1 = 0,
                         GLuint behindMoment2 = 0, GLuint thirdLayer = 0, std::span<const GLuint> clearTargets = {},
                         bool keepNextReference = true);
    // Ordered only: the kept frame's reference depth (R32F, one texel per
    // STARNT_ORDERED_REFERENCE_TILE pixels squared; reference_depth.frag.glsl), which an
    // interpolated frame's pass 3 reads; 0 before the first kept frame or when not ordered. With
    // three layers every interpolated frame's compositePacked makes it again from its own nearest
    // layers, for the next one (docs/DESIGN.md, "Corrected frames: the reference depth follows the
    // interpolated frames").
    GLuint reference() const { return hasFrame_ ? reference_.id() : 0; }
    // Ordered only: the reference depth from this real frame's pass-1 `depth`, now (before its pass 3
    // sums the moments behind it, for infer_full's STARNT_CAPTURE_ORDERED); the capture then keeps
    // it instead of making it again. Returns it.
    GLuint prepareReference(GLuint depth, int width, int height);
    bool ordered() const { return ordered_; }

    void reset() {
        hasFrame_ = false;
        referenceFresh_ = false;
    }
    size_t gpuMemoryBytes() const { return correction_.bytes() + coverDepth_.bytes() + referenceTiles_.bytes() + reference_.bytes(); }
    void addMemoryTargets(OitMethod::MemoryTargets& out) const {
        out.emplace_back("history_correction", correction_.bytes());
        out.emplace_back("corrected_cover_depth", coverDepth_.bytes());
        if (ordered_) out.emplace_back("corrected_reference_depth", referenceTiles_.bytes() + reference_.bytes());
    }

private:
    // Ordered only: the reference depth from a real frame's pass-1 `depth` or, `packed`, from an
    // interpolated frame's packed layers (three layers: the next interpolated frame's reference).
    void keepReference(GLuint depth, int width, int height, bool packed = false);
    void allocateReference(int width, int height);  // at one texel per reference tile
    void bindComposite(GLuint nearestOrPacked, GLuint depth, GLuint sumAlphaColor,
                       GLuint transmittance, GLuint behindMoment1, GLuint behindMoment2);
    bool ordered_ = false;
    bool twoLayers_ = false;
    bool threeLayers_ = false;
    bool referenceFresh_ = false;  // prepareReference ran in this real frame
    gl::Program capture_, composite_, compositePacked_;
    gl::Program compositePackedClears_;  // compositePacked with clearTargets (STARNT_CLEARS_TARGETS), built on first need
    gl::Program referenceTilesPass_, referenceAroundPass_;  // ordered only
    gl::Program referencePackedTilesPass_;                   // three layers only
    gl::Texture2D referenceTiles_, reference_;
    void setCompositeUniforms(const gl::Program& program, const glm::mat4& newViewProj, const OpaqueScene& background,
                              bool halfOutput) const;
    gl::VertexArrayHandle emptyVao_;
    gl::FramebufferHandle framebuffer_;
    gl::Texture2D correction_;
    gl::Texture2D coverDepth_;  // the copy of pass 1's depth the empty-pixel test runs against
    EmptyPixelSkip emptyPixels_;
    int width_ = 0, height_ = 0;
    glm::mat4 viewProj_{1.0f};
    bool hasFrame_ = false, hasCorrection_ = false;
};

}  // namespace starnt::temporal
