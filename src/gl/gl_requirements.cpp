// What every method needs of the current context (declared in starnt/oit_method.hpp).
#include <epoxy/gl.h>

#include <string>

#include "starnt/error.hpp"
#include "starnt/oit_method.hpp"

namespace starnt {

void checkGlRequirements() {
    // Without a current context GL calls do nothing and glGetString returns null.
    if (glGetString(GL_VERSION) == nullptr) throw Error("no OpenGL context is current on this thread");
    const int version = epoxy_gl_version();
    const std::string offered = std::to_string(version / 10) + "." + std::to_string(version % 10);
    if (epoxy_is_desktop_gl()) {
        if (version < 45) throw Error("OpenGL 4.5 core is required; the current context offers " + offered);
    } else {
        if (version < 32) {
            throw Error("OpenGL ES 3.2 is required (or desktop OpenGL 4.5 core); the current context offers OpenGL ES " +
                        offered);
        }
        // What ES 3.2 leaves optional and the methods need: float colour targets (every pass
        // writes RGBA32F/R32F) and linear filtering of float textures (the upsampling of reduced
        // passes). Blending into 32-bit float targets (GL_EXT_float_blend) only the methods that do
        // it need: their geometry pass says so (MethodBase::runGeometryPass).
        std::string missing;
        for (const char* ext : {"GL_EXT_color_buffer_float", "GL_OES_texture_float_linear"}) {
            if (!epoxy_has_gl_extension(ext)) missing += std::string(missing.empty() ? "" : ", ") + ext;
        }
        if (!missing.empty()) {
            throw Error("this OpenGL ES " + offered + " context lacks " + missing +
                        " (float colour buffers and filtering), which the methods need");
        }
    }
    GLint maxSsboFrag = 0, maxDrawBuffers = 0;
    glGetIntegerv(GL_MAX_FRAGMENT_SHADER_STORAGE_BLOCKS, &maxSsboFrag);
    glGetIntegerv(GL_MAX_DRAW_BUFFERS, &maxDrawBuffers);
    if (maxSsboFrag < 2) throw Error("the GL context offers fewer than 2 fragment shader storage blocks");
    if (maxDrawBuffers < 4) throw Error("the GL context offers fewer than 4 draw buffers");
}

}  // namespace starnt
