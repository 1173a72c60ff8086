// What every method needs of the current context (declared in starnt/oit_method.hpp).
#include <epoxy/gl.h>

#include <string>

#include "starnt/error.hpp"
#include "starnt/oit_method.hpp"

namespace starnt {

void checkGlRequirements() {
    // Without a current context GL calls do nothing and glGetString returns null.
    if (glGetString(GL_VERSION) == nullptr) throw Error("no OpenGL context is current on this thread");
    int version = epoxy_gl_version();
    if (version < 45 || epoxy_is_desktop_gl() == false) {
        throw Error("OpenGL 4.5 core is required; the current context offers " +
                    std::to_string(version / 10) + "." + std::to_string(version % 10));
    }
    GLint maxSsboFrag = 0, maxDrawBuffers = 0;
    glGetIntegerv(GL_MAX_FRAGMENT_SHADER_STORAGE_BLOCKS, &maxSsboFrag);
    glGetIntegerv(GL_MAX_DRAW_BUFFERS, &maxDrawBuffers);
    if (maxSsboFrag < 2) throw Error("the GL context offers fewer than 2 fragment shader storage blocks");
    if (maxDrawBuffers < 4) throw Error("the GL context offers fewer than 4 draw buffers");
}

}  // namespace starnt
