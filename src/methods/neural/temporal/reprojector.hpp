// GPU reprojection of the last real frame to a new camera (SPEC section 6): four small compute
// passes doing forward splatting with a nearest-depth test and a hole fill. The algorithm, its
// fallback and a CPU reference are in reprojection_reference.hpp.
#pragma once
#include <glm/glm.hpp>

#include "core/gl_util.hpp"
#include "core/shader.hpp"

namespace starnt::temporal {

class Reprojector {
public:
    Reprojector();  // builds the programs; needs a current GL context

    // Keeps a copy of a real frame: its composite (linear RGBA float texture), its pass-1 depth
    // (DEPTH_COMPONENT32F or R32F texture, window depth, 1 = far plane where nothing was drawn),
    // both width x height, and the view-projection (GL clip conventions) it was rendered with.
    void capture(GLuint colorTexture, GLuint depthTexture, int width, int height, const glm::mat4& viewProj);
    bool hasFrame() const { return hasFrame_; }
    int width() const { return width_; }
    int height() const { return height_; }
    const glm::mat4& capturedViewProj() const { return viewProj_; }

    // Writes the captured frame as seen with `newViewProj` into `outputTexture`, an immutable
    // RGBA32F texture of the captured size (written with image stores). Throws starnt::Error when
    // nothing was captured.
    void reproject(const glm::mat4& newViewProj, GLuint outputTexture) const;

    void reset() { hasFrame_ = false; }  // forgets the frame, keeps the allocations
    size_t gpuMemoryBytes() const;

private:
    void dispatch(const gl::Program& program) const;
    gl::Program capture_, clear_, splat_, pick_, gather_;
    gl::Buffer color_, depth_, splats_, winnerKey_, winnerSource_;
    int width_ = 0, height_ = 0;
    glm::mat4 viewProj_{1.0f};
    bool hasFrame_ = false;
};

}  // namespace starnt::temporal
