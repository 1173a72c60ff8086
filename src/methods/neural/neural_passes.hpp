// The three geometry passes of the low-end neural OIT pipeline (no interlock, no per-pixel
// lists), shared by `starnt` and `dfaoit` (SPEC section 2):
//   pass 1: nearest fragment (colour+alpha, depth)        full resolution
//   pass 2: second-nearest by peeling against pass 1      scale s2 (against a max-downsampled depth)
//   pass 3: sums over all fragments                       scale s3
//   (then, if pass 2 or 3 was reduced, their tails: tail_resolve.frag.glsl)
// Passes 2 and 3 render into the lower-left ceil(W s) x ceil(H s) rectangle of full-size targets,
// so a change of scale from frame to frame never reallocates; the inference reads them back at
// full resolution through upsample.glsl.
// Target formats (chosen for precision; memory is reported per method):
//   nearest / second colour RGBA32F, their depths DEPTH_COMPONENT32F, reduced depth R32F,
//   sum aC + sum a RGBA32F, sum C + N RGBA32F, transmittance R32F; these three with GL_LINEAR
//   filtering, as the inference reads their reduced tails through the bilinear filter.
#pragma once
#include <string>

#include "methods/common/method_base.hpp"
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
gl::Program buildTailResolveProgram();
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

    // Builds the three geometry-pass programs around the engine's surface shader.
    explicit NeuralPasses(const SurfaceShader& surface);

    void resize(int width, int height);
    // Renders the three passes; pass2Size / pass3Size are the reduced sizes (the full size for s = 1).
    void run(const FrameDesc& frame, const DrawCallback& draw, float peelEpsilon, Size2 pass2Size, Size2 pass3Size);
    // Pass 1 alone (nearest() and nearestDepth()), for refresh frames.
    void runNearest(const FrameDesc& frame, const DrawCallback& draw);
    // Binds the pass outputs to the NeuralInputUnit units and sets the upsample uniforms of
    // `program` (which includes neural_inputs.glsl).
    void bindInputs(const gl::Program& program) const;
    size_t gpuMemoryBytes() const;
    // Appends (name, bytes) of every target.
    void addMemoryTargets(OitMethod::MemoryTargets& out) const;
    const gl::Texture2D& nearest() const { return nearest_; }
    const gl::Texture2D& nearestDepth() const { return nearestDepth_; }
    const gl::Texture2D& second() const { return second_; }
    const gl::Texture2D& alphaColor() const { return alphaColor_; }
    const gl::Texture2D& colorCount() const { return colorCount_; }
    const gl::Texture2D& transmittance() const { return transmittance_; }
    Size2 pass2Size() const { return pass2Size_; }
    Size2 pass3Size() const { return pass3Size_; }

private:
    gl::Program pass1_;
    gl::Program pass2_;
    gl::Program pass3_;
    gl::Program depthDownsample_, tailResolve_;
    gl::VertexArrayHandle emptyVao_;
    int width_ = 0, height_ = 0;
    Size2 pass2Size_, pass3Size_;
    gl::Texture2D nearest_, nearestDepth_, reducedDepth_, second_, secondDepth_, alphaColor_, colorCount_, transmittance_;
    TailResolveCopies esResolveCopies_;  // OpenGL ES only: what the tail resolve reads
    gl::FramebufferHandle pass1Fb_, pass2Fb_, pass3Fb_;
};

}  // namespace starnt
