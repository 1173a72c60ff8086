// The three geometry passes of the low-end neural OIT pipeline (no interlock, no per-pixel
// lists), shared by `starnt` and `dfaoit` (SPEC section 2):
//   pass 1: nearest fragment (colour+alpha, depth)        full resolution
//   pass 2: second-nearest by peeling against pass 1      scale s2 (1 in this version)
//   pass 3: sums over all fragments                       scale s3 (1 in this version)
// Target formats (chosen for precision; memory is reported per method):
//   nearest / second colour RGBA32F, their depths DEPTH_COMPONENT32F,
//   sum aC + sum a RGBA32F, sum C + N RGBA32F, transmittance R32F.
#pragma once
#include "methods/common/method_base.hpp"

namespace starnt {

// Texture units the composite shaders read the pass outputs from.
enum NeuralInputUnit : GLuint {
    kUnitNearest = 0,
    kUnitSecond = 1,
    kUnitAlphaColor = 2,
    kUnitColorCount = 3,
    kUnitTransmittance = 4,
    kUnitNearestDepth = 5,
};

class NeuralPasses {
public:
    // Default peel epsilon: 1e-6 in window depth, about 16 float steps near the far plane. The
    // same fragment reproduces its pass-1 depth bit for bit (invariant gl_Position), so any
    // epsilon >= 0 removes it; the small margin also merges surfaces closer than that, which
    // would otherwise flicker between first and second with rounding.
    static constexpr float kDefaultPeelEpsilon = 1e-6f;

    NeuralPasses(const gl::Program& pass1, const gl::Program& pass2, const gl::Program& pass3);

    void resize(int width, int height);
    void run(const FrameDesc& frame, const DrawCallback& draw, float peelEpsilon);
    void bindInputs() const;  // binds the pass outputs to the NeuralInputUnit units
    size_t gpuMemoryBytes() const;
    const gl::Texture2D& nearestDepth() const { return nearestDepth_; }

private:
    const gl::Program& pass1_;
    const gl::Program& pass2_;
    const gl::Program& pass3_;
    int width_ = 0, height_ = 0;
    gl::Texture2D nearest_, nearestDepth_, second_, secondDepth_, alphaColor_, colorCount_, transmittance_;
    gl::FramebufferHandle pass1Fb_, pass2Fb_, pass3Fb_;
};

}  // namespace starnt
