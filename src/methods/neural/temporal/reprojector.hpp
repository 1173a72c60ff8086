// GPU reprojection of the last real frame to a new camera (docs/DESIGN.md, "Temporal reprojection"): a copy of the real
// frame, then one full-screen pass that searches each output pixel's source
// (reprojection_search.frag.glsl). The algorithm, its fallback and a CPU reference are in
// reprojection_cpu.hpp.
#pragma once
#include <glm/glm.hpp>

#include "gl/gl_util.hpp"
#include "starnt/oit_method.hpp"
#include "gl/shader.hpp"
#include "methods/neural/empty_pixels.hpp"

namespace starnt::temporal {

class Reprojector {
public:
    Reprojector();  // builds the program; needs a current GL context

    // Keeps a copy of a real frame: its composite (RGBA32F texture), its pass-1 depth
    // (DEPTH_COMPONENT32F or R32F texture, window depth, 1 = far plane where nothing was drawn),
    // both width x height, and the view-projection (GL clip conventions) it was rendered with.
    // With `nearestTexture` (RGBA32F pass-1 colour + alpha) it is kept too, for refresh frames.
    // With `premultiply` (the frame's opaque scene) the composite holds the transmittance in alpha
    // and the history keeps the layers over black with it (history_premultiplied.frag.glsl), so that
    // interpolated frames composite over their own frame's background and opaque depth.
    void capture(GLuint colorTexture, GLuint depthTexture, int width, int height, const glm::mat4& viewProj,
                 GLuint nearestTexture = 0, const OpaqueScene* premultiply = nullptr);
    bool hasFrame() const { return hasFrame_; }
    int width() const { return width_; }
    int height() const { return height_; }

    // Renders the captured frame as seen with `newViewProj` into `outputTexture`, a colour-renderable
    // RGBA texture of the captured size. Throws starnt::Error when nothing was captured.
    // With a premultiplied history, over `background` (its colour, and its opaque depth, which hides
    // a source point that now lies at or behind it).
    void reproject(const glm::mat4& newViewProj, GLuint outputTexture, const OpaqueScene& background = OpaqueScene());
    // A refresh frame (temporal::refreshComposite): `nearestTexture` is pass 1 rendered at the new
    // camera (RGBA32F or RGBA16F, captured size) and `nearestDepth` its depth
    // (DEPTH_COMPONENT32F): the search runs only where pass 1 drew, the background goes elsewhere
    // (empty_pixels.hpp); 0 searches every pixel (the same image). Throws when the capture kept no
    // nearest layer.
    void reprojectRefresh(const glm::mat4& newViewProj, GLuint nearestTexture, GLuint nearestDepth,
                          const OpaqueScene& background, GLuint outputTexture);

    void reset() { hasFrame_ = false; }  // forgets the frame, keeps the allocations
    void addMemoryTargets(starnt::OitMethod::MemoryTargets& out) const {
        out.insert(out.end(), {{"history_color", color_.bytes()},
                               {"history_depth", depth_.bytes()},
                               {"history_nearest", keptNearest_.bytes()},
                               {"history_behind", behind_.bytes()},
                               {"history_search_seeds", blockMinMax_.bytes() + seeds_.bytes()}});
    }
    size_t gpuMemoryBytes() const {
        return color_.bytes() + depth_.bytes() + keptNearest_.bytes() + behind_.bytes() + blockMinMax_.bytes() +
               seeds_.bytes();
    }

private:
    void setSearchUniforms(const gl::Program& program, const glm::mat4& newViewProj) const;

    gl::Program blockSeeds_, dilateSeeds_, search_, searchRefresh_, behindProgram_;
    gl::Program premultiply_;  // built on first need
    bool premultiplied_ = false;  // the history holds (layers over black, transmittance)
    gl::VertexArrayHandle emptyVao_;
    gl::Texture2D color_, depth_, keptNearest_, behind_;
    bool hasNearest_ = false;
    gl::Texture2D blockMinMax_, seeds_;  // RG32F (min, max) depth per block, then dilated
    gl::FramebufferHandle framebuffer_;
    EmptyPixelSkip emptyPixels_;
    int width_ = 0, height_ = 0;
    glm::mat4 viewProj_{1.0f};
    bool hasFrame_ = false;
};

}  // namespace starnt::temporal
