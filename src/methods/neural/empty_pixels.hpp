// Empty pixels: where pass 1 saw no fragment, every neural composite (starnt, dfaoit, hybrid) and a
// refresh frame's composite is the background, exactly (no fragment means no pass-2/3 fragment
// either: readPixelSums). The full-screen passes that produce the image therefore shade only the
// pixels pass 1 covered, and one trivial pass writes the background into the rest:
//   - the covered pixels: an early depth test of the full-screen triangle, which lies on the far
//     plane (window depth 1; fullscreen.vert.glsl), GREATER against pass 1's depth (1 where nothing
//     was drawn; pass 1 tests LESS against that clear value, so it never keeps a fragment at 1);
//   - the empty pixels: the same test with LEQUAL, writing the background (rounded to the nearest
//     16-bit float for a 16-bit output, as the composites' own writes are: half_targets.glsl).
// The images are bit for bit those of shading every pixel. Why it pays: the early test rejects
// whole blocks before the fragment shader runs, on GPUs (hierarchical depth) and on llvmpipe alike,
// whereas an `if` in the shader does not help on llvmpipe, which runs every lane of both sides of a
// branch. Measured on llvmpipe, magic_stars at 1280x720, starnt with full-resolution passes: the
// inference went from 18.1 to 2.6 ms.
// Not usable when the shader itself samples pass 1's depth (joint upsampling): that would be a
// rendering feedback loop (GL 4.5 section 9.3.1); the caller draws without it then.
#pragma once
#include <span>

#include <glm/glm.hpp>

#include "gl/gl_util.hpp"
#include "gl/shader.hpp"
#include "methods/common/opaque_scene.hpp"

namespace starnt {

class EmptyPixelSkip {
public:
    EmptyPixelSkip();  // builds the background program; needs a current GL context

    // Binds a framebuffer with `colorTexture` (the output) and `pass1Depth` (pass 1's
    // DEPTH_COMPONENT32F depth, the output's size) attached, a full viewport of that size, and the
    // depth state under which the next draws shade only the covered pixels (no depth writes).
    // Throws starnt::Error if the framebuffer is incomplete.
    // `secondColor` (optional): a second target at draw buffer 1 that the composite writes too
    // (the fused capture of corrected frames); fillEmpty writes (0, 0, 0, -1) there, "hidden".
    // `moreTargets`: further targets the composite writes, at the draw buffers after those (the
    // interpolated frames' pass-3 targets it clears: NeuralPasses::compositeClearsTargets);
    // neither clearToBackground nor fillEmpty writes them. At most 8 targets in all.
    void bindCovered(GLuint colorTexture, GLuint pass1Depth, int width, int height, GLuint secondColor = 0,
                     std::span<const GLuint> moreTargets = {});
    // Before the covered pixels are drawn, where the background is one colour and the composite
    // does not read the output (a texture of the caller's own, not a pass target written in place):
    // clears the bound targets to what fillEmpty would write, which then draws nothing. Returns
    // whether it cleared. Why: on llvmpipe the fill's full-screen draw took 3.5-4 ms a 1280x720 frame
    // (magic_stars, chess: every block runs the depth test, most shade), a clear next to nothing
    // (docs/DESIGN.md, "Corrected frames: the cost of real and interpolated frames").
    bool clearToBackground(const OpaqueScene& background, bool halfOutput);
    // After the covered pixels were drawn: writes the background into the empty ones (unless
    // clearToBackground did) and restores the default depth state (test off, function LESS, writes
    // on) and the frame's depth range (resetPassState).
    void fillEmpty(const OpaqueScene& background, bool halfOutput, const gl::VertexArrayHandle& emptyVao);

private:
    gl::Program background_;
    static constexpr size_t kMaxTargets = 8;
    static const GLenum kDrawBuffers[kMaxTargets];
    gl::FramebufferHandle framebuffer_;
    size_t attached_ = 0;  // colour attachments of framebuffer_, the output's included
    bool second_ = false;  // a second target is attached
    bool cleared_ = false;  // clearToBackground wrote the empty pixels of this composite
};

}  // namespace starnt
