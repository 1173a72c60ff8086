#include "methods/common/surface_program.hpp"

#include <utility>

namespace starnt {

gl::Program buildSurfaceProgram(const SurfaceShader& surface, const std::string& label, const std::string& fragmentFile,
                                const std::string& defines) {
    std::string fragment = surface.fragment + "\n#include \"methods/common/surface_fetch.glsl\"\n" +
                           "#include \"" + fragmentFile + "\"\n";
    return gl::buildProgram(label, surface.vertex, fragment, defines);
}

SurfaceProgram::SurfaceProgram(const SurfaceShader& surface, std::string label, std::string fragmentFile, std::string defines)
    : surface_(surface),
      label_(std::move(label)),
      fragmentFile_(std::move(fragmentFile)),
      defines_(std::move(defines)),
      plain_(buildSurfaceProgram(surface_, label_, fragmentFile_, defines_)) {}

const gl::Program& SurfaceProgram::clipping() {
    if (!clipping_.id()) {
        clipping_ = buildSurfaceProgram(surface_, label_ + "_opaque_clip", fragmentFile_, defines_ + "\n#define STARNT_OPAQUE_CLIP\n");
    }
    return clipping_;
}

}  // namespace starnt
