// Geometry-pass programs: the engine's surface shader wrapped by a method's fragment file (which
// calls fetchSurfaceOrDiscard(), methods/common/surface_fetch.glsl).
#pragma once
#include <string>

#include "gl/shader.hpp"
#include "starnt/oit_method.hpp"

namespace starnt {

// One geometry-pass program, without the opaque clip in its shader.
gl::Program buildSurfaceProgram(const SurfaceShader& surface, const std::string& label, const std::string& fragmentFile,
                                const std::string& defines = {});

// A geometry-pass program for a pass that keeps its nearest fragment in a depth target of its own
// and so clips by the engine's opaque depth in its fragment shader (OpaqueScene::clipInShader). The
// clip is a variant of its own (STARNT_OPAQUE_CLIP), built on the first frame that has an opaque
// depth, not a branch on a uniform: llvmpipe runs a branch's masked fetch and integer division for
// every fragment even where a uniform turns it off (docs/DESIGN.md, "Findings on Mesa llvmpipe":
// 80 ms of hairball's 520 ms pass at 1280x720).
class SurfaceProgram {
public:
    SurfaceProgram() = default;
    // Builds the variant without the clip; needs a current GL context.
    SurfaceProgram(const SurfaceShader& surface, std::string label, std::string fragmentFile, std::string defines = {});

    GLuint id() const { return plain_.id(); }  // 0 until built
    const gl::Program& plain() const { return plain_; }
    // The variant that clips in its shader, built on first need.
    const gl::Program& clipping();

private:
    SurfaceShader surface_;
    std::string label_, fragmentFile_, defines_;
    gl::Program plain_, clipping_;
};

}  // namespace starnt
