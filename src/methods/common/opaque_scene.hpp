// The engine's opaque scene as every method uses it (FrameDesc::opaqueDepth, backgroundTexture,
// premultipliedOutput; docs/DESIGN.md, "Opaque geometry"):
//   - clipping: each geometry pass drops fragments at or behind the opaque depth. Passes without a
//     depth target of their own (sums, accumulation, lists: most fragments) by the depth test before
//     their fragment shader runs, against a DEPTH32F copy of the opaque depth in the engine's
//     convention made canonical (one copy or full-screen pass a frame, depth writes off); passes that
//     keep the nearest fragment in a depth target of their own (pass 1, pass 2, peel layers), whose
//     depth must stay 1 where nothing transparent is, in surface_fetch.glsl, comparing the same float
//     values first thing. The engine's texture is only sampled.
//   - the background: every composite reads background.glsl, whose uniforms bindBackground sets.
#pragma once
#include <optional>
#include <string>

#include "gl/gl_util.hpp"
#include "gl/shader.hpp"
#include "methods/common/surface_program.hpp"
#include "starnt/bindings.h"
#include "starnt/oit_method.hpp"

namespace starnt {

class OpaqueScene {
public:
    OpaqueScene() = default;
    // No opaque scene: the constant `background` (until begin()).
    OpaqueScene(const glm::vec3& background) : color_(background) {}  // NOLINT: implicit on purpose

    // Checks the frame's opaque textures against the frame size, before anything is drawn: a name
    // that is not a 2D texture, a texture of another size, a depth texture of a colour format or
    // the reverse is a starnt::Error naming the FrameDesc field. Forgets the last frame's copies.
    void begin(const FrameDesc& frame);
    // Whether the frame's geometry passes are clipped by an opaque depth.
    bool clips() const { return depth_ != 0; }

    // For a pass with a depth target of its own rendering a rectangle of width x height of a frame
    // of fullWidth x fullHeight: binds and returns the variant of `program` to draw with, the one
    // that clips in its fragment shader (surface_fetch.glsl) when the frame clips, with its uniforms
    // and the opaque depth bound, else the plain one; a reduced texel takes the opaque depth of the
    // full pixel holding its sample (reduced_grid.hpp), as pass 3's copy does, so pass 1, 2 and 3
    // keep the same fragments.
    const gl::Program& clipInShader(SurfaceProgram& program, int width, int height, int fullWidth, int fullHeight) const;
    // For a pass without a depth target of its own, rendering into `framebuffer` (bound, viewport
    // and scissor set, rectangle as above): when the frame clips, attaches the method's copy of
    // the opaque depth and enables the depth test (LESS, no depth writes). endDepthTest detaches
    // it. Without opaque depth both do nothing.
    void beginDepthTest(GLuint framebuffer, int width, int height, int fullWidth, int fullHeight);
    void endDepthTest(GLuint framebuffer);

    // Sets background.glsl's uniforms on `program` (bound) and binds the engine's colour texture,
    // if any, to STARNT_UNIT_OPAQUE.
    void bindBackground(const gl::Program& program) const;
    // Binds the engine's depth texture (with the method's sampler) to `unit` (STARNT_UNIT_OPAQUE
    // unless a pass samples the background there too).
    void bindOpaqueDepth(GLuint unit = STARNT_UNIT_OPAQUE) const;
    // Unbinds the method's sampler from STARNT_UNIT_OPAQUE (the engine's own use of that unit
    // outside render() must see its texture's parameters) and gives the engine's textures back the
    // read state begin() reset: the end of every render().
    void end();
    // The output alpha the composites write is the transmittance (premultiplied output).
    bool premultiplied() const { return premultiplied_; }
    // What an empty pixel's composite is (background.glsl, transmittance 1), when it is one colour
    // for the whole frame: none with a background texture.
    std::optional<glm::vec4> uniformBackground() const {
        if (background_) return std::nullopt;
        return glm::vec4(premultiplied_ ? glm::vec3(0.0f) : color_, 1.0f);
    }
    // Whether the frame has an opaque scene or a premultiplied output: what the last real frame's
    // composite held for the background then changes from frame to frame.
    bool active() const { return depth_ || background_ || premultiplied_; }
    // While on, the composites (bindBackground) write the transmittance in alpha beside the colour
    // over the background: what a real frame's capture turns into a premultiplied history.
    void setTransmittanceInAlpha(bool on) { transmittanceInAlpha_ = on; }

    size_t gpuMemoryBytes() const { return clipDepth_.bytes(); }

private:
    void writeDepth(int width, int height, int fullWidth, int fullHeight);
    void prepare();

    GLuint depth_ = 0, background_ = 0;
    // The engine's textures whose read state (gl::TextureReadState) begin() set to the defaults,
    // with what end() puts back.
    std::vector<std::pair<GLuint, gl::TextureReadState>> restoreRead_;
    GLenum depthFormat_ = 0;
    bool premultiplied_ = false, transmittanceInAlpha_ = false;
    mutable GLuint depthUnit_ = STARNT_UNIT_OPAQUE;  // where bindOpaqueDepth put the sampler last
    glm::vec3 color_{1.0f};
    gl::Program fill_;
    gl::VertexArrayHandle vao_;
    gl::SamplerHandle sampler_;
    gl::Texture2D clipDepth_;        // frame size; holds the rectangle last written
    gl::FramebufferHandle clipFb_;  // clipDepth_ alone, for the copy's full-screen pass
    int clipWidth_ = 0, clipHeight_ = 0;  // that rectangle this frame (0: not written yet)
};

}  // namespace starnt
