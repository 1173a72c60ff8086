// Headless OpenGL 4.5 core or OpenGL ES 3.2 context through EGL.
//
// Tries EGL_EXT_platform_device first (a GPU, or Mesa's software device), then
// EGL_MESA_platform_surfaceless. No window system is needed: all rendering goes to framebuffer
// objects. When neither platform gives a 4.5 core context, the constructor throws starnt::Error
// naming what was missing. In builds with STARNT_GL_DEBUG (Debug), KHR_debug messages of high
// severity are turned into exceptions carrying the GL message.
#pragma once
#include <memory>
#include <string>

#include "starnt/oit_method.hpp"

namespace starnt {

// Which API a headless context speaks. The methods run the same passes on both (docs/INTEGRATION.md):
// Desktop is OpenGL 4.5 core with GLSL 450, Es is OpenGL ES 3.2 with GLSL ES 3.20, the mobile path.
enum class GlApi { Desktop, Es };
// "gl" or "gles" (the command line's --api); throws starnt::Error for anything else.
GlApi parseGlApi(const std::string& name);
const char* glApiName(GlApi api);

struct GlContextInfo {
    std::string platform;  // "device" or "surfaceless"
    // Why the displays tried before the one in use were refused ("device: eglInitialize failed; "),
    // empty when the first worked: on a GPU machine, why the GPU's device display was not the one.
    std::string refused;
    std::string vendor;
    std::string renderer;
    std::string version;
    GlApi api = GlApi::Desktop;
    bool software = false;  // llvmpipe/softpipe: true
};

class HeadlessGlContext {
public:
    explicit HeadlessGlContext(GlApi api = GlApi::Desktop);
    ~HeadlessGlContext();
    HeadlessGlContext(const HeadlessGlContext&) = delete;
    HeadlessGlContext& operator=(const HeadlessGlContext&) = delete;

    const GlContextInfo& info() const;
    void makeCurrent();

private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
};

// checkGlRequirements() (starnt/oit_method.hpp) checks the current context: HeadlessGlContext
// calls it, and so does createMethod in an engine's own context.
// Sanitizer builds (STARNT_SANITIZE): keeps the loaded GL driver libraries mapped until exit, so
// LeakSanitizer can name the driver's leaks and tests/lsan.supp suppress them; call it before a
// context ends (eglTerminate / glfwTerminate unload the driver). Does nothing in other builds.
void keepGlDriverLoadedAtExit();

}  // namespace starnt
